// Shape edits of spectral, cross-section and B-spline PDE models (session.hpp: ShapeEdit):
// each edit's effect on the solved surface, its refusals (the reason, the session unchanged),
// and undo back to the same bytes; the spine edit against `pdesurf spine`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/cli_run.hpp"
#include "support/examples.hpp"

namespace pdesurf {
namespace {

using Json = nlohmann::json;

/// Surfaces through their conditions meet them to rounding; the solves are QR of modest
/// condition number (docs/spectral.md), so 1e-9 of the model's size is far above rounding
/// and far below any real miss.
constexpr double kThrough = 1e-9;

std::string docFile(const std::string& name) {
  return (std::filesystem::path(PDESURF_SOURCE_DIR) / "docs" / "model-format" / name).string();
}

ModelSession open(const std::string& path) { return ModelSession(loadModel(path), path); }

/// Parses and applies a shape edit.
void edit(ModelSession& s, const std::string& json) {
  const GroupedShapeEdit e = parseShapeEdit(json, s.model());
  s.apply(e.edit, e.group);
}

/// The refusal's problem and path ("" when the edit went through), the session checked to be
/// unchanged by it.
std::string refusal(ModelSession& s, const std::string& json, std::string* path = nullptr) {
  const std::string before = serializeModel(s.model());
  const auto revision = s.revision();
  const auto undo = s.undoDepth();
  try {
    edit(s, json);
  } catch (const ModelError& e) {
    EXPECT_EQ(serializeModel(s.model()), before) << json;
    EXPECT_EQ(s.revision(), revision);
    EXPECT_EQ(s.undoDepth(), undo);
    if (path) *path = e.jsonPath();
    return e.problem();
  }
  return "";
}

const SpectralPatch& patchOf(ModelSession& s) { return *s.solved().spectral()->patch; }

/// A spectral tube of order 4 (Ugail N = 2) through 4 circles given as 12 points each: well
/// conditioned, so a moved point stays a bounded edit (the shell's order 12 through 12 curves
/// is not: locality_test.cpp).
std::string pointTube() {
  Json doc = {{"type", "spectral"}, {"operator", "ugail"}, {"N", 2}, {"modes", 4}};
  doc["conditions"] = Json::array();
  for (int i = 0; i < 4; ++i) {
    Json points = Json::array();
    const double r = 1.0 - 0.15 * i;
    for (int j = 0; j < 12; ++j) {
      const double t = 2.0 * std::numbers::pi * j / 12;
      points.push_back({r * std::cos(t), r * std::sin(t), i / 3.0});
    }
    doc["conditions"].push_back({{"u", i / 3.0}, {"curve", {{"points", points}}}});
  }
  return doc.dump();
}

TEST(ShapeEdits, MovedCurvePointsAreInterpolatedAndUndoRestoresTheBytes) {
  ModelSession s(parseModel(pointTube(), "tube"), "tube");
  const std::string original = serializeModel(s.model());
  const auto& condition = s.model().get<SpectralModel>().conditions[3];
  const Vec3 was = std::get<SampledCurve>(condition.curve).points[5];
  const Vec3 to = was + Vec3(0.02, -0.01, 0.03);
  edit(
      s,
      fmt::format(
          R"({{"op":"move-curve-points","curve":3,"points":[5],"positions":[[{},{},{}]],"group":"drag"}})",
          to.x(), to.y(), to.z()));
  const SpectralPatch::ResolvedCondition& resolved = patchOf(s).conditions()[3];
  EXPECT_EQ(resolved.points[5], to);
  EXPECT_LT((patchOf(s).position(resolved.u, resolved.v[5]) - to).norm(), kThrough);
  // A second step of the same drag: still one undo step.
  edit(
      s,
      fmt::format(
          R"({{"op":"move-curve-points","curve":3,"points":[5],"positions":[[{},{},{}]],"group":"drag"}})",
          to.x(), to.y(), to.z() + 0.01));
  EXPECT_EQ(s.undoDepth(), 1u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
}

TEST(ShapeEdits, FourierCurvesTurnWholeAndDerivativeCurvesTakeTheLinearPartOnly) {
  ModelSession s = open(docFile("tube.json"));
  const std::string original = serializeModel(s.model());
  edit(s, R"({"op":"transform-curve","curve":2,"translate":[0.5,0,0.25]})");
  const auto& m = s.model().get<SpectralModel>();
  const auto& moved = std::get<FourierCurve>(m.conditions[2].curve);
  EXPECT_EQ(moved.a0, Vec3(0.5, 0, 1.25));
  EXPECT_EQ(moved.a[0], Vec3(0.5, 0, 0));  // modes are directions: a translation leaves them
  // The surface ends on the moved circle: S(1, v) = a0 + a1 cos v + b1 sin v.
  for (double v : {0.0, 1.0, 2.5})
    EXPECT_LT((patchOf(s).position(1.0, v) - moved.evaluate(v)).norm(), kThrough);
  // A derivative condition's curve is a vector: turned, never translated.
  edit(
      s,
      R"({"op":"transform-curve","curve":1,"rotate":{"axis":[0,1,0],"degrees":90},"translate":[5,5,5]})");
  const auto& d = std::get<FourierCurve>(s.model().get<SpectralModel>().conditions[1].curve);
  EXPECT_LT((d.a0 - Vec3(2, 0, 0)).norm(), 1e-15);
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
}

TEST(ShapeEdits, ACurveDragFromTheGroupStartIsAbsoluteAndOneUndoStep) {
  ModelSession s = open(docFile("tube.json"));
  const std::string original = serializeModel(s.model());
  const auto top = [&] {
    return std::get<FourierCurve>(s.model().get<SpectralModel>().conditions[2].curve);
  };
  // Three steps of one drag, each the whole offset so far: the last one counts alone.
  for (const char* dx : {"0.1", "0.45", "0.3"})
    edit(
        s,
        fmt::format(
            R"({{"op":"transform-curve","curve":2,"translate":[{},0,0],"from":"group-start","group":"drag"}})",
            dx));
  EXPECT_EQ(top().a0, Vec3(0.3, 0, 1));  // 0 + 0.3 exactly: not the sum of the steps
  EXPECT_EQ(top().a[0], Vec3(0.5, 0, 0));
  EXPECT_EQ(s.undoDepth(), 1u);
  // A turn by 90 degrees about z through a0, from the same start: the coefficient vectors
  // turn (a1 = (0.5, 0, 0) -> (0, 0.5, 0), b1 = (0, 0.5, 0) -> (-0.5, 0, 0)), a0 stays.
  edit(
      s,
      R"({"op":"transform-curve","curve":2,"rotate":{"axis":[0,0,1],"degrees":90},"center":[0,0,1],"from":"group-start","group":"drag"})");
  EXPECT_LT((top().a0 - Vec3(0, 0, 1)).norm(), 1e-15);
  EXPECT_LT((top().a[0] - Vec3(0, 0.5, 0)).norm(), 1e-15);
  EXPECT_LT((top().b[0] - Vec3(-0.5, 0, 0)).norm(), 1e-15);
  // After the group ends, a step of a new group starts from the model as it is now.
  s.endGroup();
  edit(
      s,
      R"({"op":"transform-curve","curve":2,"translate":[0,0,0.5],"from":"group-start","group":"next"})");
  EXPECT_LT((top().a0 - Vec3(0, 0, 1.5)).norm(), 1e-15);
  EXPECT_LT((top().a[0] - Vec3(0, 0.5, 0)).norm(), 1e-15);
  EXPECT_EQ(s.undoDepth(), 2u);
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
  // The same on a blend's B-spline curve (its corners stay shared with the other curves).
  ModelSession blend = open(testing::example("bspline-blend.json"));
  const auto uMin = [&] { return blend.model().get<BSplinePdeModel>().curves[0].points; };
  const auto before = uMin();
  for (const char* dz : {"0.2", "0.1"})
    edit(
        blend,
        fmt::format(
            R"({{"op":"transform-curve","curve":"uMin","translate":[0,0,{}],"from":"group-start","group":"g"}})",
            dz));
  for (std::size_t k = 0; k < before.size(); ++k) EXPECT_EQ(uMin()[k], before[k] + Vec3(0, 0, 0.1));
  EXPECT_EQ(blend.model().get<BSplinePdeModel>().curves[2].points.front(), uMin().front());
}

TEST(ShapeEdits, CurveTransformsAreRefusedWithThePathOfWhatIsWrong) {
  ModelSession s = open(docFile("tube.json"));
  std::string path;
  // Curves that are not there.
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":4,"translate":[1,0,0]})", &path)
                .find("condition 4 is out of range"),
            std::string::npos);
  EXPECT_EQ(path, "$.curve");
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":-1,"translate":[1,0,0]})", &path), "");
  EXPECT_EQ(path, "$.curve");
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":"uMin","translate":[1,0,0]})", &path)
                .find("numbered"),
            std::string::npos);
  EXPECT_EQ(path, "$.curve");
  // Numbers that are not finite, or no transform at all.
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":0,"translate":[1,1e999,0]})", &path)
                .find("not finite"),
            std::string::npos);
  EXPECT_EQ(path, "$.translate[1]");
  EXPECT_NE(
      refusal(s, R"({"op":"transform-curve","curve":0,"scale":-1e999})", &path).find("not finite"),
      std::string::npos);
  EXPECT_EQ(path, "$.scale");
  EXPECT_NE(
      refusal(s, R"({"op":"transform-curve","curve":0,"rotate":{"axis":[0,0,0],"degrees":90}})",
              &path),
      "");
  EXPECT_EQ(path.rfind("$.rotate", 0), 0u) << path;
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":0,"translate":[1,0]})", &path), "");
  EXPECT_EQ(path.rfind("$.translate", 0), 0u) << path;
  // "from" names a group's start: it needs the group, and knows no other start.
  EXPECT_NE(
      refusal(s, R"({"op":"transform-curve","curve":0,"translate":[1,0,0],"from":"group-start"})",
              &path)
          .find("needs the edit's \"group\""),
      std::string::npos);
  EXPECT_EQ(path, "$.from");
  EXPECT_NE(
      refusal(
          s, R"({"op":"transform-curve","curve":0,"translate":[1,0,0],"from":"start","group":"g"})",
          &path)
          .find("unknown value \"start\""),
      std::string::npos);
  EXPECT_EQ(path, "$.from");
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":0,"translate":[1,0,0],"by":2})", &path)
                .find("unknown field \"by\""),
            std::string::npos);
  // A B-spline PDE model's curves are named, and only its form's names.
  ModelSession dome = open(testing::example("bspline-dome.json"));
  EXPECT_NE(refusal(dome, R"({"op":"transform-curve","curve":"start","scale":2})", &path)
                .find("no curve \"start\""),
            std::string::npos);
  EXPECT_EQ(path, "$.curve");
}

