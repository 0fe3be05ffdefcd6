// What the CLI's commands share: exit statuses, timing, and how models and counts are named
// in their output.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model.hpp"

namespace pdesurf::cli {

constexpr int kExitInput = 1;  ///< an input file is invalid or unreadable
constexpr int kExitUsage = 2;  ///< a usage error

/// A well-formed argument that cannot be used with this input (main prints it, exit 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Clock = std::chrono::steady_clock;

/// JSON that keeps its keys in the order written (slice and compare output).
using Json = nlohmann::ordered_json;

/// JSON for a point.
inline Json pointJson(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The model's own name, else its file name.
inline std::string modelName(const std::string& name, const std::string& path) {
  return modelDisplayName(name, path);
}

/// The tessellation's samples per patch side (--resolution, 2 to 4097), shown with its default.
inline CLI::Option* addResolution(CLI::App* cmd, std::uint32_t& resolution,
                                  const std::string& help = "samples per patch side") {
  return cmd->add_option("--resolution", resolution, help)
      ->check(CLI::Range(2u, 4097u))
      ->capture_default_str();
}

/// An option whose value must lie in [lo, hi], shown with its default in --help.
template <class T>
CLI::Option* addInRange(CLI::App* cmd, const std::string& name, T& value, const std::string& help,
                        T lo, T hi) {
  return cmd->add_option(name, value, help)->check(CLI::Range(lo, hi))->capture_default_str();
}

/// The required positional argument "model": the model file a command reads.
inline CLI::Option* addModelFile(CLI::App* cmd, std::string& path,
                                 const std::string& help = "model file (JSON)") {
  return cmd->add_option("model", path, help)->required();
}

/// The required positional argument "mesh": the mesh file a command reads.
inline CLI::Option* addMeshFile(CLI::App* cmd, std::string& path,
                                const std::string& help = "mesh file: .off .obj .ply .stl") {
  return cmd->add_option("mesh", path, help)->required();
}

/// The required -o,--output: the mesh file a command writes.
inline CLI::Option* addMeshOutput(CLI::App* cmd, std::string& path) {
  return cmd->add_option("-o,--output", path, "mesh file to write: .obj .ply .stl .glb .off")
      ->required();
}

/// "1 frame", "2 frames", "1 vertex", "3 vertices".
inline std::string count(std::size_t n, const std::string& noun) { return countText(n, noun); }

/// Reads a mesh with at least one triangle (MeshIoError naming the file otherwise).
inline Mesh readTriangles(const std::string& path) {
  Mesh mesh = readMesh(path);
  if (mesh.triangleCount() == 0) throw MeshIoError(path, "the mesh has no triangles");
  return mesh;
}

/// The planes and loops `slice` and `rebuild` choose from their shared options (--axis, the
/// count, --range, --near, --track), checked before any work; a bad --range or --near throws
/// `UsageError` (the caller's usage error, exit 2) naming the option.
template <class UsageError>
SliceOptions sliceOptionsFrom(const std::string& axis, std::uint32_t planes,
                              const std::vector<double>& range, const std::vector<double>& near,
                              bool track) {
  SliceOptions slice;
  slice.axis = *parseAxis(axis);
  slice.count = planes;
  if (!range.empty()) {
    slice.range = {range[0], range[1]};
    try {
      slicePlanes(slice, 0.0, 1.0);  // the range's own checks, before any work
    } catch (const InvalidArgument& e) {
      throw UsageError(fmt::format("--range: {}", e.what()));
    }
  }
  if (!near.empty()) {
    slice.near = Vec3(near[0], near[1], near[2]);
    if (!slice.near->allFinite())
      throw UsageError(
          fmt::format("--near: {} {} {} is not a finite point", near[0], near[1], near[2]));
  }
  slice.track = track;
  return slice;
}

}  // namespace pdesurf::cli
