// Mesh files written: OBJ, PLY, STL, glb and OFF, each through the project's one atomic-file
// writer (src/io/atomic_file.hpp), after checking that the mesh's buffers are consistent.
#include "pdesurf/mesh_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/compile.h>
#include <fmt/format.h>
#include <tiny_gltf.h>

#include "io/atomic_file.hpp"
#include "io/mesh_read.hpp"
#include "io/mesh_text.hpp"

namespace pdesurf {
namespace {

using detail::fail;
using detail::kBigEndianHost;
using detail::swapBytesIf;

/// Throws unless the mesh's buffers are consistent, so that every writer may trust them.
void validateForWriting(const Mesh& mesh, const std::string& path) {
  if (mesh.positions.size() % 3 != 0)
    fail(path, "invalid mesh: {} position values is not a multiple of 3", mesh.positions.size());
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    fail(path, "invalid mesh: {} normal values for {} position values", mesh.normals.size(),
         mesh.positions.size());
  if (mesh.indices.size() % 3 != 0)
    fail(path, "invalid mesh: {} indices is not a multiple of 3", mesh.indices.size());
  if (mesh.vertexCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "invalid mesh: {} vertices do not fit 32-bit indices", mesh.vertexCount());
  // Every format stores single-precision numbers; an infinite or NaN one would make a file
  // other programs reject or misdraw (a surface beyond ±3.4e38 overflows float).
  for (const auto* buffer : {&mesh.positions, &mesh.normals})
    for (std::size_t i = 0; i < buffer->size(); ++i)
      if (!std::isfinite((*buffer)[i]))
        fail(path,
             "invalid mesh: vertex {} has a non-finite {} ({}): coordinates must fit single "
             "precision (|x| < 3.4e38)",
             i / 3, buffer == &mesh.positions ? "position" : "normal", (*buffer)[i]);
  const std::size_t vertexCount = mesh.vertexCount();
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= vertexCount)
      fail(path, "invalid mesh: triangle {} refers to vertex {} but the mesh has {} vertices",
           i / 3, mesh.indices[i], vertexCount);
  }
}

using detail::AtomicFileWriter;

/// Appends `value` to `file` in little-endian byte order (call checkpoint() after each record).
template <typename T>
void appendLittle(AtomicFileWriter& file, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  value = swapBytesIf(value, kBigEndianHost);
  file.append(&value, sizeof(T));
}

void writeObj(const Mesh& mesh, AtomicFileWriter& file) {
  const auto& p = mesh.positions;
  const auto& n = mesh.normals;
  fmt::format_to(file.out(), "# pdesurf mesh: {} vertices, {} triangles\n", mesh.vertexCount(),
                 mesh.triangleCount());
  for (std::size_t i = 0; i < p.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("v {} {} {}\n"), p[i], p[i + 1], p[i + 2]);
    file.checkpoint();
  }
  for (std::size_t i = 0; i < n.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("vn {} {} {}\n"), n[i], n[i + 1], n[i + 2]);
    file.checkpoint();
  }
  const auto& t = mesh.indices;
  for (std::size_t i = 0; i < t.size(); i += 3) {
    const std::uint64_t a = t[i] + std::uint64_t{1}, b = t[i + 1] + std::uint64_t{1},
                        c = t[i + 2] + std::uint64_t{1};
    if (n.empty())
      fmt::format_to(file.out(), FMT_COMPILE("f {} {} {}\n"), a, b, c);
    else
      fmt::format_to(file.out(), FMT_COMPILE("f {}//{} {}//{} {}//{}\n"), a, a, b, b, c, c);
    file.checkpoint();
  }
}

void writePly(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  if (mesh.vertexCount() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    fail(path, "{} vertices are too many for PLY's int indices", mesh.vertexCount());
  const bool hasNormals = !mesh.normals.empty();
  fmt::format_to(file.out(),
                 "ply\nformat binary_little_endian 1.0\ncomment pdesurf\nelement vertex {}\n"
                 "property float x\nproperty float y\nproperty float z\n",
                 mesh.vertexCount());
  if (hasNormals)
    fmt::format_to(file.out(), "property float nx\nproperty float ny\nproperty float nz\n");
  fmt::format_to(file.out(),
                 "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                 mesh.triangleCount());
  for (std::size_t i = 0; i < mesh.positions.size(); i += 3) {
    for (std::size_t k = 0; k < 3; ++k) appendLittle(file, mesh.positions[i + k]);
    if (hasNormals)
      for (std::size_t k = 0; k < 3; ++k) appendLittle(file, mesh.normals[i + k]);
    file.checkpoint();
  }
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    appendLittle(file, std::uint8_t{3});
    for (std::size_t k = 0; k < 3; ++k)
      appendLittle(file, static_cast<std::int32_t>(mesh.indices[i + k]));
    file.checkpoint();
  }
}

void writeStl(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  if (mesh.triangleCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} triangles are too many for STL", mesh.triangleCount());
  std::array<char, 80> header{};
  constexpr std::string_view kHeader = "pdesurf binary STL";
  std::copy(kHeader.begin(), kHeader.end(), header.begin());
  file.append(header.data(), header.size());
  appendLittle(file, static_cast<std::uint32_t>(mesh.triangleCount()));
  const float* p = mesh.positions.data();
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const float* a = p + 3 * std::size_t{mesh.indices[i]};
    const float* b = p + 3 * std::size_t{mesh.indices[i + 1]};
    const float* c = p + 3 * std::size_t{mesh.indices[i + 2]};
    const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
    const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
    double normal[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0]};
    const double length =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (double& component : normal) component = length > 0 ? component / length : 0.0;
    for (double component : normal) appendLittle(file, static_cast<float>(component));
    for (const float* corner : {a, b, c})
      for (int k = 0; k < 3; ++k) appendLittle(file, corner[k]);
    appendLittle(file, std::uint16_t{0});
    file.checkpoint();
  }
}