TEST(ShapeEdits, AFourierCurvesCoefficientsAreSetAndTheSurfaceLeavesAlongThem) {
  ModelSession s = open(docFile("tube.json"));
  const std::string original = serializeModel(s.model());
  // The tube leaves its bottom circle straight up, x_u(0, v) = (0, 0, 2): tilted toward x.
  edit(s, R"({"op":"set-fourier","curve":1,"a0":[0.5,0,2],"group":"drag"})");
  edit(s, R"({"op":"set-fourier","curve":1,"a0":[0.75,0,2],"group":"drag"})");
  const auto& d = std::get<FourierCurve>(s.model().get<SpectralModel>().conditions[1].curve);
  EXPECT_EQ(d.a0, Vec3(0.75, 0, 2));
  EXPECT_TRUE(d.a.empty());
  for (double v : {0.0, 1.0, 2.5})
    EXPECT_LT((patchOf(s).derivative(0.0, v, 1, 0) - d.evaluate(v)).norm(), kThrough);
  EXPECT_EQ(s.undoDepth(), 1u);  // one drag
  // The lists replace the curve's whole.
  edit(s, R"({"op":"set-fourier","curve":2,"a":[[0.25,0,0],[0,0,0.1]],"b":[[0,0.25,0]]})");
  const auto& top = std::get<FourierCurve>(s.model().get<SpectralModel>().conditions[2].curve);
  EXPECT_EQ(top.a.size(), 2u);
  EXPECT_EQ(top.a[1], Vec3(0, 0, 0.1));
  EXPECT_EQ(top.b, (std::vector<Vec3>{Vec3(0, 0.25, 0), Vec3::Zero()}));  // as the file pads
  EXPECT_EQ(top.a0, Vec3(0, 0, 1));
  std::string path;
  EXPECT_NE(refusal(s, R"({"op":"set-fourier","curve":1})", &path).find("needs"),
            std::string::npos);
  EXPECT_EQ(path, "$");
  EXPECT_NE(
      refusal(s, R"({"op":"set-fourier","curve":7,"a0":[0,0,0]})", &path).find("out of range"),
      std::string::npos);
  EXPECT_EQ(path, "$.curve");
  EXPECT_NE(
      refusal(s, R"({"op":"set-fourier","curve":1,"a0":[0,1e999,0]})", &path).find("not finite"),
      std::string::npos);
  EXPECT_EQ(path, "$.a0[1]");
  EXPECT_NE(refusal(s, R"({"op":"set-fourier","curve":1,"a":[[0,0,0],[1,2]]})", &path), "");
  EXPECT_EQ(path.rfind("$.a[1]", 0), 0u) << path;
  EXPECT_NE(refusal(s, R"({"op":"set-fourier","curve":1,"a0":[0,0,0],"v":[1]})", &path)
                .find("unknown field \"v\""),
            std::string::npos);
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
  // A curve of points has no coefficients to set.
  ModelSession shell = open(testing::example("shell.json"));
  EXPECT_NE(refusal(shell, R"({"op":"set-fourier","curve":0,"a0":[0,0,0]})", &path)
                .find("not given by Fourier coefficients"),
            std::string::npos);
  EXPECT_EQ(path, "$.curve");
  ModelSession dome = open(testing::example("bspline-dome.json"));
  EXPECT_NE(refusal(dome, R"({"op":"set-fourier","curve":"uMin","a0":[0,0,0]})", &path), "");
  EXPECT_EQ(path, "$.curve");
}

