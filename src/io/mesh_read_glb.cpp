// glb meshes through tinygltf: every triangle primitive of every mesh, positions and normals.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <tiny_gltf.h>

#include "io/mesh_read.hpp"
#include "io/mesh_text.hpp"

namespace pdesurf::detail {

namespace {

/// Where accessor `index`'s elements start in their buffer, and their stride.
struct AccessorData {
  const unsigned char* data;
  std::size_t stride;
  std::size_t count;
  int componentType;
};

AccessorData accessorData(const tinygltf::Model& model, int index, const std::string& path,
                          const std::string& what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    fail(path, "{}: no accessor {}", what, index);
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.sparse.isSparse) fail(path, "{}: sparse accessors are not supported", what);
  if (accessor.bufferView < 0 ||
      static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size())
    fail(path, "{}: accessor {} has no valid buffer view", what, index);
  const tinygltf::BufferView& view =
      model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail(path, "{}: buffer view {} has no valid buffer", what, accessor.bufferView);
  const std::vector<unsigned char>& buffer =
      model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const int stride = accessor.ByteStride(view);
  const int componentSize =
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  const int components =
      tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  if (stride <= 0 || componentSize <= 0 || components <= 0)
    fail(path, "{}: accessor {} has an invalid type or stride", what, index);
  const std::size_t elementSize = static_cast<std::size_t>(componentSize * components);
  const std::size_t needed = accessor.count == 0
                                 ? 0
                                 : accessor.byteOffset +
                                       static_cast<std::size_t>(stride) * (accessor.count - 1) +
                                       elementSize;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset ||
      needed > view.byteLength)
    fail(path, "{}: accessor {} reaches beyond its buffer", what, index);
  return {buffer.data() + view.byteOffset + accessor.byteOffset, static_cast<std::size_t>(stride),
          accessor.count, accessor.componentType};
}

/// Appends the float VEC3 accessor `index` to `out`.
std::size_t appendVec3(const tinygltf::Model& model, int index, const std::string& path,
                       const std::string& what, MeshBuffer<float>& out) {
  const AccessorData data = accessorData(model, index, path, what);
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
      accessor.type != TINYGLTF_TYPE_VEC3)
    fail(path, "{}: expected float VEC3 values", what);
  for (std::size_t i = 0; i < data.count; ++i) {
    std::array<float, 3> value;
    std::memcpy(value.data(), data.data + i * data.stride, sizeof(value));
    for (float component : value) out.push_back(swapBytesIf(component, kBigEndianHost));
  }
  return data.count;
}

template <typename T>
std::uint32_t loadIndex(const unsigned char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return swapBytesIf(value, kBigEndianHost);
}

}  // namespace

Mesh readGlb(const std::string& data, const std::string& path) {
  if (data.size() > std::numeric_limits<unsigned int>::max())
    fail(path, "{} bytes is too large for tinygltf", data.size());
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const std::size_t slash = path.rfind('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  if (!loader.LoadBinaryFromMemory(&model, &error, &warning,
                                   reinterpret_cast<const unsigned char*>(data.data()),
                                   static_cast<unsigned int>(data.size()), directory)) {
    while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back())))
      error.pop_back();
    fail(path, "{}", error.empty() ? std::string("not a valid glb file") : error);
  }
  Mesh mesh;
  bool allNormals = true;
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      const std::string what = fmt::format("mesh {} primitive {}", m, p);
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != TINYGLTF_MODE_POINTS)
        fail(path, "{}: mode {} is not triangles", what, primitive.mode);
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) fail(path, "{} has no POSITION", what);
      const std::size_t base = mesh.vertexCount();
      const std::size_t count = appendVec3(model, position->second, path, what, mesh.positions);
      const auto normal = primitive.attributes.find("NORMAL");
      allNormals = allNormals && normal != primitive.attributes.end() &&
                   appendVec3(model, normal->second, path, what, mesh.normals) == count;
      if (primitive.mode == TINYGLTF_MODE_POINTS) continue;
      if (primitive.indices < 0) {  // not indexed: consecutive corners
        if (count % 3 != 0) fail(path, "{}: {} corners do not make triangles", what, count);
        for (std::size_t i = 0; i < count; ++i)
          mesh.indices.push_back(static_cast<std::uint32_t>(base + i));
        continue;
      }
      const AccessorData indices = accessorData(model, primitive.indices, path, what);
      if (indices.count % 3 != 0 ||
          model.accessors[static_cast<std::size_t>(primitive.indices)].type != TINYGLTF_TYPE_SCALAR)
        fail(path, "{}: the indices are not triangles", what);
      for (std::size_t i = 0; i < indices.count; ++i) {
        const unsigned char* at = indices.data + i * indices.stride;
        std::uint32_t index = 0;
        switch (indices.componentType) {
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            index = *at;
            break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            index = loadIndex<std::uint16_t>(at);
            break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            index = loadIndex<std::uint32_t>(at);
            break;
          default:
            fail(path, "{}: indices must be unsigned integers", what);
        }
        if (index >= count)
          fail(path, "{}: triangle {} refers to vertex {} but the primitive has {} vertices", what,
               i / 3, index, count);
        mesh.indices.push_back(static_cast<std::uint32_t>(base + index));
      }
    }
  }
  if (mesh.vertexCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} vertices do not fit 32-bit indices", mesh.vertexCount());
  if (!allNormals) mesh.normals.clear();
  return mesh;
}

}  // namespace pdesurf::detail
