// Shared by the mesh readers and writers of src/io: the error they throw and each format's
// reader, which mesh_io.cpp calls by the file's extension.
#pragma once

#include <cmath>
#include <limits>
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
  throw MeshIoError(path, fmt::format(format, std::forward<Args>(args)...));
}

/// `value` as a float: rounded to nearest, ±FLT_MAX for values that round to it, infinite
/// beyond (a plain cast would be undefined there); checkReadMesh reports infinite ones.
inline float toFloat(double value) {
  constexpr float kMax = std::numeric_limits<float>::max();
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  // FLT_MAX plus half its unit in the last place (2^104): values below it round to FLT_MAX.
  constexpr double kRoundsToMax = double{kMax} + 0x1p103;
  if (std::abs(value) > double{kMax}) {
    const float magnitude = std::abs(value) < kRoundsToMax ? kMax : kInfinity;
    return value > 0 ? magnitude : -magnitude;
  }
  return static_cast<float>(value);
}

/// OBJ (mesh_read_obj.cpp).
Mesh readObj(const std::string& text, const std::string& path);

/// PLY, ASCII or binary (mesh_read_ply.cpp).
Mesh readPly(const std::string& data, const std::string& path);

/// glb, through tinygltf (mesh_read_glb.cpp).
Mesh readGlb(const std::string& data, const std::string& path);

/// ASCII or binary OFF (NOFF: with normals), polygons fanned into triangles, through CGAL
/// (mesh_read_cgal.cpp, in the CGAL module pdesurf::cgal).
Mesh readOff(const std::string& data, const std::string& path);

/// Binary or ASCII STL through CGAL, corners at equal positions merged into one vertex (the
/// CGAL module).
Mesh readStl(const std::string& data, const std::string& path);

/// A format's reader: the file's bytes and its path (for messages).
using MeshReader = Mesh (*)(const std::string& data, const std::string& path);

/// The readers of OFF and STL, which the core calls without linking them: null until the CGAL
/// module is linked, whose mesh_read_cgal.cpp sets them as the program starts (its users link
/// with --undefined=pdesurf_cgal_mesh_readers, which keeps that object in the program).
struct CgalMeshReaders {
  MeshReader off = nullptr;
  MeshReader stl = nullptr;
};
CgalMeshReaders& cgalMeshReaders();

}  // namespace pdesurf::detail
