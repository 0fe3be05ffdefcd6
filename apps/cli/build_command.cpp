// `pdesurf build`: solve a model and write its mesh.
#include <cstdint>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/mesh_io.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf build`: solve a model and write its mesh.
struct BuildCommand {
  std::string modelPath, outPath;
  std::uint32_t resolution = 17;
  bool quiet = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("build",
                                       "Solve a model and write its mesh (OBJ, PLY, STL, "
                                       "glb or OFF, chosen by the output's extension)");
    addModelFile(cmd, modelPath);
    addMeshOutput(cmd, outPath);
    addResolution(cmd, resolution);
    cmd->add_flag("-q,--quiet", quiet, "print nothing on success");
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    checkMeshExtension(outPath);
    const BuiltModel built = buildModel(modelPath, resolution, solveArgs);
    const Mesh& mesh = built.mesh;
    auto t0 = Clock::now();
    writeMesh(mesh, outPath);
    const double writeMs = msSince(t0);
    if (!quiet)
      fmt::print(
          "{}: {}, {}, {}, {} -> {} "
          "(solve {:.3f} ms, tessellate {:.3f} ms, write {:.1f} ms)\n",
          built.name, built.report.summary, count(mesh.vertexCount(), "vertex"),
          count(mesh.triangleCount(), "triangle"), built.report.quality, outPath, built.solveMs,
          built.tessMs, writeMs);
    return 0;
  }
};

}  // namespace

Registered addBuildCommand(CLI::App& app) { return registerCommand<BuildCommand>(app); }

}  // namespace pdesurf::cli