TEST(ShapeEdits, OperatorChangesSolveOrAreRefusedWithTheReason) {
  ModelSession s = open(docFile("tube.json"));
  edit(s, R"({"op":"set-operator","a":3,"modes":2})");
  EXPECT_EQ(patchOf(s).op().a, 3.0);
  EXPECT_EQ(patchOf(s).modes(), 2u);
  std::string path;
  // Order 6 needs 6 conditions; the tube has 4.
  EXPECT_NE(refusal(s, R"({"op":"set-operator","N":3})", &path).find("6"), std::string::npos);
  EXPECT_EQ(refusal(s, R"({"op":"set-operator","operator":"fu","a":1})"),
            refusal(s, R"({"op":"set-operator","N":3})"));
  EXPECT_NE(refusal(s, R"({"op":"set-operator","a":-1})", &path), "");
  EXPECT_EQ(path, "$.a");
  EXPECT_NE(refusal(s, R"({"op":"set-operator"})", &path).find("needs"), std::string::npos);
  EXPECT_NE(refusal(s, R"({"op":"set-operator","N":2,"size":1})", &path).find("unknown field"),
            std::string::npos);
  // A chain takes a, modes and remainder only.
  ModelSession chain = open(docFile("column.json"));
  EXPECT_NE(refusal(chain, R"({"op":"set-operator","N":3})", &path).find("unknown field \"N\""),
            std::string::npos);
  edit(chain, R"({"op":"set-operator","a":2})");
  EXPECT_EQ(chain.model().get<CrossSectionModel>().options.a, 2.0);
}

