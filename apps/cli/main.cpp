// pdesurf: the command line. Thin: parse arguments, call the library, report.
// Exit codes: 0 success, 1 bad input (model or mesh file), 2 usage error.
#include <csignal>
#include <cstdio>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "distance_report.hpp"
#include "export_command.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/coons.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "rebuild_command.hpp"
#include "server.hpp"
#include "spectral_commands.hpp"

namespace {

using namespace pdesurf;
using cli::Clock;
using cli::count;
using cli::kExitInput;
using cli::kExitUsage;
using cli::msSince;
using cli::readTriangles;

/// An argument that is well-formed but unusable with this model (exit 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SolveArgs {
  std::string solver = "global";
  std::uint32_t seedFrame = 0;

  void add(CLI::App* cmd) {
    cmd->add_option("--solver", solver,
                    "global: each strip minimises its patches' summed PDE "
                    "residual; local: the seed's patch generation rule")
        ->check(CLI::IsMember({"global", "local"}))
        ->capture_default_str();
    cmd->add_option("--seed-frame", seedFrame, "local solver: the frame generation starts from")
        ->capture_default_str();
  }
  /// The options for `model`; a seed frame it does not have is a usage error.
  SolveOptions options(const AnyModel& model) const {
    const SolveOptions options{solver == "local" ? Solver::Local : Solver::Global, seedFrame};
    try {
      checkSolveOptions(model, options);
    } catch (const std::out_of_range& e) {
      throw UsageError(fmt::format("--seed-frame {}: {}", seedFrame, e.what()));
    }
    return options;
  }
};

void printNotes(const SolvedModel& solved) {
  for (const std::string& note : solved.notes())
    fmt::print(stderr, "{}: note: {}\n", solved.source(), note);
}

/// An output path pdesurf cannot write (by its extension) is a usage error, found before
/// any work.
void checkMeshExtension(const std::string& outPath) {
  try {
    meshFormatFromPath(outPath);
  } catch (const MeshIoError& e) {
    throw UsageError(e.what());
  }
}

/// Solves a model of any type with the command's solver options (vertex frames), printing
/// the solver's notes.
SolvedModel solveWith(AnyModel any, const std::string& modelPath, const SolveArgs& args) {
  const SolveOptions options = args.options(any);
  SolvedModel solved = solveModel(std::move(any), modelPath, options);
  printNotes(solved);
  return solved;
}

SolvedModel loadSolved(const std::string& modelPath, const SolveArgs& args) {
  return solveWith(loadModel(modelPath), modelPath, args);
}

/// A model of any type solved and tessellated: what `build` writes and `compare` measures.
struct BuiltModel {
  std::string name;
  ModelReport report;
  Mesh mesh;
  double solveMs = 0.0, tessMs = 0.0;
};

BuiltModel buildModel(const std::string& modelPath, std::uint32_t resolution,
                      const SolveArgs& args) {
  BuiltModel built;
  AnyModel any = loadModel(modelPath);
  auto t0 = Clock::now();
  const SolvedModel solved = solveWith(std::move(any), modelPath, args);
  built.solveMs = msSince(t0);
  built.name = solved.displayName();
  t0 = Clock::now();
  built.mesh = tessellate(solved, {resolution});
  built.tessMs = msSince(t0);
  built.report = report(solved);
  return built;
}

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
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_option("-o,--output", outPath, "mesh file to write: .obj .ply .stl .glb .off")
        ->required();
    cmd->add_option("--resolution", resolution, "samples per patch side")
        ->check(CLI::Range(2u, 4097u))
        ->capture_default_str();
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

/// `pdesurf sample`: every patch on a grid, as JSON.
struct SampleCommand {
  std::string modelPath;
  std::uint32_t grid = 0;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "sample",
        "Print each patch sampled on a grid as JSON: points[j*N+i] = S(i/(N-1), j/(N-1))");
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_option("--grid", grid, "samples per patch side (N)")
        ->required()
        ->check(CLI::Range(2u, 4097u));
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    // Keys in the order written; doubles in their shortest round-trip form.
    nlohmann::ordered_json patches = nlohmann::ordered_json::array();
    for (const PatchSamples& p : sample(loadSolved(modelPath, solveArgs), grid)) {
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const Vec3& q : p.points) points.push_back({q.x(), q.y(), q.z()});
      nlohmann::ordered_json patch = {{p.label, p.index}, {"grid", p.grid}};
      if (p.u) patch["u"] = {p.u->first, p.u->second};
      if (p.origin) patch["origin"] = {(*p.origin)[0], (*p.origin)[1]};
      patch["points"] = std::move(points);
      patches.push_back(std::move(patch));
    }
    std::cout << nlohmann::ordered_json{{"patches", std::move(patches)}}.dump() << '\n';
    return 0;
  }
};

