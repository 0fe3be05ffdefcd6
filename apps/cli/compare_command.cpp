// `pdesurf compare`: Metro-style distances between a model's mesh and a mesh file
// (docs/mesh-tools.md).
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "distance_report.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_rebuild.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

namespace {

/// What `pdesurf compare --help` says the command does.
constexpr const char* kCompareHelp =
    "RMS, mean and largest distance between a model (tessellated as by build) and a mesh, "
    "both ways, relative to the mesh's bounding-box diagonal, and how the model's normals "
    "agree with the mesh's (folded area, RMS normal deviation)";

/// `pdesurf compare`: Metro-style distances between a model's mesh and a mesh file.
struct CompareCommand {
  std::string modelPath, meshPath;
  std::uint32_t resolution = 17;
  std::size_t samples = DistanceOptions{}.samples;
  bool json = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("compare", kCompareHelp);
    addModelFile(cmd, modelPath);
    addMeshFile(cmd, meshPath, "reference mesh file: .off .obj .ply .stl");
    addResolution(cmd, resolution, "samples per patch side, as for build");
    cmd->add_option("--samples", samples,
                    "face samples on each mesh, spread by area (every vertex and every "
                    "triangle is sampled too)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
        ->capture_default_str();
    cmd->add_flag("--json", json, "print JSON");
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    const BuiltModel built = buildModel(modelPath, resolution, solveArgs);
    auto t0 = Clock::now();
    const Mesh mesh = readTriangles(meshPath);
    const double readMs = msSince(t0);
    t0 = Clock::now();
    DistanceOptions options;
    options.samples = samples;
    MeshDistance d;
    NormalDeviation normals;
    try {
      d = meshDistance(built.mesh, mesh, options);
      normals = normalDeviation(built.mesh, mesh);
    } catch (const InvalidArgument& e) {
      throw MeshIoError(fmt::format("{} vs {}: {}", modelPath, meshPath, e.what()));
    }
    const double distanceMs = msSince(t0);
    if (json) {
      Json j = {{"model", modelPath},
                {"mesh", meshPath},
                {"resolution", resolution},
                {"diagonal", d.diagonal},
                {"model_to_mesh", oneWayDistanceJson(d.aToB, DistanceFields::All)},
                {"mesh_to_model", oneWayDistanceJson(d.bToA, DistanceFields::All)},
                {"hausdorff", d.hausdorff},
                {"hausdorff_relative", d.hausdorffRelative},
                {"normals", normalDeviationJson(normals)}};
      std::cout << j.dump(2) << '\n';
      return 0;
    }
    fmt::print(
        "{}: {} at resolution {}; {}: {}, bounding-box diagonal {:.6g} "
        "(solve {:.3f} ms, tessellate {:.3f} ms, read {:.1f} ms, distance {:.1f} ms)\n",
        built.name, count(built.mesh.triangleCount(), "triangle"), resolution, meshPath,
        count(mesh.triangleCount(), "triangle"), d.diagonal, built.solveMs, built.tessMs, readMs,
        distanceMs);
    printDistances(d);
    printNormals(normals);
    return 0;
  }
};

}  // namespace

Registered addCompareCommand(CLI::App& app) { return registerCommand<CompareCommand>(app); }

}  // namespace pdesurf::cli