TEST(ShapeEdits, SpineEditsAreTheFilesFieldAndMatchTheSpineCommand) {
  ModelSession s = open(docFile("tube.json"));
  constexpr std::uint32_t kHandles = 9;
  const SpineHandles before = spineHandles(s.solved(), kHandles);
  ASSERT_EQ(before.u.size(), kHandles);
  // Drag handle 4 (u = 0.5) sideways; the others are held where they are.
  Json moved = Json::array();
  for (std::uint32_t i = 0; i < kHandles; ++i) {
    const Vec3 p = before.points[i] + (i == 4 ? Vec3(0.3, 0, 0) : Vec3::Zero());
    moved.push_back({p.x(), p.y(), p.z()});
  }
  const Json spine = Json::array({{{"u", before.u}, {"moved", moved}}});
  edit(s, Json{{"op", "set-spine"}, {"spine", spine}}.dump());
  const SpineHandles after = spineHandles(s.solved(), kHandles);
  for (std::uint32_t i = 0; i < kHandles; ++i)
    EXPECT_LT(
        (after.points[i] - (before.points[i] + (i == 4 ? Vec3(0.3, 0, 0) : Vec3::Zero()))).norm(),
        kThrough)
        << i;
  // Saved, the file's "spine" field is the edit, and `pdesurf spine` reads the same spine.
  const Json file = Json::parse(serializeModel(s.model()));
  EXPECT_EQ(file.at("spine"), spine);
  testing::TempDir work, capture;
  { std::ofstream(work.file("edited.json")) << file.dump(); }
  const testing::CliRun run =
      testing::runCli(work, capture, fmt::format("spine edited.json --count {}", kHandles));
  ASSERT_EQ(run.code, 0) << run.err;
  const Json cli = Json::parse(run.out).at("patches").at(0);
  for (std::uint32_t i = 0; i < kHandles; ++i) {
    EXPECT_EQ(cli.at("u")[i].get<double>(), after.u[i]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(cli.at("points")[i][c].get<double>(), after.points[i][c]);
  }
  // Refused: u not increasing (the file's own check and path), a spine on a chain.
  std::string path;
  EXPECT_NE(
      refusal(s, R"({"op":"set-spine","spine":[{"u":[0.5,0.2],"moved":[[0,0,0],[0,0,1]]}]})", &path)
          .find("increase"),
      std::string::npos);
  EXPECT_EQ(path, "$.spine[0].u[1]");
  ModelSession chain = open(docFile("column.json"));
  EXPECT_NE(refusal(chain, R"({"op":"set-spine","spine":[]})", &path).find("spectral models"),
            std::string::npos);
  EXPECT_EQ(path, "$.op");
}

TEST(ShapeEdits, PointEditsAreRefusedOnFourierCurvesAndOutOfRange) {
  ModelSession s = open(docFile("tube.json"));
  std::string path;
  EXPECT_NE(refusal(s, R"({"op":"move-curve-points","curve":0,"points":[0],"positions":[[0,0,0]]})",
                    &path)
                .find("Fourier"),
            std::string::npos);
  EXPECT_EQ(path, "$.curve");
  EXPECT_NE(
      refusal(s, R"({"op":"transform-curve","curve":9,"scale":2})", &path).find("out of range"),
      std::string::npos);
  EXPECT_NE(refusal(s, R"({"op":"transform-curve","curve":0,"scale":0})", &path), "");
  EXPECT_EQ(path, "$.scale");
  EXPECT_NE(refusal(s, R"({"op":"spin"})", &path).find("unknown edit"), std::string::npos);
  ModelSession shell = open(testing::example("shell.json"));
  EXPECT_NE(
      refusal(shell, R"({"op":"move-curve-points","curve":0,"points":[48],"positions":[[0,0,0]]})",
              &path)
          .find("out of range"),
      std::string::npos);
  EXPECT_EQ(path, "$.points[0]");
  EXPECT_NE(
      refusal(
          shell,
          R"({"op":"move-curve-points","curve":0,"points":[1,1],"positions":[[0,0,0],[0,0,0]]})",
          &path)
          .find("twice"),
      std::string::npos);
  EXPECT_NE(
      refusal(shell, R"({"op":"move-curve-points","curve":0,"points":[1],"positions":[]})", &path),
      "");
  EXPECT_EQ(path, "$.positions");
}

TEST(ShapeEdits, SectionsAreAddedOnTheSurfaceAndRemoved) {
  ModelSession s = open(docFile("column.json"));
  const std::string original = serializeModel(s.model());
  const SolvedModel before = s.solved();
  edit(s, R"({"op":"add-section","index":2})");
  const auto& m = s.model().get<CrossSectionModel>();
  ASSERT_EQ(m.curves.size(), 5u);
  // The new section lies on the old surface half way along the chain, and the new chain
  // passes through it and through every old section.
  const auto& added = std::get<SampledCurve>(m.curves[2]);
  EXPECT_GE(added.points.size(), kMinSampledSection);
  const CrossSectionChain& chain = *s.solved().spectral()->chain;
  ASSERT_EQ(chain.curveU.size(), 5u);
  const double mid = chain.curveU[2];
  const auto& patch = chain.patches[2];
  EXPECT_EQ(patch.firstCurve, 2u);
  for (std::size_t j = 0; j < added.points.size(); ++j)
    EXPECT_LT((patch.patch.position(0.0, added.v[j]) - added.points[j]).norm(), kThrough);
  EXPECT_GT(mid, chain.curveU[1]);
  EXPECT_NE(refusal(s, R"({"op":"add-section","index":0})").find("needs its"), std::string::npos);
  edit(s, R"({"op":"remove-section","index":2})");
  EXPECT_EQ(serializeModel(s.model()), original);  // removing it gives the same file back
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
  // A section turned whole; the c2 chain cannot lose a section below 4.
  edit(s, R"({"op":"transform-curve","curve":0,"scale":1.5,"center":[0,0,0]})");
  EXPECT_EQ(std::get<SampledCurve>(s.model().get<CrossSectionModel>().curves[0]).points[0],
            Vec3(1.5, 0, 0));
  std::string path;
  Json doc = Json::parse(serializeModel(open(docFile("column.json")).model()));
  doc["method"] = "c2";
  for (const char* global : {"spacing", "ends", "u"}) doc.erase(global);
  ModelSession c2(parseModel(doc.dump(), "c2"), "c2");
  EXPECT_NE(refusal(c2, R"({"op":"remove-section","index":1})", &path).find("at least 4"),
            std::string::npos);
  EXPECT_EQ(path, "$.curves");
}

TEST(ShapeEdits, GivenControlPointsMoveAndTheInnerOnesAreSolvedAgain) {
  ModelSession s = open(docFile("tray.json"));
  const std::string original = serializeModel(s.model());
  const auto innerBefore = s.solved();
  edit(s, R"({"op":"move-control-points","points":[[1,2],[4,4]],"positions":[[1,2,0.4],[4,4,1]]})");
  const SolvedBSplinePde& solved = s.solved().surface().get<SolvedBSplinePde>();
  const ControlNet& net = solved.pieces.at(0).net();
  EXPECT_EQ(net(1, 2), Vec3(1, 2, 0.4));
  EXPECT_EQ(net(4, 4), Vec3(4, 4, 1));
  const ControlNet& old = innerBefore.surface().get<SolvedBSplinePde>().pieces.at(0).net();
  EXPECT_GT((net(2, 2) - old(2, 2)).norm(), 1e-3);  // the inner points followed
  std::string path;
  EXPECT_NE(
      refusal(s, R"({"op":"move-control-points","points":[[2,2]],"positions":[[0,0,0]]})", &path)
          .find("inner point"),
      std::string::npos);
  EXPECT_EQ(path, "$.points[0]");
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), original);
}

