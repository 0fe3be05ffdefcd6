// What the CLI's commands share: exit statuses, timing, and how models and counts are named
// in their output.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include <fmt/format.h>

#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model.hpp"

namespace pdesurf::cli {

constexpr int kExitInput = 1;  ///< an input file is invalid or unreadable
constexpr int kExitUsage = 2;  ///< a usage error

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The model's own name, else its file name.
inline std::string modelName(const std::string& name, const std::string& path) {
  return modelDisplayName(name, path);
}

/// "1 frame", "2 frames", "1 vertex", "3 vertices".
inline std::string count(std::size_t n, const std::string& noun) { return countText(n, noun); }

/// Reads a mesh with at least one triangle (MeshIoError naming the file otherwise).
inline Mesh readTriangles(const std::string& path) {
  Mesh mesh = readMesh(path);
  if (mesh.triangleCount() == 0) throw MeshIoError(path + ": the mesh has no triangles");
  return mesh;
}

}  // namespace pdesurf::cli
