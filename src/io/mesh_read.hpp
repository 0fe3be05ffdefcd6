// Shared by the mesh readers and writers of src/io (mesh_io.cpp, mesh_read_cgal.cpp).
#pragma once

#include <string>
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

/// ASCII or binary OFF (NOFF: with normals), polygons fanned into triangles, through CGAL.
Mesh readOff(const std::string& data, const std::string& path);

/// Binary or ASCII STL through CGAL, corners at equal positions merged into one vertex.
Mesh readStl(const std::string& data, const std::string& path);

}  // namespace pdesurf::detail
