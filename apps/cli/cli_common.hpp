// What the CLI's commands share: exit statuses, timing, and how models and counts are named
// in their output.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include <fmt/format.h>

#include "pdesurf/mesh_io.hpp"

namespace pdesurf::cli {

constexpr int kExitInput = 1;  ///< an input file is invalid or unreadable
constexpr int kExitUsage = 2;  ///< a usage error

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The model's own name, else its file name.
inline std::string modelName(const std::string& name, const std::string& path) {
  if (!name.empty()) return name;
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// "1 frame", "2 frames", "1 vertex", "3 vertices".
inline std::string count(std::size_t n, const std::string& noun) {
  if (n == 1) return "1 " + noun;
  if (noun == "vertex") return fmt::format("{} vertices", n);
  return fmt::format("{} {}{}", n, noun, noun.ends_with("ch") ? "es" : "s");
}

/// Reads a mesh with at least one triangle (MeshIoError naming the file otherwise).
inline Mesh readTriangles(const std::string& path) {
  Mesh mesh = readMesh(path);
  if (mesh.triangleCount() == 0) throw MeshIoError(path + ": the mesh has no triangles");
  return mesh;
}

}  // namespace pdesurf::cli
