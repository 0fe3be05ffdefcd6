// `pdesurf rebuild`: a mesh rebuilt as a model of one of pdesurf's methods, with its distance
// to the mesh and its storage (docs/rebuild.md). The work is the library's rebuild()
// (include/pdesurf/mesh_rebuild.hpp); the command parses the options, writes the files and
// prints the report.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "pdesurf/mesh_rebuild.hpp"
#include "rebuild_auto.hpp"

namespace pdesurf::cli {

/// `--as vertex-frames`: a layout (a quad mesh, a U × V grid on a disk, a tube, or the
/// automatic layout) fitted to the mesh.
struct VertexFrameRebuildArgs {
  std::string layoutPath;
  std::vector<std::uint32_t> grid;  ///< U V
  std::vector<std::uint32_t> tube;  ///< RINGS SECTORS (the part chosen by --axis/--range/--near)
  std::uint32_t iterations = 30;
  double tolerance = 1e-3;
  double smoothness = 1e-5;
  std::uint32_t samples = 9;  ///< surface samples per patch side (0: automatic)
  bool preventFolds = false;  ///< refuse steps that fold more of the surface over
  bool fitShape = false;      ///< then fit a force, a1 and a2 per frame too
  AutoLayoutArgs automatic;   ///< without --layout, --grid and --tube
  /// Weight of the fold-free term (0: off; FitOptions::conformalWeight).
  double conformalWeight = 1e-5;
  /// Weight of the normal-alignment term (RebuildOptions::normalWeight), where given.
  double normalWeight = 0.0;
  CLI::Option* normalWeightOption = nullptr;

  void add(CLI::App* cmd);
};

/// Each kind `--as` names is one branch of run() with its own options.
struct RebuildCommand {
  std::string meshPath, outPath, as, partPath, name, ends = "natural";
  // Cross sections: the slicing (as `pdesurf slice`) and the chain.
  std::string axis = "z";
  std::uint32_t sectionCount = 25, modes = 8, points = 128;
  std::vector<double> range, near;
  bool track = false;
  double a = 1.0;
  std::size_t samples = 100000;
  bool json = false, loft = false, exact = false;
  // Vertex frames.
  VertexFrameRebuildArgs vertexFrames;
  std::uint32_t resolution = 17;  ///< samples per patch side for the final distances
  bool quiet = false;

  /// Registers the subcommand on `app`.
  CLI::App* add(CLI::App& app);
  /// Runs it: 0 on success, 2 for a usage error (after printing it); a mesh that cannot be
  /// rebuilt as asked throws, for main's handlers (exit 1). Nothing is written on failure.
  int run() const;

 private:
  /// The library's options from the command's (a bad --range, --near or --target-rms
  /// throws).
  RebuildOptions options() const;
  int runCrossSections(const RebuildOptions& options) const;
  int runVertexFrames(const RebuildOptions& options) const;
};

}  // namespace pdesurf::cli
