#include "rebuild_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "distance_report.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/occt_loft.hpp"

namespace pdesurf::cli {

namespace {

/// rebuild(), with the errors of a mesh it cannot use (`Caught`: InvalidArgument for
/// vertex frames, any for cross sections) turned into MeshIoError "MESH: reason" (exit 1,
/// naming the file).
template <class Caught>
RebuildResult namingMesh(const Mesh& mesh, const RebuildOptions& options,
                         const RebuildProgress& progress = {}) {
  try {
    return rebuild(mesh, options, progress);
  } catch (const Caught& e) {
    throw MeshIoError(fmt::format("{}: {}", options.source, e.what()));
  }
}

/// A well-formed argument that cannot be used (exit 2).
struct RebuildUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The loft's triangulation lies within this fraction of the part's diagonal of the loft
/// surface: 0.01 %, a tenth of the smallest distances compared (0.1 % and up).
constexpr double kLoftDeflection = 1e-4;

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
  cmd->add_option("--tube", tube,
                  "vertex-frames: RINGS SECTORS, a tube of frames on the part of the mesh that "
                  "--axis, --range, --near and --track choose (rings from slicing, sectors "
                  "closed round the tube)")
      ->expected(2)
      ->check(CLI::Range(1u, 1000u));
  addInRange(cmd, "--iterations", iterations, "vertex-frames: most fitting iterations", 0u,
             100000u);
  // The fit's real-valued options: flag, value, help, range.
  struct RealOption {
    const char* flag;
    double* value;
    const char* help;
    double low, high;
  };
  const RealOption reals[] = {
      {"--tolerance", &tolerance,
       "vertex-frames: stop when an iteration lowers the RMS by less than this fraction of it", 0.0,
       1.0},
      {"--smoothness", &smoothness,
       "vertex-frames: weight of the Laplacian of the vertex positions against the mean "
       "squared distances",
       0.0, 1e6},
      {"--fold-weight", &conformalWeight,
       "vertex-frames: weight of the fold-free term, which keeps each frame's map from (u, v) "
       "near a rotation and scale in the mesh's tangent plane (0: distances alone)",
       0.0, 1.0}};
  for (const RealOption& r : reals) addInRange(cmd, r.flag, *r.value, r.help, r.low, r.high);
  normalWeightOption =
      cmd->add_option("--normal-weight", normalWeight,
                      fmt::format("vertex-frames: weight of the normal-alignment term, which "
                                  "pulls the patches' tangents into the mesh's tangent plane "
                                  "(fewer creases at frame sides; 0: off; default {:g} with "
                                  "--target-rms, whose bounds judge the model, 0 otherwise: it "
                                  "costs about 1.6x the fit's time)",
                                  kNormalWeight))
          ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--fit-samples", samples,
                  "vertex-frames: surface samples per patch side (3 to 65; 0: about as many "
                  "surface samples as mesh vertices, 4 to 9 a side)")
      ->check(CLI::Range(0u, 65u) & !CLI::Range(1u, 2u))
      ->capture_default_str();
  cmd->add_flag("--prevent-folds", preventFolds,
                "vertex-frames: refuse steps that fold more of the surface over (fewer folds, "
                "a higher RMS)");
  cmd->add_flag("--fit-shape", fitShape,
                "vertex-frames: after the vertices, fit a whole-frame force, a1 and a2 per frame "
                "too (up to --iterations more iterations; more storage, a lower RMS)");
  automatic.add(cmd);
}