/// `pdesurf info`: counts, quality figures, bounding box, storage.
struct InfoCommand {
  std::string modelPath;
  bool json = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "info", "Counts, the largest C0 gap on shared edges, bounding box and storage size");
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_flag("--json", json, "print JSON");
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    std::cout << infoText(loadSolved(modelPath, solveArgs), json);
    return 0;
  }
};

/// `pdesurf studio`: the studio server until Ctrl-C.
struct StudioCommand {
  std::string modelPath;
  pdesurf::studio::StudioOptions options;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "studio", "Serve a model for interactive editing in a browser (until Ctrl-C)");
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_option("--root", options.root,
                    "folder the studio may open and write in (default: the model's folder)");
    cmd->add_option("--port", options.port, "port to listen on (0: any free port)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    cmd->add_option("--host", options.host, "address to listen on")->capture_default_str();
    cmd->add_flag_callback(
        "--no-token", [this] { options.requireToken = false; },
        "UNSAFE, for tests only: serve the API without the per-launch token of the printed URL "
        "(any program of any local user may then read and change the models)");
    return cmd;
  }

  int run() const { return pdesurf::studio::runStudio(modelPath, options); }
};

/// `pdesurf fit`: Fourier fits of the closed curves of a curves file.
struct FitCommand {
  std::string curvesPath;
  std::vector<std::uint32_t> terms;
  bool uniform = false, json = false;

  static constexpr const char* kHelp =
      "Fit each closed curve of a curves file (a cross-sections model or {\"curves\": [...]}) by "
      "a Fourier series; print the largest and mean distance of the points per number of terms";

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("fit", kHelp);
    cmd->add_option("curves", curvesPath, "curves file (JSON)")->required();
    cmd->add_option("--terms", terms, "numbers of Fourier terms N (one or more)")
        ->required()
        ->check(CLI::Range(0u, 512u));
    cmd->add_flag("--uniform", uniform,
                  "give points uniform v (default: chord length, as the seeds)");
    cmd->add_flag("--json", json, "print JSON");
    return cmd;
  }

  int run() const {
    std::cout << cli::fitReport(curvesPath, terms, !uniform, json);
    return 0;
  }
};

/// `pdesurf spine`: A0(u) of a spectral or cross-sections model.
struct SpineCommand {
  std::string modelPath;
  std::uint32_t count = 33;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "spine", "Print the spine A0(u) of a spectral or cross-sections model as JSON polylines");
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_option("--count", count, "points per patch")
        ->check(CLI::Range(2u, 100000u))
        ->capture_default_str();
    return cmd;
  }

  int run() const {
    const SolvedModel solved = loadAndSolve(modelPath);
    if (!solved.spectral())
      throw UsageError(fmt::format(
          "{}: only spectral and cross-sections models have a spine (this is a {} model)",
          modelPath, solved.type()));
    std::cout << cli::spineJson(*solved.spectral(), count);
    return 0;
  }
};

/// JSON that keeps its keys in the order written (slice and compare output).
using Json = nlohmann::ordered_json;

/// JSON for a point.
Json pointJson(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

/// `pdesurf slice`: each plane's largest closed loop, as JSON.
struct SliceCommand {
  std::string meshPath, outPath, axis;
  std::uint32_t count = 0;
  std::vector<double> range, near;
  bool track = false;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "slice",
        "Cut a mesh (OFF, OBJ, PLY, STL) by planes perpendicular to an axis; print each "
        "plane's largest closed loop (or the one --near / --track pick) as JSON");
    cmd->add_option("mesh", meshPath, "mesh file: .off .obj .ply .stl")->required();
    cmd->add_option("--axis", axis, "axis the planes are perpendicular to: x, y or z")
        ->required()
        ->check(CLI::IsMember({"x", "y", "z"}));
    cmd->add_option("--count", count, "number of planes K, evenly spaced")
        ->required()
        ->check(CLI::Range(1u, 100000u));
    cmd->add_option("--range", range,
                    "planes from a to b, both ends included (default: the mesh's extent cut "
                    "into K slabs, a plane in the middle of each)")
        ->expected(2);
    cmd->add_option("--near", near,
                    "keep on each plane the closed loop whose centroid is nearest to the point "
                    "X Y Z projected onto the plane (one part of a mesh that a plane cuts in "
                    "several loops, such as one leg)")
        ->expected(3);
    cmd->add_flag("--track", track,
                  "keep on each plane the loop nearest to the previous plane's loop (the first "
                  "plane: nearest to --near if given, else the largest), following a part "
                  "that moves across the planes");
    cmd->add_option("-o,--output", outPath, "write the JSON to this file (whole or not at all)");
    return cmd;
  }

  int run() const {
    const SliceOptions options = cli::sliceOptionsFrom<UsageError>(axis, count, range, near, track);
    const Mesh mesh = readTriangles(meshPath);
    std::vector<MeshSection> sections;
    try {
      sections = sliceMesh(mesh, options);
    } catch (const MeshSliceError& e) {
      throw MeshIoError(fmt::format("{}: {}", meshPath, e.what()));
    }
    Json planes = Json::array();
    for (const MeshSection& section : sections) {
      Json points = Json::array();
      for (const Vec3& p : section.points) points.push_back(pointJson(p));
      planes.push_back({{"index", section.index},
                        {"coordinate", section.coordinate},
                        {"points", std::move(points)},
                        {"length", section.length},
                        {"area", section.area}});
    }
    const std::string text =
        Json{{"axis", axisName(options.axis)}, {"planes", std::move(planes)}}.dump() + "\n";
    if (outPath.empty())
      std::cout << text;
    else
      writeFileAtomically(outPath, text);
    return 0;
  }
};

