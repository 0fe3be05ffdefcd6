#include "rebuild_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "distance_report.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/occt_loft.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/spectral_io.hpp"
#include "pdesurf/tube_layout.hpp"

namespace pdesurf::cli {

namespace {

using Json = nlohmann::ordered_json;

/// `compute()`, with the InvalidArgument a mesh it cannot use throws turned into
/// MeshIoError "MESH: WHAT<reason>" (exit 1, naming the file).
template <class Compute>
auto namingMesh(const std::string& meshPath, std::string_view what, Compute&& compute) {
  try {
    return compute();
  } catch (const InvalidArgument& e) {
    throw MeshIoError(fmt::format("{}: {}{}", meshPath, what, e.what()));
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

Json oneWay(const OneWayDistance& d) {
  return {{"rms", d.rms},   {"rms_relative", d.rmsRelative},
          {"mean", d.mean}, {"mean_relative", d.meanRelative},
          {"max", d.max},   {"max_relative", d.maxRelative}};
}

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
  addInRange(cmd, "--tolerance", tolerance,
             "vertex-frames: stop when an iteration lowers the RMS by less than this "
             "fraction of it",
             0.0, 1.0);
  addInRange(cmd, "--smoothness", smoothness,
             "vertex-frames: weight of the Laplacian of the vertex positions against the "
             "mean squared distances",
             0.0, 1e6);
  cmd->add_option("--fit-samples", samples,
                  "vertex-frames: surface samples per patch side (3 to 65; 0: about as many "
                  "surface samples as mesh vertices, 4 to 9 a side)")
      ->check(CLI::Range(0u, 65u) & !CLI::Range(1u, 2u))
      ->capture_default_str();
  cmd->add_flag("--prevent-folds", preventFolds,
                "vertex-frames: refuse steps that fold more of the surface over (fewer folds, "
                "a higher RMS)");
  addInRange(cmd, "--fold-weight", conformalWeight,
             "vertex-frames: weight of the fold-free term, which keeps each frame's map from "
             "(u, v) near a rotation and scale in the mesh's tangent plane (0: distances alone)",
             0.0, 1.0);
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
    return as == "vertex-frames" ? runVertexFrames() : runCrossSections();
  } catch (const RebuildUsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  }
}

SliceOptions RebuildCommand::sliceOptions() const {
  return sliceOptionsFrom<RebuildUsageError>(axis, sectionCount, range, near, track);
}

int RebuildCommand::runCrossSections() const {
  if (vertexFrames.fitShape)
    throw RebuildUsageError(
        "--fit-shape fits the force, a1 and a2 of vertex frames: it needs --as vertex-frames");
  if (!std::isfinite(a) || a == 0.0)
    throw RebuildUsageError(fmt::format("--a {}: a must be finite and non-zero", a));
  if (points < 2 * modes + 1)
    throw RebuildUsageError(
        fmt::format("--points {} cannot determine --modes {}: give at least {} points", points,
                    modes, 2 * modes + 1));
  if (!outPath.empty() && !outPath.ends_with(".json"))
    throw RebuildUsageError(fmt::format("-o {}: a model file ends in .json", outPath));
  SectionRebuildOptions options;
  options.slice = sliceOptions();
  options.modes = modes;
  options.exact = exact;
  options.prep.points = points;
  options.a = a;
  options.ends = ends == "natural" ? ChainEnds::Natural : ChainEnds::Estimated;
  options.name = name.empty() ? modelName("", meshPath) : name;
  auto t0 = Clock::now();
  const Mesh mesh = readTriangles(meshPath);
  const double readMs = msSince(t0);
  t0 = Clock::now();
  SectionRebuild rebuilt;
  try {
    rebuilt = rebuildFromSections(mesh, options);
  } catch (const std::exception& e) {
    throw MeshIoError(fmt::format("{}: {}", meshPath, e.what()));
  }
  const double rebuildMs = msSince(t0);
  const auto& sections = rebuilt.sections;
  rebuilt.model.description =
      fmt::format("{} rebuilt by pdesurf rebuild from {} sections along {} in [{}, {}]", meshPath,
                  sections.size(), axis, sections.front().coordinate, sections.back().coordinate);
  t0 = Clock::now();
  const Mesh part = sectionedPart(mesh, options.slice.axis, sections);
  const Mesh surface = tessellate(rebuilt.chain, chainMeasureOptions(rebuilt.chain.patches.size()));
  DistanceOptions distanceOptions;
  distanceOptions.samples = samples;
  const MeshDistance d = namingMesh(
      meshPath, "the rebuilt part: ", [&] { return meshDistance(surface, part, distanceOptions); });
  const NormalDeviation normals =
      namingMesh(meshPath, "the rebuilt part: ", [&] { return normalDeviation(surface, part); });
  const double measureMs = msSince(t0);
  // The peer: Open CASCADE's loft through the same sections, measured the same way.
  std::optional<MeshDistance> loftDistance;
  std::string loftFailure;
  if (loft) {
    try {
      const Mesh lofted = occtLoft(rebuilt.prepared, kLoftDeflection * d.diagonal);
      loftDistance = meshDistance(lofted, part, distanceOptions);
    } catch (const std::exception& e) {
      loftFailure = e.what();
    }
  }
  if (!partPath.empty()) writeMesh(part, partPath);
  if (!outPath.empty()) writeFileAtomically(outPath, serializeModel(rebuilt.model));
  const std::size_t modelBytes = storageBytes(rebuilt.model), partBytes = storageBytes(part);
  if (json) {
    Json j = {{"mesh", meshPath},
              {"as", as},
              {"output", outPath},
              {"axis", axis},
              {"sections", sections.size()},
              {"from", sections.front().coordinate},
              {"to", sections.back().coordinate},
              {"modes", modes},
              {"exact", exact},
              {"a", a},
              {"ends", ends},
              {"diagonal", d.diagonal},
              {"model_to_part", oneWay(d.aToB)},
              {"part_to_model", oneWay(d.bToA)},
              {"normals", normalsJson(normals)},
              {"model_storage_bytes", modelBytes},
              {"part_storage_bytes", partBytes},
              {"part_triangles", part.triangleCount()},
              {"part_vertices", part.vertexCount()},
              {"ms", {{"read", readMs}, {"rebuild", rebuildMs}, {"measure", measureMs}}}};
    if (loftDistance)
      j["loft"] = {{"model_to_part", oneWay(loftDistance->aToB)},
                   {"part_to_model", oneWay(loftDistance->bToA)}};
    else if (loft)
      j["loft"] = {{"failed", loftFailure}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  fmt::print(
      "{}: {} sections along {} from {} to {}, {} modes{}, global C4 chain (a = {}, {} "
      "ends){}\n",
      options.name, sections.size(), axis, sections.front().coordinate, sections.back().coordinate,
      modes, exact ? " + exact remainder" : "", a, ends, outPath.empty() ? "" : " -> " + outPath);
  fmt::print("part of the mesh: {}, {}, diagonal {:.6g}\n", count(part.vertexCount(), "vertex"),
             count(part.triangleCount(), "triangle"), d.diagonal);
  printOneWay("model -> part", d.aToB, 4);
  printOneWay("part -> model", d.bToA, 4);
  printNormals(normals);
  if (loftDistance) {
    printOneWay("OCCT loft -> part", loftDistance->aToB, 4);
    printOneWay("part -> OCCT loft", loftDistance->bToA, 4);
  } else if (loft) {
    fmt::print("OCCT loft: failed ({})\n", loftFailure);
  }
  fmt::print(
      "storage: model {} bytes, part of the mesh {} bytes ({:.3g}x; numbers to six "
      "significant digits)\n",
      modelBytes, partBytes, double(modelBytes) / double(partBytes));
  fmt::print("(read {:.1f} ms, slice + prepare + fit + solve {:.1f} ms, measure {:.1f} ms)\n",
             readMs, rebuildMs, measureMs);
  return 0;
}

int RebuildCommand::runVertexFrames() const {
  const VertexFrameRebuildArgs& args = vertexFrames;
  if (outPath.empty()) throw RebuildUsageError("--as vertex-frames: -o MODEL.json is required");
  const int layouts =
      int(!args.layoutPath.empty()) + int(!args.grid.empty()) + int(!args.tube.empty());
  if (layouts > 1)
    throw RebuildUsageError(
        "--as vertex-frames: give one of --layout QUADS, --grid U V and --tube RINGS SECTORS "
        "(or none of them: the automatic layout)");
  const bool automatic = layouts == 0;
  if (!automatic && args.automatic.given())
    throw RebuildUsageError(
        "--frames, --target-rms, --quads and --crease-angle shape the automatic layout: not "
        "with --layout, --grid or --tube");
  args.automatic.check();
  const bool search = automatic && !args.automatic.targetRms.empty();
  if (search) args.automatic.target();  // a bad target is a usage error before any work
  if (!args.tube.empty() && args.tube[1] < 3)
    throw RebuildUsageError(
        "--tube: a tube needs at least 3 sectors round it (two would join along both sides)");
  if (args.fitShape && args.iterations == 0)
    throw RebuildUsageError(
        "--fit-shape with --iterations 0 would fit nothing: the shape is fitted in up to "
        "--iterations iterations after the vertices");
  const SliceOptions slice = sliceOptions();

  auto t0 = Clock::now();
  Mesh mesh = readTriangles(meshPath);
  VertexFrameModel layout;
  if (!args.layoutPath.empty()) {
    layout = quadLayout(readPolygonMesh(args.layoutPath), args.layoutPath);
  } else if (automatic) {
    if (!search) layout = automaticLayout(args.automatic, mesh, meshPath, quiet);
  } else if (!args.grid.empty()) {
    layout = gridLayout(mesh, {args.grid[0], args.grid[1]}, meshPath);
  } else {
    // The tube is fitted to, and measured against, the part between its end planes.
    TubeLayout tube = tubeLayout(mesh, {args.tube[0], args.tube[1], slice}, meshPath);
    layout = std::move(tube.model);
    mesh = std::move(tube.part);
    if (!partPath.empty()) writeMesh(mesh, partPath);
  }
  layout.name = std::filesystem::path(meshPath).stem().string() + " (vertex frames)";
  const double layoutMs = msSince(t0);

  FitOptions options;
  options.maxIterations = args.iterations;
  options.tolerance = args.tolerance;
  options.smoothness = args.smoothness;
  options.samplesPerSide = args.samples;
  options.preventFolds = args.preventFolds;
  options.conformalWeight = args.conformalWeight;
  options.fitShape = args.fitShape;
  ProgressBar bar(args.fitShape ? 2 * args.iterations : args.iterations, !quiet);
  options.onIteration = [&](const FitIteration& it) {
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
  t0 = Clock::now();
  const FitResult fitted = namingMesh(meshPath, "", [&] {
    return search ? searchAutomaticLayout(args.automatic, mesh, meshPath, options, resolution,
                                          quiet, layout)
                  : fitVertexFrames(layout, mesh, options);
  });
  const double fitMs = msSince(t0);

  writeFileAtomically(outPath, serializeVertexFrameModel(fitted.model));
  if (quiet) return 0;
  const VertexFrameSurface surface = solve(fitted.model);
  const Mesh tessellated = tessellate(surface, {resolution});
  const MeshDistance d = meshDistance(tessellated, mesh);
  const NormalDeviation normals = normalDeviation(tessellated, mesh);
  fmt::print("{}: {}\n", outPath, fitted.stopReason);
  fmt::print("{}: {}, {}, {} -> {} (layout {:.1f} ms, fit {:.1f} ms)\n", layout.name,
             count(fitted.model.frames.size(), "frame"),
             count(fitted.model.vertices.size(), "vertex"),
             count(fitted.iterations.size() - 1, "iteration"), outPath, layoutMs, fitMs);
  fmt::print("{} at resolution {}; {}{}: {}, bounding-box diagonal {:.6g}\n", outPath, resolution,
             meshPath, args.tube.empty() ? "" : " (the part between the end planes)",
             count(mesh.triangleCount(), "triangle"), d.diagonal);
  printDistances(d);
  printNormals(normals);
  fmt::print("storage        {} bytes (numbers to six significant digits)\n",
             storageBytes(fitted.model));
  if (automatic) printStorageAgainstMesh(fitted.model, mesh);
  return 0;
}

}  // namespace pdesurf::cli