CLI::App* RebuildCommand::add(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "rebuild",
      "Rebuild a mesh as a PDE model (cross-sections: slice it, align and fit the sections, "
      "join them by the global C4 chain; vertex-frames: fit a layout of frames to it); print "
      "its distance to the mesh and its storage");
  cmd->add_option("mesh", meshPath, "mesh file: .off .obj .ply .stl")->required();
  cmd->add_option("--as", as, "the kind of model to build")
      ->required()
      ->check(CLI::IsMember({"cross-sections", "vertex-frames"}));
  cmd->add_option("-o,--output", outPath, "model file to write (JSON; whole or not at all)");
  cmd->add_option("--axis", axis, "cross-sections: axis the slicing planes are perpendicular to")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  addInRange(cmd, "--count", sectionCount, "cross-sections: number of sections K", 2u, 100000u);
  cmd->add_option("--range", range,
                  "cross-sections: sections from a to b, both ends included (default: the "
                  "mesh's extent cut into K slabs, a plane in the middle of each)")
      ->expected(2);
  cmd->add_option("--near", near,
                  "cross-sections: on each plane the loop whose centroid is nearest to X Y Z "
                  "(needed where a plane cuts several parts)")
      ->expected(3);
  cmd->add_flag("--track", track,
                "cross-sections: follow the part from plane to plane (each plane: the loop "
                "nearest to the previous plane's)");
  addInRange(cmd, "--modes", modes, "Fourier modes per section", 1u, 256u);
  addInRange(cmd, "--points", points, "points per section after arc-length resampling", 8u,
             100000u);
  cmd->add_option("--a", a, "the sixth-order operator's a (chain parameter u in [0, 1])")
      ->capture_default_str();
  cmd->add_option("--ends", ends,
                  "conditions at the end sections: natural (third and fourth u-derivatives "
                  "zero) or estimated (first and second from the end sections)")
      ->check(CLI::IsMember({"natural", "estimated"}))
      ->capture_default_str();
  cmd->add_option("--name", name, "the model's name (default: the mesh file's name)");
  cmd->add_option("--part", partPath,
                  "also write the part of the mesh the model rebuilds (.obj .ply .stl .off)");
  addInRange(cmd, "--samples", samples, "face samples on each mesh for the distances",
             std::size_t{1}, std::size_t{100000000});
  cmd->add_flag("--exact", exact,
                "cross-sections: pass through every prepared point of every section (the "
                "model keeps the points and the remainder; more storage) instead of their "
                "smooth M-mode fits");
  cmd->add_flag("--loft", loft,
                "also loft the same prepared sections with Open CASCADE "
                "(BRepOffsetAPI_ThruSections through periodic interpolating B-splines) and "
                "measure it the same way: the peer a CAD user would reach for");
  cmd->add_flag("--json", json, "cross-sections: print JSON");
  addInRange(cmd, "--resolution", resolution,
             "vertex-frames: samples per patch side for the distances printed at the end, "
             "as for compare",
             2u, 4097u);
  cmd->add_flag("-q,--quiet", quiet, "vertex-frames: print nothing on success");
  vertexFrames.add(cmd);
  return cmd;
}

int RebuildCommand::run() const {
  try {
    if (as == "vertex-frames" && outPath.empty())
      throw RebuildUsageError("--as vertex-frames: -o MODEL.json is required");
    const RebuildOptions o = options();
    checkRebuildOptions(o);
    if (as == "cross-sections" && !outPath.empty() && !outPath.ends_with(".json"))
      throw RebuildUsageError(fmt::format("-o {}: a model file ends in .json", outPath));
    return o.kind == RebuildKind::VertexFrames ? runVertexFrames(o) : runCrossSections(o);
  } catch (const RebuildUsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  } catch (const RebuildOptionError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  }
}

RebuildOptions RebuildCommand::options() const {
  RebuildOptions o;
  o.kind = *parseRebuildKind(as);
  o.source = meshPath;
  o.name = name;
  const VertexFrameRebuildArgs& v = vertexFrames;
  o.quadsPath = v.layoutPath;
  if (!v.grid.empty()) o.grid = {v.grid[0], v.grid[1]};
  if (!v.tube.empty()) o.tube = {v.tube[0], v.tube[1]};
  v.automatic.apply(o);
  o.fit.maxIterations = v.iterations;
  o.fit.tolerance = v.tolerance;
  o.fit.smoothness = v.smoothness;
  o.fit.samplesPerSide = v.samples;
  o.fit.preventFolds = v.preventFolds;
  o.fit.conformalWeight = v.conformalWeight;
  if (v.normalWeightOption != nullptr && v.normalWeightOption->count() > 0)
    o.normalWeight = v.normalWeight;
  o.fit.fitShape = v.fitShape;
  o.resolution = resolution;
  o.slice = sliceOptionsFrom<RebuildUsageError>(axis, sectionCount, range, near, track);
  o.modes = modes;
  o.points = points;
  o.a = a;
  o.ends = *parseChainEnds(ends);
  o.exact = exact;
  o.samples = samples;
  // Vertex frames measure what they print: nothing with --quiet.
  o.measure = o.kind == RebuildKind::CrossSections || !quiet;
  return o;
}