TEST(ShapeEdits, BoundaryAndBlendCurvesMove) {
  for (const char* file : {"bspline-dome.json", "bspline-blend.json", "bspline-tube.json"}) {
    SCOPED_TRACE(file);
    ModelSession s = open(testing::example(file));
    const std::string original = serializeModel(s.model());
    const auto& m = s.model().get<BSplinePdeModel>();
    const char* name = m.form == BSplinePdeModel::Form::ClosedBlend ? "start" : "vMin";
    // An inner point of the curve (its ends are corners other curves share).
    edit(s, fmt::format(R"({{"op":"transform-curve","curve":"{}","translate":[0,0,0.1]}})", name));
    EXPECT_NE(serializeModel(s.model()), original);
    std::string path;
    EXPECT_NE(
        refusal(s,
                R"({"op":"move-curve-points","curve":"middle","points":[0],"positions":[[0,0,0]]})",
                &path)
            .find("no curve"),
        std::string::npos);
    EXPECT_EQ(path, "$.curve");
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(serializeModel(s.model()), original);
  }
}

TEST(ShapeEdits, ABlendsCornerMovesInEveryCurveThatSharesIt) {
  ModelSession s = open(testing::example("bspline-blend.json"));
  const auto curves = [&] { return s.model().get<BSplinePdeModel>().curves; };
  const Vec3 corner = curves()[0].points.front();
  const Vec3 to = corner + Vec3(0, 0, 0.1);
  std::size_t sharing = 0;  // curve ends at that corner
  for (const BSplineCurve& c : curves())
    sharing += (c.points.front() == corner) + (c.points.back() == corner);
  ASSERT_EQ(sharing, 2u);  // uMin's start and the curve that meets it there
  edit(s,
       fmt::format(
           R"({{"op":"move-curve-points","curve":"uMin","points":[0],"positions":[[{},{},{}]]}})",
           to.x(), to.y(), to.z()));
  std::size_t moved = 0;
  for (const BSplineCurve& c : curves()) {
    EXPECT_NE(c.points.front(), corner);
    EXPECT_NE(c.points.back(), corner);
    moved += (c.points.front() == to) + (c.points.back() == to);
  }
  EXPECT_EQ(moved, 2u);
  // The solved blend passes through the moved corner.
  const SolvedBSplinePde& solved = s.solved().surface().get<SolvedBSplinePde>();
  double nearest = 1e300;
  for (const BSplineSurface& piece : solved.pieces)
    for (double u : {0.0, 1.0})
      for (double v : {0.0, 1.0}) nearest = std::min(nearest, (piece.position(u, v) - to).norm());
  EXPECT_LT(nearest, kThrough);
}

}  // namespace
}  // namespace pdesurf

