// `pdesurf rebuild MESH --as KIND`: a mesh turned into a model file of the given kind
// (docs/rebuild.md). Each kind is one branch of run() with its own options struct.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pdesurf::cli {

/// `--as vertex-frames`: a layout (a quad mesh, or a U × V grid on a disk) fitted to the mesh.
struct VertexFrameRebuildArgs {
  std::string layoutPath;
  std::vector<std::uint32_t> grid;  ///< U V
  std::uint32_t iterations = 30;
  double tolerance = 1e-3;
  double smoothness = 1e-5;
  std::uint32_t samples = 9;  ///< surface samples per patch side

  void add(CLI::App* cmd);
};

struct RebuildCommand {
  std::string meshPath, outPath, kind;
  std::uint32_t resolution = 17;
  bool quiet = false;
  VertexFrameRebuildArgs vertexFrames;

  /// Registers the subcommand on `app`.
  CLI::App* add(CLI::App& app);
  /// Runs it: 0 on success, 2 for a usage error (after printing it); an invalid mesh or
  /// layout throws, for main's handlers (exit 1). The model file is written whole at the
  /// end or not at all.
  int run() const;

 private:
  int runVertexFrames() const;
};

}  // namespace pdesurf::cli