int RebuildCommand::runCrossSections(const RebuildOptions& o) const {
  auto t0 = Clock::now();
  const Mesh mesh = readTriangles(meshPath);
  const double readMs = msSince(t0);
  RebuildResult rebuilt = namingMesh<std::exception>(mesh, o);
  RebuildReport& report = rebuilt.report;
  report.ms.read = readMs;
  const Mesh& part = *rebuilt.part;
  const MeshDistance& d = report.distance;
  // The peer: Open CASCADE's loft through the same sections, measured the same way.
  if (loft) {
    report.loft.emplace();
    try {
      const Mesh lofted = occtLoft(rebuilt.prepared, kLoftDeflection * d.diagonal);
      DistanceOptions distanceOptions;
      distanceOptions.samples = samples;
      report.loft->distance = meshDistance(lofted, part, distanceOptions);
    } catch (const std::exception& e) {
      report.loft->failure = e.what();
    }
  }
  if (!partPath.empty()) writeMesh(part, partPath);
  if (!outPath.empty()) writeFileAtomically(outPath, serializeModel(rebuilt.model));
  if (json) {
    std::cout << rebuildReportJson(report, o, outPath) << '\n';
    return 0;
  }
  fmt::print(
      "{}: {} sections along {} from {} to {}, {} modes{}, global C4 chain (a = {}, {} "
      "ends){}\n",
      report.name, report.sections, axis, report.from, report.to, modes,
      exact ? " + exact remainder" : "", a, ends, outPath.empty() ? "" : " -> " + outPath);
  fmt::print("part of the mesh: {}, {}, diagonal {:.6g}\n",
             count(report.referenceVertices, "vertex"),
             count(report.referenceTriangles, "triangle"), d.diagonal);
  printOneWay("model -> part", d.aToB, 4);
  printOneWay("part -> model", d.bToA, 4);
  printNormals(report.normals);
  if (report.loft && report.loft->distance) {
    printOneWay("OCCT loft -> part", report.loft->distance->aToB, 4);
    printOneWay("part -> OCCT loft", report.loft->distance->bToA, 4);
  } else if (report.loft) {
    fmt::print("OCCT loft: failed ({})\n", report.loft->failure);
  }
  fmt::print(
      "storage: model {} bytes, part of the mesh {} bytes ({:.3g}x; numbers to six "
      "significant digits)\n",
      report.storageBytes, report.referenceStorageBytes,
      double(report.storageBytes) / double(report.referenceStorageBytes));
  fmt::print("(read {:.1f} ms, slice + prepare + fit + solve {:.1f} ms, measure {:.1f} ms)\n",
             readMs, report.ms.fit, report.ms.measure);
  return 0;
}

int RebuildCommand::runVertexFrames(const RebuildOptions& o) const {
  const VertexFrameRebuildArgs& args = vertexFrames;
  auto t0 = Clock::now();
  const Mesh mesh = readTriangles(meshPath);
  const double readMs = msSince(t0);

  ProgressBar bar(args.fitShape ? 2 * args.iterations : args.iterations, !quiet);
  RebuildProgress progress;
  progress.onIteration = [&](const FitIteration& it) {
    bar.update(it.iteration, it.measure.rms());
    if (quiet) return;
    const FitMeasure& m = it.measure;
    fmt::print(
        "iteration {:>3}{}: RMS {}  surface -> mesh RMS {} mean {} max {}  mesh -> surface RMS "
        "{} mean {} max {}  folded {} ({}/{})\n",
        it.iteration,
        it.iteration == 0 ? " (layout)"
        : it.shape ? fmt::format(" (shape: step {:g}, a1 a2 step {:g})", it.step, it.parameterStep)
                   : fmt::format(" (step {:g})", it.step),
        percent(m.rms()), percent(m.rmsToMesh), percent(m.meanToMesh), percent(m.maxToMesh),
        percent(m.rmsToModel), percent(m.meanToModel), percent(m.maxToModel), percent(m.foldedArea),
        m.foldedSamples, m.samples);
  };
  if (!quiet) {
    progress.onLayout = printAutomaticLayout;
    progress.onTrial = [&](std::uint32_t requested, const AutoFit& f) {
      printTrial(o, requested, f);
    };
  }
  const RebuildResult rebuilt = namingMesh<InvalidArgument>(mesh, o, progress);
  const RebuildReport& report = rebuilt.report;
  if (report.search && !quiet) printSearch(o, report);
  // The tube's part: what the model was fitted to and measured against.
  if (rebuilt.part && !partPath.empty()) writeMesh(*rebuilt.part, partPath);
  writeFileAtomically(outPath, serializeModel(rebuilt.model));
  if (quiet) return 0;
  const MeshDistance& d = report.distance;
  fmt::print("{}: {}\n", outPath, report.stopReason);
  fmt::print("{}: {}, {}, {} -> {} (layout {:.1f} ms, fit {:.1f} ms)\n", report.name,
             count(report.frames, "frame"), count(report.vertices, "vertex"),
             count(report.iterations.size() - 1, "iteration"), outPath, readMs + report.ms.layout,
             report.ms.fit);
  fmt::print("{} at resolution {}; {}{}: {}, bounding-box diagonal {:.6g}\n", outPath, resolution,
             meshPath, o.tube ? " (the part between the end planes)" : "",
             count(report.referenceTriangles, "triangle"), d.diagonal);
  printDistances(d);
  printNormals(report.normals);
  fmt::print("storage        {} bytes (numbers to six significant digits)\n", report.storageBytes);
  if (report.automatic) printStorageAgainstMesh(report);
  // A model that folds is what a user rejects whatever its RMS: say so, and what helps.
  if (report.normals.foldedArea > kMaxFoldedArea)
    fmt::print(stderr,
               "pdesurf: warning: {:.3g}% of the model's area is folded (its normal points "
               "against the mesh's), more than {:.3g}%: the layout is too coarse for this mesh; "
               "more frames ({}) usually unfold it\n",
               100.0 * report.normals.foldedArea, 100.0 * kMaxFoldedArea,
               report.automatic ? "a larger --frames, or --target-rms"
                                : "a finer --grid, --tube or --layout");
  return 0;
}

}  // namespace pdesurf::cli
