#include "rebuild_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "distance_report.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf::cli {

namespace {

/// The kinds `--as` takes; each is one branch of RebuildCommand::run().
const std::vector<std::string> kRebuildKinds = {"vertex-frames"};

/// A well-formed argument that cannot be used (exit 2).
struct RebuildUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads a mesh with at least one triangle (MeshIoError naming the file otherwise).
Mesh readTarget(const std::string& path) {
  Mesh mesh = readMesh(path);
  if (mesh.triangleCount() == 0) throw MeshIoError(path + ": the mesh has no triangles");
  return mesh;
}

/// A bar on standard error, redrawn in place, when it is a terminal.
class ProgressBar {
 public:
  ProgressBar(std::uint32_t total, bool enabled)
      : total_(total), enabled_(enabled && ::isatty(STDERR_FILENO) == 1) {}
  ~ProgressBar() {
    if (drawn_) fmt::print(stderr, "\r{:{}}\r", "", kWidth + 40);
  }
  void update(std::uint32_t done, double rms) {
    if (!enabled_) return;
    const auto filled = static_cast<int>(kWidth * std::min(done, total_) / std::max(total_, 1u));
    fmt::print(stderr, "\rfitting [{:#<{}}{:<{}}] {}/{}  RMS {}", "", filled, "", kWidth - filled,
               done, total_, percent(rms));
    std::fflush(stderr);
    drawn_ = true;
  }

 private:
  static constexpr int kWidth = 30;
  std::uint32_t total_;
  bool enabled_, drawn_ = false;
};

}  // namespace

void VertexFrameRebuildArgs::add(CLI::App* cmd) {
  cmd->add_option("--layout", layoutPath,
                  "vertex-frames: a quad mesh (OBJ, OFF, PLY) whose quads become the frames");
  cmd->add_option("--grid", grid,
                  "vertex-frames: U V, a grid of U × V frames laid on a mesh with one boundary "
                  "loop through its parameterisation onto a square")
      ->expected(2)
      ->check(CLI::Range(1u, 1000u));
  cmd->add_option("--iterations", iterations, "vertex-frames: most fitting iterations")
      ->check(CLI::Range(0u, 100000u))
      ->capture_default_str();
  cmd->add_option("--tolerance", tolerance,
                  "vertex-frames: stop when an iteration lowers the RMS by less than this "
                  "fraction of it")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--smoothness", smoothness,
                  "vertex-frames: weight of the Laplacian of the vertex positions against the "
                  "mean squared distances")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--fit-samples", samples, "vertex-frames: surface samples per patch side")
      ->check(CLI::Range(3u, 65u))
      ->capture_default_str();
}

CLI::App* RebuildCommand::add(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "rebuild",
      "Turn a mesh into a model file of the kind --as names (the distances between the model "
      "and the mesh are printed as by compare)");
  cmd->add_option("mesh", meshPath, "mesh file: .off .obj .ply .stl")->required();
  cmd->add_option("--as", kind, "the kind of model to build")
      ->required()
      ->check(CLI::IsMember(kRebuildKinds));
  cmd->add_option("-o,--output", outPath, "model file to write (JSON), whole or not at all")
      ->required();
  cmd->add_option("--resolution", resolution,
                  "samples per patch side for the distances printed at the end, as for compare")
      ->check(CLI::Range(2u, 4097u))
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", quiet, "print nothing on success");
  vertexFrames.add(cmd);
  return cmd;
}

int RebuildCommand::run() const {
  try {
    if (kind == "vertex-frames") return runVertexFrames();
    throw RebuildUsageError(fmt::format("--as {}: not a kind rebuild makes", kind));
  } catch (const RebuildUsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  }
}

int RebuildCommand::runVertexFrames() const {
  const VertexFrameRebuildArgs& args = vertexFrames;
  if (args.layoutPath.empty() == args.grid.empty())
    throw RebuildUsageError("--as vertex-frames: give one of --layout QUADS and --grid U V");

  auto t0 = Clock::now();
  const Mesh mesh = readTarget(meshPath);
  VertexFrameModel layout;
  if (!args.layoutPath.empty()) {
    layout = quadLayout(readPolygonMesh(args.layoutPath), args.layoutPath);
  } else {
    layout = gridLayout(mesh, {args.grid[0], args.grid[1]}, meshPath);
  }
  layout.name = std::filesystem::path(meshPath).stem().string() + " (vertex frames)";
  const double layoutMs = msSince(t0);

  FitOptions options;
  options.maxIterations = args.iterations;
  options.tolerance = args.tolerance;
  options.smoothness = args.smoothness;
  options.samplesPerSide = args.samples;
  ProgressBar bar(args.iterations, !quiet);
  options.onIteration = [&](const FitIteration& it) {
    bar.update(it.iteration, it.measure.rms());
    if (quiet) return;
    const FitMeasure& m = it.measure;
    fmt::print(
        "iteration {:>3}{}: RMS {}  surface -> mesh RMS {} mean {} max {}  mesh -> surface RMS "
        "{} mean {} max {}\n",
        it.iteration, it.iteration == 0 ? " (layout)" : fmt::format(" (step {:g})", it.step),
        percent(m.rms()), percent(m.rmsToMesh), percent(m.meanToMesh), percent(m.maxToMesh),
        percent(m.rmsToModel), percent(m.meanToModel), percent(m.maxToModel));
  };
  t0 = Clock::now();
  FitResult fitted;
  try {
    fitted = fitVertexFrames(layout, mesh, options);
  } catch (const std::invalid_argument& e) {
    throw MeshIoError(fmt::format("{}: {}", meshPath, e.what()));
  }
  const double fitMs = msSince(t0);

  writeTextFile(outPath, serializeVertexFrameModel(fitted.model));
  if (quiet) return 0;
  const VertexFrameSurface surface = solve(fitted.model);
  const MeshDistance d = meshDistance(tessellate(surface, {resolution}), mesh);
  fmt::print("{}: {}\n", outPath, fitted.stopReason);
  fmt::print("{}: {}, {}, {} -> {} (layout {:.1f} ms, fit {:.1f} ms)\n", layout.name,
             count(fitted.model.frames.size(), "frame"),
             count(fitted.model.vertices.size(), "vertex"),
             count(fitted.iterations.size() - 1, "iteration"), outPath, layoutMs, fitMs);
  fmt::print("{} at resolution {}; {}: {}, bounding-box diagonal {:.6g}\n", outPath, resolution,
             meshPath, count(mesh.triangleCount(), "triangle"), d.diagonal);
  printDistances(d);
  fmt::print("storage        {} bytes (numbers to six significant digits)\n",
             storageBytes(fitted.model));
  return 0;
}

}  // namespace pdesurf::cli
