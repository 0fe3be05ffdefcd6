// The library's rebuild() (include/pdesurf/mesh_rebuild.hpp): its option checks, and its
// report against the steps it is made of, measured independently.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "support/cgal_data.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

/// The message of the RebuildOptionError `options` raise, and its option key.
std::pair<std::string, std::string> refusal(const RebuildOptions& options,
                                            RebuildOptionStyle style) {
  try {
    checkRebuildOptions(options, style);
  } catch (const RebuildOptionError& e) {
    return {e.option(), e.what()};
  }
  return {"", "accepted"};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(RebuildOptions, DefaultsPassAndEachConflictIsNamedInTheFrontEndsSpelling) {
  EXPECT_NO_THROW(checkRebuildOptions({}));
  RebuildOptions two;
  two.grid = {{2, 2}};
  two.tube = {{2, 4}};
  const auto [key, cli] = refusal(two, RebuildOptionStyle::Cli);
  EXPECT_EQ(key, "layout");
  EXPECT_TRUE(contains(cli, "give one of --layout QUADS, --grid U V and --tube RINGS SECTORS"))
      << cli;
  const std::string python = refusal(two, RebuildOptionStyle::Python).second;
  EXPECT_TRUE(contains(python, "layout=QUADS_FILE, grid=(U, V) and tube=(RINGS, SECTORS)"))
      << python;

  RebuildOptions automatic;
  automatic.grid = {{2, 2}};
  automatic.frames = 10;
  EXPECT_TRUE(contains(refusal(automatic, RebuildOptionStyle::Cli).second,
                       "shape the automatic layout: not with --layout, --grid or --tube"));
  RebuildOptions both;
  both.frames = 10;
  both.targetRms = 0.01;
  EXPECT_EQ(refusal(both, RebuildOptionStyle::Python).second,
            "frames and target_rms both choose the number of frames: give one of them");

  RebuildOptions normals;
  normals.targetRms = 0.01;
  normals.maxNormalDeviation = std::nan("");
  EXPECT_EQ(refusal(normals, RebuildOptionStyle::Python).second,
            "max_normal_deviation nan: must be in [0, 180]");
  normals.targetRms.reset();
  normals.maxNormalDeviation = 5.0;
  EXPECT_EQ(refusal(normals, RebuildOptionStyle::Python).first, "max_normal_deviation");

  RebuildOptions weight;
  weight.fit.conformalWeight = -1.0;
  EXPECT_EQ(refusal(weight, RebuildOptionStyle::Python).first, "fold_weight");
  RebuildOptions alignment;
  alignment.normalWeight = 2.0;
  EXPECT_EQ(refusal(alignment, RebuildOptionStyle::Cli).first, "normal_weight");
  RebuildOptions tube;
  tube.tube = {{2, 2}};
  EXPECT_TRUE(contains(refusal(tube, RebuildOptionStyle::Cli).second, "at least 3 sectors"));
  RebuildOptions shape;
  shape.fit.fitShape = true;
  shape.fit.maxIterations = 0;
  EXPECT_EQ(refusal(shape, RebuildOptionStyle::Cli).first, "fit_shape");
  RebuildOptions samples;
  samples.fit.samplesPerSide = 2;
  EXPECT_EQ(refusal(samples, RebuildOptionStyle::Cli).first, "fit_samples");
  RebuildOptions range;
  range.slice.range = {{1.0, 0.0}};
  EXPECT_EQ(refusal(range, RebuildOptionStyle::Cli).first, "range");
}

TEST(RebuildOptions, CrossSectionsCheckTheirChainAndRefuseTheShapeFit) {
  RebuildOptions o;
  o.kind = RebuildKind::CrossSections;
  o.grid = {{2, 2}};  // vertex frames' options are ignored...
  o.tube = {{2, 4}};
  EXPECT_NO_THROW(checkRebuildOptions(o));
  o.fit.fitShape = true;  // ...but for the one that says it is refused
  EXPECT_TRUE(contains(refusal(o, RebuildOptionStyle::Cli).second, "it needs --as vertex-frames"));
  o.fit.fitShape = false;
  o.modes = 40;
  o.points = 64;
  EXPECT_EQ(refusal(o, RebuildOptionStyle::Cli).second,
            "--points 64 cannot determine --modes 40: give at least 81 points");
  o.points = 128;
  o.a = 0.0;
  EXPECT_EQ(refusal(o, RebuildOptionStyle::Python).first, "a");
}

TEST(RebuildOptions, TargetRmsReadsFractionsAndPercentages) {
  EXPECT_DOUBLE_EQ(parseTargetRms("0.002"), 0.002);
  EXPECT_DOUBLE_EQ(parseTargetRms("0.2%"), 0.002);
  EXPECT_THROW(parseTargetRms("2x"), RebuildOptionError);
  EXPECT_THROW(parseTargetRms("100%"), RebuildOptionError);
  EXPECT_THROW(parseTargetRms("0"), RebuildOptionError);
  EXPECT_THROW(parseTargetRms(""), RebuildOptionError);
  try {
    parseTargetRms("2x", RebuildOptionStyle::Python);
  } catch (const RebuildOptionError& e) {
    EXPECT_TRUE(contains(e.what(), "target_rms 2x: not a number")) << e.what();
  }
}

/// RebuildOptions::normalWeight unset: the target search fits with kNormalWeight, a fixed
/// layout with none; given, both fit with it.
TEST(RebuildOptions, TheNormalWeightIsTheSearchsTermUnlessGiven) {
  RebuildOptions o;
  o.targetRms = 0.002;
  EXPECT_EQ(targetSearchOptions(o).fit.normalWeight, kNormalWeight);
  EXPECT_EQ(TargetSearchOptions{}.fit.normalWeight, kNormalWeight);
  o.normalWeight = 0.0;
  EXPECT_EQ(targetSearchOptions(o).fit.normalWeight, 0.0);
  o.normalWeight = 1e-3;
  EXPECT_EQ(targetSearchOptions(o).fit.normalWeight, 1e-3);

  // A grid: unset fits as ν = 0 does (the same vertices), and unlike ν = kNormalWeight.
  const Mesh mesh = readMesh(testing::cgalData("three_peaks.off"));
  RebuildOptions grid;
  grid.grid = {{3, 3}};
  grid.fit.maxIterations = 3;
  grid.measure = false;
  const auto vertices = [&](std::optional<double> weight) {
    RebuildOptions g = grid;
    g.normalWeight = weight;
    return rebuild(mesh, g).model.get<VertexFrameModel>().vertices;
  };
  const auto unset = vertices(std::nullopt);
  EXPECT_EQ(unset, vertices(0.0));
  EXPECT_NE(unset, vertices(kNormalWeight));
}

TEST(Rebuild, GridReportIsTheModelMeasuredAndMoreFramesFitCloser) {
  const std::string path = testing::cgalData("three_peaks.off");
  const Mesh mesh = readMesh(path);
  RebuildOptions o;
  o.source = path;
  o.fit.maxIterations = 4;
  o.samples = 20000;
  double previous[2] = {1.0, 1.0};
  std::size_t previousBytes = 0;
  for (std::uint32_t side : {2u, 4u}) {
    o.grid = {{side, side}};
    std::uint32_t calls = 0;
    RebuildProgress progress;
    progress.onIteration = [&](const FitIteration& it) { EXPECT_EQ(it.iteration, calls++); };
    const RebuildResult r = rebuild(mesh, o, progress);
    const auto& model = r.model.get<VertexFrameModel>();
    const RebuildReport& report = r.report;
    EXPECT_EQ(model.name, "three_peaks (vertex frames)");
    EXPECT_EQ(report.frames, side * side);
    EXPECT_EQ(calls, report.iterations.size());
    EXPECT_FALSE(report.stopReason.empty());
    EXPECT_EQ(report.storageBytes, storageBytes(model));
    EXPECT_EQ(report.referenceStorageBytes, storageBytes(mesh));
    EXPECT_FALSE(r.part.has_value());
    EXPECT_FALSE(report.automatic.has_value());
    // The report's distances are the model's tessellation measured as compare measures it.
    ASSERT_TRUE(report.measured);
    DistanceOptions distance;
    distance.samples = o.samples;
    const MeshDistance d = meshDistance(tessellate(solve(model), {o.resolution}), mesh, distance);
    EXPECT_EQ(report.distance.aToB.rms, d.aToB.rms);
    EXPECT_EQ(report.distance.bToA.rms, d.bToA.rms);
    // More frames: closer both ways, more storage.
    EXPECT_LT(report.distance.aToB.rmsRelative, previous[0]);
    EXPECT_LT(report.distance.bToA.rmsRelative, previous[1]);
    EXPECT_GT(report.storageBytes, previousBytes);
    previous[0] = report.distance.aToB.rmsRelative;
    previous[1] = report.distance.bToA.rmsRelative;
    previousBytes = report.storageBytes;
  }
  o.measure = false;
  EXPECT_FALSE(rebuild(mesh, o).report.measured);
}

TEST(Rebuild, CrossSectionsAreTheSectionRebuildMeasuredAgainstItsPart) {
  const std::string path = testing::cgalData("elephant.off");
  const Mesh elephant = readMesh(path);
  RebuildOptions o;
  o.kind = RebuildKind::CrossSections;
  o.source = path;
  o.slice.axis = Axis::Y;
  o.slice.range = {{-0.45, -0.32}};
  o.slice.count = 12;
  o.slice.near = Vec3(0.117, -0.4, -0.045);
  o.samples = 5000;
  const RebuildResult r = rebuild(elephant, o);
  const auto& model = r.model.get<CrossSectionModel>();
  EXPECT_EQ(model.name, "elephant.off");
  EXPECT_EQ(r.report.sections, 12u);
  EXPECT_EQ(r.sections.size(), 12u);
  EXPECT_DOUBLE_EQ(r.report.from, -0.45);
  EXPECT_DOUBLE_EQ(r.report.to, -0.32);
  ASSERT_TRUE(r.part.has_value());
  EXPECT_EQ(r.report.referenceTriangles, r.part->triangleCount());
  EXPECT_EQ(r.report.storageBytes, storageBytes(model));
  // The leg at 12 sections: within 1 % of its diagonal both ways (0.2 % measured at 25).
  constexpr double kLegRms = 0.01;
  EXPECT_LT(r.report.distance.aToB.rmsRelative, kLegRms);
  EXPECT_LT(r.report.distance.bToA.rmsRelative, kLegRms);
  // The JSON `pdesurf rebuild --json` prints: its keys in order, the report's numbers.
  const std::string json = rebuildReportJson(r.report, o, "leg.json");
  EXPECT_EQ(json.rfind("{\n  \"mesh\": \"" + path +
                           "\",\n  \"as\": \"cross-sections\",\n  "
                           "\"output\": \"leg.json\",\n  \"axis\": \"y\",\n  \"sections\": 12,",
                       0),
            0u)
      << json;
  EXPECT_TRUE(contains(json, "\"model_storage_bytes\": " + std::to_string(r.report.storageBytes)))
      << json;
  EXPECT_FALSE(contains(json, "loft"));
}

/// The keys of a JSON object, in their order.
std::vector<std::string> keysOf(const nlohmann::ordered_json& j) {
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  return keys;
}

TEST(RebuildReportJson, DistancesAndNormalsAreWrittenByOneWriterInTheirOrder) {
  OneWayDistance d;
  d.samples = 7;
  d.rms = 0.5;
  d.max = 2.0;
  d.maxAt = Vec3(1, 2, 3);
  d.coverRadius = 0.25;
  // The rebuild's report: the six figures alone.
  const nlohmann::ordered_json figures = oneWayDistanceJson(d, DistanceFields::Figures);
  EXPECT_EQ(keysOf(figures), (std::vector<std::string>{"rms", "rms_relative", "mean",
                                                       "mean_relative", "max", "max_relative"}));
  EXPECT_EQ(figures["rms"], 0.5);
  // compare --json: the samples first, where the max is and the cover radius last.
  const nlohmann::ordered_json all = oneWayDistanceJson(d, DistanceFields::All);
  EXPECT_EQ(keysOf(all),
            (std::vector<std::string>{"samples", "rms", "rms_relative", "mean", "mean_relative",
                                      "max", "max_relative", "max_at", "cover_radius"}));
  EXPECT_EQ(all["samples"], 7);
  EXPECT_EQ(all["max_at"], nlohmann::ordered_json({1.0, 2.0, 3.0}));
  EXPECT_EQ(all["cover_radius"], 0.25);
  NormalDeviation n;
  n.foldedArea = 0.125;
  n.reversed = true;
  const nlohmann::ordered_json normals = normalDeviationJson(n);
  EXPECT_EQ(keysOf(normals), (std::vector<std::string>{"folded_area", "rms_degrees", "reversed"}));
  EXPECT_EQ(normals["folded_area"], 0.125);
  EXPECT_EQ(normals["reversed"], true);
}

TEST(Rebuild, ABadMeshThrowsTheLayoutsError) {
  RebuildOptions o;
  o.grid = {{2, 2}};
  o.source = "sphere";
  EXPECT_THROW(rebuild(testing::sphereMesh(1.0, 12, 8), o), LayoutError);  // no boundary
  o.grid.reset();
  o.tube = {{2, 2}};
  EXPECT_THROW(rebuild(testing::sphereMesh(1.0, 12, 8), o), RebuildOptionError);
}

}  // namespace
}  // namespace pdesurf