/// `pdesurf compare`: Metro-style distances between a model's mesh and a mesh file.
struct CompareCommand {
  std::string modelPath, meshPath;
  std::uint32_t resolution = 17;
  std::size_t samples = DistanceOptions{}.samples;
  bool json = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "RMS, mean and largest distance between a model (tessellated as by build) and a mesh, "
        "both ways, relative to the mesh's bounding-box diagonal");
    cmd->add_option("model", modelPath, "model file (JSON)")->required();
    cmd->add_option("mesh", meshPath, "reference mesh file: .off .obj .ply .stl")->required();
    cmd->add_option("--resolution", resolution, "samples per patch side, as for build")
        ->check(CLI::Range(2u, 4097u))
        ->capture_default_str();
    cmd->add_option("--samples", samples,
                    "face samples on each mesh, spread by area (every vertex and every "
                    "triangle is sampled too)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
        ->capture_default_str();
    cmd->add_flag("--json", json, "print JSON");
    solveArgs.add(cmd);
    return cmd;
  }

  static Json oneWayJson(const OneWayDistance& d) {
    return {{"samples", d.samples},
            {"rms", d.rms},
            {"rms_relative", d.rmsRelative},
            {"mean", d.mean},
            {"mean_relative", d.meanRelative},
            {"max", d.max},
            {"max_relative", d.maxRelative},
            {"max_at", pointJson(d.maxAt)},
            {"cover_radius", d.coverRadius}};
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
    try {
      d = meshDistance(built.mesh, mesh, options);
    } catch (const std::invalid_argument& e) {
      throw MeshIoError(fmt::format("{} vs {}: {}", modelPath, meshPath, e.what()));
    }
    const double distanceMs = msSince(t0);
    if (json) {
      Json j = {{"model", modelPath},
                {"mesh", meshPath},
                {"resolution", resolution},
                {"diagonal", d.diagonal},
                {"model_to_mesh", oneWayJson(d.aToB)},
                {"mesh_to_model", oneWayJson(d.bToA)},
                {"hausdorff", d.hausdorff},
                {"hausdorff_relative", d.hausdorffRelative}};
      std::cout << j.dump(2) << '\n';
      return 0;
    }
    fmt::print(
        "{}: {} at resolution {}; {}: {}, bounding-box diagonal {:.6g} "
        "(solve {:.3f} ms, tessellate {:.3f} ms, read {:.1f} ms, distance {:.1f} ms)\n",
        built.name, count(built.mesh.triangleCount(), "triangle"), resolution, meshPath,
        count(mesh.triangleCount(), "triangle"), d.diagonal, built.solveMs, built.tessMs, readMs,
        distanceMs);
    cli::printDistances(d);
    return 0;
  }
};