namespace pdesurf {
namespace {

TEST(ShapeEdits, AFalloffBendsAClosedCurveRoundTheMovedPointFromTheDragsStart) {
  ModelSession s = open(testing::example("vase-sections.json"));
  const auto section = [&] {
    return std::get<SampledCurve>(s.model().get<CrossSectionModel>().curves[6]).points;
  };
  const std::vector<Vec3> was = section();
  const std::size_t n = was.size();
  const auto step = [&](const Vec3& offset) {
    const Vec3 to = was[0] + offset;
    edit(s, fmt::format(R"({{"op":"move-curve-points","curve":6,"points":[0],)"
                        R"("positions":[[{},{},{}]],"falloff":0.125,"group":"drag"}})",
                        to.x(), to.y(), to.z()));
  };
  // Two steps of one drag: the second replaces the first (the bump from the drag's start).
  step(Vec3(0.05, 0, 0.02));
  step(Vec3(0.02, 0.01, 0));
  const std::vector<Vec3> now = section();
  EXPECT_EQ(now[0], was[0] + Vec3(0.02, 0.01, 0));
  double length = 0.0;
  for (std::size_t j = 0; j < n; ++j) length += (was[(j + 1) % n] - was[j]).norm();
  double along = 0.0;  // arc length from point 0, forwards
  for (std::size_t j = 1; j < n; ++j) {
    along += (was[j] - was[j - 1]).norm();
    const double t = std::min(along, length - along) / (0.125 * length);
    const double w = t < 1.0 ? std::pow(1.0 - t * t, 3) : 0.0;
    EXPECT_LT((now[j] - (was[j] + w * Vec3(0.02, 0.01, 0))).norm(), kThrough) << "point " << j;
  }
  EXPECT_EQ(s.undoDepth(), 1u);
  // A falloff bends closed curves only; the method of a chain is set like its operator.
  ModelSession dome = open(testing::example("bspline-dome.json"));
  std::string path;
  const std::string openCurve = R"({"op":"move-curve-points","curve":"vMin","points":[3],)"
                                R"("positions":[[0,0,0]],"falloff":0.1})";
  EXPECT_NE(refusal(dome, openCurve, &path).find("not a closed curve"), std::string::npos);
  EXPECT_EQ(path, "$.falloff");
  const std::string wide = R"({"op":"move-curve-points","curve":6,"points":[0],)"
                           R"("positions":[[0,0,0]],"falloff":0.6})";
  EXPECT_NE(refusal(s, wide, &path), "");
  EXPECT_EQ(path, "$.falloff");
  EXPECT_EQ(dragAdvice(s.model()), "");
  edit(s, R"({"op":"set-operator","method":"c2"})");
  EXPECT_NE(dragAdvice(s.model()).find("\"c2\""), std::string::npos);
}

}  // namespace
}  // namespace pdesurf
