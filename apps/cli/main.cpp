// pdesurf: the command line. Thin: parse arguments, call the library, report.
// Exit codes: 0 success, 1 bad input (model or mesh file), 2 usage error.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <variant>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bspline_commands.hpp"
#include "cli_common.hpp"
#include "distance_report.hpp"
#include "export_command.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/coons.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"
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
using cli::modelName;
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
  SolveOptions options(const VertexFrameModel& model) const {
    if (seedFrame >= model.frames.size())
      throw UsageError(
          fmt::format("--seed-frame {}: out of range, the model has {} frame{} "
                      "(indices 0 to {})",
                      seedFrame, model.frames.size(), model.frames.size() == 1 ? "" : "s",
                      model.frames.size() - 1));
    return {solver == "local" ? Solver::Local : Solver::Global, seedFrame};
  }
};

void printNotes(const VertexFrameSurface& surface, const std::string& model) {
  for (const std::string& note : surface.notes) fmt::print(stderr, "{}: note: {}\n", model, note);
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

/// A model of any type solved and tessellated: what `build` writes and `compare` measures.
struct BuiltModel {
  std::string name;
  std::string summary;  ///< "3 frames, 2 strips" / "spectral, order 12, 1 patch"
  std::string quality;  ///< "C0 gap 0" / "condition error 1e-15" / "joint C0 gap 0"
  Mesh mesh;
  double solveMs = 0.0, tessMs = 0.0;
};

BuiltModel buildModel(const std::string& modelPath, std::uint32_t resolution,
                      const SolveArgs& args) {
  BuiltModel built;
  const AnyModel any = loadModel(modelPath);
  built.name = modelName(modelNameOf(any), modelPath);
  if (const auto* model = std::get_if<VertexFrameModel>(&any)) {
    const SolveOptions options = args.options(*model);
    auto t0 = Clock::now();
    const VertexFrameSurface surface = solve(*model, options);
    built.solveMs = msSince(t0);
    printNotes(surface, modelPath);
    t0 = Clock::now();
    built.mesh = tessellate(surface, {resolution});
    built.tessMs = msSince(t0);
    built.summary = fmt::format("{}, {}", count(model->frames.size(), "frame"),
                                count(surface.topology->stripCount, "strip"));
    built.quality = fmt::format("C0 gap {:.3g}", measureC0Gap(surface).maxGap);
    return built;
  }
  if (const auto* model = std::get_if<BSplinePdeModel>(&any)) {
    auto t0 = Clock::now();
    const SolvedBSplinePde solved = solveBSplineModel(*model, modelPath);
    built.solveMs = msSince(t0);
    t0 = Clock::now();
    built.mesh = tessellate(solved, resolution);
    built.tessMs = msSince(t0);
    built.summary = cli::bsplineSummary(solved);
    built.quality = cli::bsplineQuality(solved);
    return built;
  }
  auto t0 = Clock::now();
  const SolvedSpectral solved = *solveIfSpectral(any, modelPath);  // the types left
  built.solveMs = msSince(t0);
  t0 = Clock::now();
  built.mesh = tessellate(solved, resolution);
  built.tessMs = msSince(t0);
  const SpectralPatch& first = solved.patchAt(0);
  built.summary =
      fmt::format("{}, order {}, {} mode{}, {}", solved.type, first.op().order(), first.modes(),
                  first.modes() == 1 ? "" : "s", count(solved.patchCount(), "patch"));
  double worst = 0.0;
  for (std::size_t k = 0; k < solved.patchCount(); ++k)
    for (double e : conditionErrors(solved.patchAt(k))) worst = std::max(worst, e);
  built.quality = fmt::format("condition error {:.3g}", worst);
  if (solved.chain) {
    double gap = 0.0;
    for (const JointGap& g : measureJointGaps(*solved.chain)) gap = std::max(gap, g.c0Relative);
    built.quality += fmt::format(", joint C0 gap {:.3g}", gap);
  }
  return built;
}

int runBuild(const std::string& modelPath, const std::string& outPath, std::uint32_t resolution,
             const SolveArgs& args, bool quiet) {
  checkMeshExtension(outPath);
  const BuiltModel built = buildModel(modelPath, resolution, args);
  const Mesh& mesh = built.mesh;
  auto t0 = Clock::now();
  writeMesh(mesh, outPath);
  const double writeMs = msSince(t0);
  if (!quiet)
    fmt::print(
        "{}: {}, {}, {}, {} -> {} "
        "(solve {:.3f} ms, tessellate {:.3f} ms, write {:.1f} ms)\n",
        built.name, built.summary, count(mesh.vertexCount(), "vertex"),
        count(mesh.triangleCount(), "triangle"), built.quality, outPath, built.solveMs,
        built.tessMs, writeMs);
  return 0;
}

int runSample(const std::string& modelPath, std::uint32_t grid, const SolveArgs& args) {
  AnyModel any = loadModel(modelPath);
  if (auto solved = solveIfSpectral(any, modelPath)) {
    std::cout << cli::sampleJson(*solved, grid);
    return 0;
  }
  if (const auto* m = std::get_if<BSplinePdeModel>(&any)) {
    std::cout << cli::bsplineSampleJson(solveBSplineModel(*m, modelPath), grid);
    return 0;
  }
  const VertexFrameModel model = std::get<VertexFrameModel>(std::move(any));
  const VertexFrameSurface surface = solve(model, args.options(model));
  printNotes(surface, modelPath);
  // nlohmann writes doubles in their shortest round-trip form.
  nlohmann::json patches = nlohmann::json::array();
  for (std::size_t k = 0; k < surface.patches.size(); ++k) {
    nlohmann::json points = nlohmann::json::array();
    for (std::uint32_t j = 0; j < grid; ++j)
      for (std::uint32_t i = 0; i < grid; ++i) {
        const double u = static_cast<double>(i) / (grid - 1);
        const double v = static_cast<double>(j) / (grid - 1);
        const Vec3 p = surface.patches[k].position(u, v);
        points.push_back({p.x(), p.y(), p.z()});
      }
    patches.push_back({{"frame", k}, {"grid", grid}, {"points", std::move(points)}});
  }
  std::cout << nlohmann::json{{"patches", std::move(patches)}}.dump() << '\n';
  return 0;
}

int runInfo(const std::string& modelPath, bool json, const SolveArgs& args) {
  AnyModel any = loadModel(modelPath);
  if (auto solved = solveIfSpectral(any, modelPath)) {
    std::cout << cli::infoText(*solved, modelPath, modelNameOf(any), json);
    return 0;
  }
  if (const auto* m = std::get_if<BSplinePdeModel>(&any)) {
    std::cout << cli::bsplineInfoText(*m, solveBSplineModel(*m, modelPath), modelPath, json);
    return 0;
  }
  const VertexFrameModel model = std::get<VertexFrameModel>(std::move(any));
  const VertexFrameSurface surface = solve(model, args.options(model));
  printNotes(surface, modelPath);
  const C0Report c0 = measureC0Gap(surface);
  const Bounds b = surfaceBounds(surface);
  const double diag = b.diagonal();
  const double rel = diag > 0.0 ? c0.maxGap / diag : c0.maxGap;
  std::size_t pinned = 0;
  for (auto p : surface.topology->stripPinned) pinned += p;
  const std::size_t storage = storageBytes(model);
  const std::size_t coincident = coincidentVertices(model);
  if (json) {
    nlohmann::json j = {
        {"model", modelPath},
        {"name", model.name},
        {"vertices", model.vertices.size()},
        {"frames", model.frames.size()},
        {"strips", surface.topology->stripCount},
        {"pinned_strips", pinned},
        {"edges", surface.topology->edges.size()},
        {"shared_edges", c0.sharedEdges},
        {"orientable", surface.topology->orientable},
        {"c0_gap", c0.maxGap},
        {"c0_gap_relative", rel},
        {"bbox",
         {{"min", {b.min.x(), b.min.y(), b.min.z()}}, {"max", {b.max.x(), b.max.y(), b.max.z()}}}},
        {"storage_bytes", storage},
        {"coincident_vertices", coincident},
        {"solver", args.solver},
        {"notes", surface.notes}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  fmt::print("model      {}{}\n", modelPath, model.name.empty() ? "" : " (" + model.name + ")");
  fmt::print("vertices   {}\nframes     {}\n", model.vertices.size(), model.frames.size());
  fmt::print("strips     {} ({} pinned to 0)\n", surface.topology->stripCount, pinned);
  fmt::print("edges      {} ({} shared)\n", surface.topology->edges.size(), c0.sharedEdges);
  fmt::print("C0 gap     {} (relative to the bounding-box diagonal: {})\n", c0.maxGap, rel);
  fmt::print("bbox       [{}, {}, {}] to [{}, {}, {}]\n", b.min.x(), b.min.y(), b.min.z(),
             b.max.x(), b.max.y(), b.max.z());
  fmt::print("storage    {} bytes (numbers to six significant digits)\n", storage);
  if (!surface.topology->orientable) fmt::print("orientable no\n");
  if (coincident > 0)
    fmt::print(
        "warning    {} {} where another vertex stands, under another index: frames "
        "meet only through shared indices, so the surface may have cracks there\n",
        coincident, coincident == 1 ? "vertex stands" : "vertices stand");
  return 0;
}

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
    SliceOptions options;
    options.axis = *parseAxis(axis);
    options.count = count;
    if (!range.empty()) {
      options.range = {range[0], range[1]};
      try {
        slicePlanes(options, 0.0, 1.0);  // the range's own checks, before any work
      } catch (const std::invalid_argument& e) {
        throw UsageError(fmt::format("--range: {}", e.what()));
      }
    }
    if (!near.empty()) {
      options.near = Vec3(near[0], near[1], near[2]);
      if (!options.near->allFinite())
        throw UsageError(
            fmt::format("--near: {} {} {} is not a finite point", near[0], near[1], near[2]));
    }
    options.track = track;
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
    const VertexFrameSurface surface = solve(*model, solveArgs.options(*model));
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
    fmt::print("{}: {} {} Coons patch{} -> {} ({}, {})\n", modelName(model->name, modelPath),
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

  std::string modelPath, outPath;
  std::uint32_t resolution = 17, grid = 0;
  bool json = false, quiet = false;
  SolveArgs solveArgs;

  CLI::App* build = app.add_subcommand("build",
                                       "Solve a model and write its mesh (OBJ, PLY, STL, "
                                       "glb or OFF, chosen by the output's extension)");
  build->add_option("model", modelPath, "model file (JSON)")->required();
  build->add_option("-o,--output", outPath, "mesh file to write: .obj .ply .stl .glb .off")
      ->required();
  build->add_option("--resolution", resolution, "samples per patch side")
      ->check(CLI::Range(2u, 4097u))
      ->capture_default_str();
  build->add_flag("-q,--quiet", quiet, "print nothing on success");
  solveArgs.add(build);

  CLI::App* sample = app.add_subcommand(
      "sample", "Print each patch sampled on a grid as JSON: points[j*N+i] = S(i/(N-1), j/(N-1))");
  sample->add_option("model", modelPath, "model file (JSON)")->required();
  sample->add_option("--grid", grid, "samples per patch side (N)")
      ->required()
      ->check(CLI::Range(2u, 4097u));
  solveArgs.add(sample);

  CLI::App* info = app.add_subcommand(
      "info", "Counts, the largest C0 gap on shared edges, bounding box and storage size");
  info->add_option("model", modelPath, "model file (JSON)")->required();
  info->add_flag("--json", json, "print JSON");
  solveArgs.add(info);

  pdesurf::studio::StudioOptions studioOptions;
  CLI::App* studio = app.add_subcommand(
      "studio", "Serve a model for interactive editing in a browser (until Ctrl-C)");
  studio->add_option("model", modelPath, "model file (JSON)")->required();
  studio->add_option("--root", studioOptions.root,
                     "folder the studio may open and write in (default: the model's folder)");
  studio->add_option("--port", studioOptions.port, "port to listen on (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  studio->add_option("--host", studioOptions.host, "address to listen on")->capture_default_str();
  studio->add_flag_callback(
      "--no-token", [&studioOptions] { studioOptions.requireToken = false; },
      "UNSAFE, for tests only: serve the API without the per-launch token of the printed URL "
      "(any program of any local user may then read and change the models)");

  std::vector<std::uint32_t> fitTerms;
  bool fitUniform = false;
  CLI::App* fit = app.add_subcommand(
      "fit",
      "Fit each closed curve of a curves file (a cross-sections model or {\"curves\": [...]}) "
      "by a Fourier series; print the largest and mean distance of the points per number of "
      "terms");
  fit->add_option("curves", modelPath, "curves file (JSON)")->required();
  fit->add_option("--terms", fitTerms, "numbers of Fourier terms N (one or more)")
      ->required()
      ->check(CLI::Range(0u, 512u));
  fit->add_flag("--uniform", fitUniform,
                "give points uniform v (default: chord length, as the seeds)");
  fit->add_flag("--json", json, "print JSON");

  std::uint32_t spineCount = 33;
  CLI::App* spine = app.add_subcommand(
      "spine", "Print the spine A0(u) of a spectral or cross-sections model as JSON polylines");
  spine->add_option("model", modelPath, "model file (JSON)")->required();
  spine->add_option("--count", spineCount, "points per patch")
      ->check(CLI::Range(2u, 100000u))
      ->capture_default_str();

  CoonsCommand coonsCommand;
  CLI::App* coons = coonsCommand.add(app);

  SliceCommand sliceCommand;
  CLI::App* slice = sliceCommand.add(app);
  CompareCommand compareCommand;
  CLI::App* compare = compareCommand.add(app);
  cli::ExportCommand exportCommand;
  CLI::App* exportCmd = exportCommand.add(app);
  cli::RebuildCommand rebuildCommand;
  CLI::App* rebuild = rebuildCommand.add(app);

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
    if (*build) return runBuild(modelPath, outPath, resolution, solveArgs, quiet);
    if (*sample) return runSample(modelPath, grid, solveArgs);
    if (*studio) return pdesurf::studio::runStudio(modelPath, studioOptions);
    if (*slice) return sliceCommand.run();
    if (*coons) return coonsCommand.run();
    if (*fit) {
      std::cout << cli::fitReport(modelPath, fitTerms, !fitUniform, json);
      return 0;
    }
    if (*spine) {
      AnyModel any = loadModel(modelPath);
      auto solved = solveIfSpectral(any, modelPath);
      if (!solved)
        throw UsageError(fmt::format(
            "{}: only spectral and cross-sections models have a spine (this is a {} model)",
            modelPath, modelTypeName(any)));
      std::cout << cli::spineJson(*solved, spineCount);
      return 0;
    }
    if (*compare) return compareCommand.run();
    if (*exportCmd) return exportCommand.run();
    if (*rebuild) return rebuildCommand.run();
    return runInfo(modelPath, json, solveArgs);
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
