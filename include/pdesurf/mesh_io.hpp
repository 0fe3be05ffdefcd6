// Reading and writing triangle meshes: OBJ, PLY (binary), STL (binary), glTF binary (.glb), OFF.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "pdesurf/mesh.hpp"

namespace pdesurf {

/// A mesh file could not be read or written; what() names the file and the problem.
class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The mesh formats pdesurf writes and reads.
enum class MeshFormat { Obj, Ply, Stl, Glb, Off };

/// The format named by a path's extension (case-insensitive: .obj .ply .stl .glb .off);
/// throws MeshIoError naming the path when the extension is none of these.
MeshFormat meshFormatFromPath(const std::string& path);

/// Writes `mesh` to `path` in the format its extension names. The file appears whole or
/// not at all: the data go to a temporary file beside it, renamed over `path` at the end.
/// OBJ, PLY and glb carry the normals; STL carries per-triangle facet normals.
/// Throws MeshIoError (and leaves no file) on failure.
void writeMesh(const Mesh& mesh, const std::string& path);

/// Writes `text` to `path` whole or not at all, as writeMesh writes a mesh: for the text
/// outputs derived from meshes (slices as JSON). Throws MeshIoError (and leaves no file).
void writeTextFile(const std::string& path, std::string_view text);

/// Reads a mesh written by writeMesh, or an ASCII OFF file (as in CGAL's data sets).
/// Polygons with more than three corners are fanned into triangles. STL files are
/// read as triangle soups, their coincident corners merged so that the result is indexed.
/// Throws MeshIoError naming the file and the problem.
Mesh readMesh(const std::string& path);

}  // namespace pdesurf
