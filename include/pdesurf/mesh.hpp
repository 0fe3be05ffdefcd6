// Triangle meshes as flat buffers, ready for GL, glTF and mesh files (cf. Manifold's MeshGL).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pdesurf {

/// A triangle mesh. Vertex k has position (positions[3k], positions[3k+1], positions[3k+2])
/// and unit normal likewise in `normals` (empty when the mesh has no normals). Triangle t
/// has corners indices[3t..3t+2], counter-clockwise seen from the side its normals face.
/// `patchIds[t]` names the patch (frame) triangle t came from (empty when unknown).
struct Mesh {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> patchIds;

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace pdesurf