/// `pdesurf coons`: bilinear or bicubic Coons patches on the boundaries of a model's
/// vertex-frame patches (the seed 000 §4.2 baselines), written as a mesh.
struct CoonsCommand {
  std::string modelPath, outPath;
  std::vector<std::uint32_t> frames;
  std::vector<double> tangents;
  std::uint32_t resolution = 17;
  bool bilinear = false, own = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "coons",
        "Coons patches on the boundary curves of a vertex-frame model's patches (the seed's "
        "baselines): bicubic with tangents w1 α(u), w2 β(u), w3 γ(v), w4 δ(v), or bilinear");
    cmd->add_option("model", modelPath, "vertex-frames model file (JSON)")->required();
    cmd->add_option("-o,--output", outPath, "mesh file to write: .obj .ply .stl .glb .off")
        ->required();
    cmd->add_option("--frame", frames, "the frames to fill (default: every frame)");
    cmd->add_option("--tangents", tangents,
                    "w1,w2,w3,w4 as 12 numbers w1x,w1y,w1z,...,w4z (default 0: flat tangents)")
        ->delimiter(',')
        ->expected(12);
    cmd->add_flag("--own-tangents", own,
                  "use each patch's own cross-boundary derivatives as tangents (then a patch "
                  "without forces is reproduced)");
    cmd->add_flag("--bilinear", bilinear, "bilinear Coons patches (no tangents)");
    cmd->add_option("--resolution", resolution, "samples per patch side")
        ->check(CLI::Range(2u, 4097u))
        ->capture_default_str();
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    if (bilinear + own + !tangents.empty() > 1)
      throw UsageError("coons: choose one of --bilinear, --tangents and --own-tangents");
    checkMeshExtension(outPath);
    AnyModel any = loadModel(modelPath);
    const auto* model = std::get_if<VertexFrameModel>(&any);
    if (!model) throw UsageError(fmt::format("{}: coons takes a vertex-frames model", modelPath));
    const VertexFrameSurface surface = solve(*model, solveArgs.options(any));
    std::vector<std::uint32_t> which = frames;
    if (which.empty())
      for (std::uint32_t k = 0; k < surface.patches.size(); ++k) which.push_back(k);
    std::array<Vec3, 4> w;  // Eigen vectors start uninitialised: zero them
    w.fill(Vec3::Zero());
    for (std::size_t i = 0; i < tangents.size(); ++i)
      w[i / 3][static_cast<int>(i % 3)] = tangents[i];
    std::vector<CoonsPatch> patches;
    for (std::uint32_t k : which) {
      if (k >= surface.patches.size())
        throw UsageError(fmt::format("--frame {}: out of range, the model has {} frame{}", k,
                                     surface.patches.size(),
                                     surface.patches.size() == 1 ? "" : "s"));
      const VertexFramePatch& patch = surface.patches[k];
      CoonsBoundary boundary = boundaryOf(patch);
      if (bilinear) {
        patches.push_back(CoonsPatch::bilinear(std::move(boundary)));
      } else {
        CoonsTangents t = own ? patchTangents(patch) : seedTangents(boundary, w);
        patches.push_back(CoonsPatch::bicubic(std::move(boundary), std::move(t)));
      }
    }
    const Mesh mesh = tessellate(patches, resolution);
    writeMesh(mesh, outPath);
    fmt::print("{}: {} {} Coons patch{} -> {} ({}, {})\n", modelDisplayName(model->name, modelPath),
               patches.size(), bilinear ? "bilinear" : "bicubic", patches.size() == 1 ? "" : "es",
               outPath, count(mesh.vertexCount(), "vertex"),
               count(mesh.triangleCount(), "triangle"));
    return 0;
  }
};

}  // namespace

int main(int argc, char** argv) {
  // Past a file-size limit, a write should fail (and the temporary file go) rather than
  // the process be killed mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "pdesurf: PDE-based surface modelling from vertex-frames.\n"
      "Exit status: 0 success, 1 invalid input file, 2 usage error."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pdesurf 0.1.0");
  // Before or after the command's name: `pdesurf --threads 2 build …` or `pdesurf build … --threads
  // 2`.
  app.fallthrough();
  unsigned threads = 0;
  app.add_option("--threads", threads,
                 "threads for tessellation, evaluation, compare and slice (default 0: all cores); "
                 "the output is the same for any number")
      ->check(CLI::Range(0u, 4096u));

  // Every command, in the order --help lists them, and what runs the one given.
  std::tuple<BuildCommand, SampleCommand, InfoCommand, StudioCommand, FitCommand, SpineCommand,
             CoonsCommand, SliceCommand, CompareCommand, cli::ExportCommand, cli::RebuildCommand>
      commands;
  std::vector<std::pair<CLI::App*, std::function<int()>>> registered;
  std::apply(
      [&](auto&... command) {
        (registered.emplace_back(command.add(app), [&command] { return command.run(); }), ...);
      },
      commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }

  // Every parallel loop (oneTBB) runs on at most this many threads.
  std::optional<tbb::global_control> threadLimit;
  if (threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, threads);

  try {
    for (const auto& [command, run] : registered)
      if (*command) return run();
    return kExitUsage;  // require_subcommand(1): not reached
  } catch (const UsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  } catch (const MeshIoError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitInput;
  } catch (const ModelError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitInput;
  }
}
