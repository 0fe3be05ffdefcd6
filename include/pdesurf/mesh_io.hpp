// Reading and writing triangle meshes: OBJ, PLY (binary), STL (binary), glTF binary (.glb), OFF.
#pragma once

#include <string>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf {

/// The mesh formats pdesurf writes and reads.
enum class MeshFormat { Obj, Ply, Stl, Glb, Off };

/// The format named by a path's extension (case-insensitive: .obj .ply .stl .glb .off);
/// throws MeshIoError naming the path when the extension is none of these.
MeshFormat meshFormatFromPath(const std::string& path);

/// Writes `mesh` to `path` in the format its extension names. The file appears whole or
/// not at all, with the permissions of writeFileAtomically (pdesurf/atomic_file.hpp).
/// OBJ, PLY and glb carry the normals; STL carries per-triangle facet normals.
/// Throws MeshIoError (and leaves no file) on failure.
void writeMesh(const Mesh& mesh, const std::string& path);

/// Reads a mesh written by writeMesh, or an OFF file (as in CGAL's data sets). OFF and STL
/// are read by CGAL's readers, glb by tinygltf, OBJ and PLY by pdesurf's own (they keep the
/// normals). Polygons with more than three corners are fanned into triangles. STL files are
/// read as triangle soups, their coincident corners merged so that the result is indexed.
/// Every result is checked: indices in range, finite positions, at most 2^32 - 1 vertices.
/// Throws MeshIoError naming the file and the problem.
Mesh readMesh(const std::string& path);

}  // namespace pdesurf