void writeOff(const Mesh& mesh, AtomicFileWriter& file) {
  fmt::format_to(file.out(), "OFF\n{} {} 0\n", mesh.vertexCount(), mesh.triangleCount());
  const auto& p = mesh.positions;
  for (std::size_t i = 0; i < p.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("{} {} {}\n"), p[i], p[i + 1], p[i + 2]);
    file.checkpoint();
  }
  const auto& t = mesh.indices;
  for (std::size_t i = 0; i < t.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("3 {} {} {}\n"), t[i], t[i + 1], t[i + 2]);
    file.checkpoint();
  }
}

/// Appends `values` to a glTF buffer in little-endian order; returns the byte offset.
template <typename T>
std::size_t appendToBuffer(std::vector<unsigned char>& buffer, const MeshBuffer<T>& values) {
  const std::size_t offset = buffer.size();
  buffer.resize(offset + values.size() * sizeof(T));
  unsigned char* out = buffer.data() + offset;
  for (const T& value : values) {
    const T little = swapBytesIf(value, kBigEndianHost);
    std::memcpy(out, &little, sizeof(T));
    out += sizeof(T);
  }
  return offset;
}

/// Adds a buffer view over buffer 0 and a tightly packed accessor over it; returns the accessor.
int addAccessor(tinygltf::Model& model, std::size_t byteOffset, std::size_t byteLength, int target,
                int componentType, int type, std::size_t count) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = byteOffset;
  view.byteLength = byteLength;
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

void writeGlb(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "pdesurf";
  tinygltf::Node node;
  node.name = "pdesurf";  // tinygltf writes a node without properties as null, not {}
  // glTF forbids empty accessors: a mesh without vertices is an empty node, one without
  // triangles a point primitive.
  if (mesh.vertexCount() > 0) {
    tinygltf::Buffer buffer;
    tinygltf::Primitive primitive;
    const std::size_t n = mesh.vertexCount();
    const std::size_t vec3Bytes = n * 3 * sizeof(float);
    const int position = addAccessor(model, appendToBuffer(buffer.data, mesh.positions), vec3Bytes,
                                     TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                     TINYGLTF_TYPE_VEC3, n);
    tinygltf::Accessor& positions = model.accessors[static_cast<std::size_t>(position)];
    positions.minValues.assign(3, std::numeric_limits<double>::infinity());
    positions.maxValues.assign(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      positions.minValues[i % 3] = std::min<double>(positions.minValues[i % 3], mesh.positions[i]);
      positions.maxValues[i % 3] = std::max<double>(positions.maxValues[i % 3], mesh.positions[i]);
    }
    primitive.attributes["POSITION"] = position;
    if (!mesh.normals.empty())
      primitive.attributes["NORMAL"] = addAccessor(
          model, appendToBuffer(buffer.data, mesh.normals), vec3Bytes, TINYGLTF_TARGET_ARRAY_BUFFER,
          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    if (mesh.indices.empty()) {
      primitive.mode = TINYGLTF_MODE_POINTS;
    } else {
      primitive.mode = TINYGLTF_MODE_TRIANGLES;
      primitive.indices = addAccessor(
          model, appendToBuffer(buffer.data, mesh.indices),
          mesh.indices.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, mesh.indices.size());
    }
    // The glb container counts its bytes in 32 bits; leave room for the JSON chunk.
    if (buffer.data.size() > std::numeric_limits<std::uint32_t>::max() - (std::size_t{1} << 24))
      fail(path, "{} bytes of mesh data are too many for glb", buffer.data.size());
    model.buffers.push_back(std::move(buffer));
    tinygltf::Mesh gltfMesh;
    gltfMesh.primitives.push_back(std::move(primitive));
    model.meshes.push_back(std::move(gltfMesh));
    node.mesh = 0;
  }
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  std::ostringstream stream;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false, /*writeBinary=*/true) ||
      !stream)
    fail(path, "tinygltf could not serialize the mesh");
  const std::string bytes = std::move(stream).str();
  file.append(bytes.data(), bytes.size());
}

}  // namespace

void writeMesh(const Mesh& mesh, const std::string& path) {
  const MeshFormat format = meshFormatFromPath(path);
  validateForWriting(mesh, path);
  try {
    AtomicFileWriter file(path);
    switch (format) {
      case MeshFormat::Obj:
        writeObj(mesh, file);
        break;
      case MeshFormat::Ply:
        writePly(mesh, file, path);
        break;
      case MeshFormat::Stl:
        writeStl(mesh, file, path);
        break;
      case MeshFormat::Glb:
        writeGlb(mesh, file, path);
        break;
      case MeshFormat::Off:
        writeOff(mesh, file);
        break;
    }
    file.commit();
  } catch (const MeshIoError&) {
    throw;
  } catch (const FileError& e) {  // the write itself: a MeshIoError like every other failure
    throw MeshIoError(e.file(), e.message());
  }
}

}  // namespace pdesurf
