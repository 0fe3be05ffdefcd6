// Shared by the mesh readers and writers of src/io: the error they throw and each format's
// reader, which mesh_io.cpp calls by the file's extension.
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "pdesurf/mesh_io.hpp"

namespace pdesurf::detail {

/// Throws MeshIoError "PATH: MESSAGE".
template <typename... Args>
[[noreturn]] void fail(const std::string& path, fmt::format_string<Args...> format,
                       Args&&... args) {
  throw MeshIoError(fmt::format("{}: {}", path, fmt::format(format, std::forward<Args>(args)...)));
}

/// OBJ (mesh_read_obj.cpp).
Mesh readObj(std::string_view text, const std::string& path);

/// PLY, ASCII or binary (mesh_read_ply.cpp).
Mesh readPly(std::string_view data, const std::string& path);

/// glb, through tinygltf (mesh_read_glb.cpp).
Mesh readGlb(const std::string& data, const std::string& path);

/// ASCII or binary OFF (NOFF: with normals), polygons fanned into triangles, through CGAL.
Mesh readOff(const std::string& data, const std::string& path);

/// Binary or ASCII STL through CGAL, corners at equal positions merged into one vertex.
Mesh readStl(const std::string& data, const std::string& path);

}  // namespace pdesurf::detail
