// Whole-model transforms (include/pdesurf/transform.hpp): the solved transformed model
// against the transformed solved surface, by sampling both, for every model type.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"
#include "pdesurf/transform.hpp"
#include "support/examples.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

namespace fs = std::filesystem;

/// Vertex frames whose a1, a2 are alike in x, y, z: the transformed surface is the solve of
/// the transformed model up to the rounding of the solves (relative to the diagonal).
constexpr double kFramesTransformTolerance = 1e-12;
/// Spectral models: mode solves in extended precision, fits and remainders in double, and
/// the ill-conditioned high orders (Klein bottle, order 40) amplify rounding.
constexpr double kSpectralTransformTolerance = 1e-9;

/// A similarity with every part non-trivial: scale 1.7 about c, a turn of 37° about
/// (1, 2, 3) through c, a translation.
AffineMap similarity() {
  const Vec3 c(0.3, -0.2, 0.5);
  return AffineMap::translationBy({1.5, -2.0, 0.75}) *
         AffineMap::rotationAbout({1, 2, 3}, 37.0 * std::numbers::pi / 180.0, c) *
         AffineMap::scalingAbout(1.7, c);
}

/// A general invertible map (shear and unequal scales).
AffineMap general() {
  AffineMap m;
  m.linear << 1.2, 0.3, -0.1, 0.0, 0.8, 0.4, 0.2, -0.5, 1.5;
  m.translation = {-1, 2, 0.5};
  return m;
}

using testing::exampleFiles;

bool isotropic(const VertexFrameModel& m) {
  return std::all_of(m.frames.begin(), m.frames.end(), [](const Frame& f) {
    return f.a1.x() == f.a1.y() && f.a1.y() == f.a1.z() && f.a2.x() == f.a2.y() &&
           f.a2.y() == f.a2.z();
  });
}

/// max |map(S(u, v)) − S'(u, v)| over a 9 × 9 grid of every patch, relative to the diagonal
/// of the transformed surface.
double framesDeviation(const VertexFrameModel& model, const AffineMap& map) {
  const VertexFrameSurface s = solve(model), t = solve(transformModel(model, map));
  double worst = 0;
  for (std::size_t k = 0; k < s.patches.size(); ++k)
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const double u = i / 8.0, v = j / 8.0;
        worst = std::max(
            worst, (map.point(s.patches[k].position(u, v)) - t.patches[k].position(u, v)).norm());
      }
  return worst / surfaceBounds(t).diagonal();
}

/// The same for a spectral or cross-section model over every patch's shown range.
double spectralDeviation(const AnyModel& model, const AffineMap& map) {
  const auto solveAny = [](const AnyModel& m) {
    return m.is<SpectralModel>() ? solve(m.get<SpectralModel>(), "test")
                                 : solve(m.get<CrossSectionModel>(), "test");
  };
  const SolvedSpectral s = solveAny(model), t = solveAny(transformModel(model, map));
  EXPECT_EQ(s.patchCount(), t.patchCount());
  double worst = 0;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (std::size_t k = 0; k < s.patchCount(); ++k) {
    const auto [u0, u1] = s.range(k);
    const auto [w0, w1] = t.range(k);
    EXPECT_NEAR(u0, w0, 1e-12);
    EXPECT_NEAR(u1, w1, 1e-12);
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j < 24; ++j) {
        const double u = u0 + (u1 - u0) * i / 10.0, v = 2 * std::numbers::pi * j / 24;
        const Vec3 expected = map.point(s.patchAt(k).position(u, v));
        const Vec3 got = t.patchAt(k).position(u, v);
        worst = std::max(worst, (expected - got).norm());
        lo = lo.cwiseMin(got);
        hi = hi.cwiseMax(got);
      }
  }
  return worst / (hi - lo).norm();
}

// ---------------------------------------------------------------------------------------
// The map

TEST(AffineMap, PartsComposeInOrder) {
  const Vec3 c(1, 2, 3), x(2, 2, 3);
  // Scale 2 about c: (3, 2, 3); a quarter turn about z through c: (1, 4, 3); then + (0, 0, 1).
  const AffineMap m = AffineMap::translationBy({0, 0, 1}) *
                      AffineMap::rotationAbout({0, 0, 5}, std::numbers::pi / 2, c) *
                      AffineMap::scalingAbout(2, c);
  EXPECT_LT((m.point(x) - Vec3(1, 4, 4)).norm(), 1e-15);
  EXPECT_LT((m.vector(Vec3(1, 0, 0)) - Vec3(0, 2, 0)).norm(), 1e-15);
  EXPECT_TRUE(m.isSimilarity());
  EXPECT_FALSE(general().isSimilarity());
  EXPECT_NO_THROW(general().validate());
}

TEST(AffineMap, RefusesScalesAtOrBelowZeroAndNonFiniteParts) {
  const double inf = std::numeric_limits<double>::infinity();
  for (double s : {0.0, -1.0, -0.0, inf, std::nan("")})
    EXPECT_THROW(AffineMap::scalingAbout(s, Vec3::Zero()), InvalidArgument) << s;
  EXPECT_THROW(AffineMap::rotationAbout(Vec3::Zero(), 1.0, Vec3::Zero()), InvalidArgument);
  EXPECT_THROW(AffineMap::rotationAbout({0, 0, 1}, inf, Vec3::Zero()), InvalidArgument);
  EXPECT_THROW(AffineMap::rotationAbout({0, 0, 1}, 1.0, {0, inf, 0}), InvalidArgument);
  EXPECT_THROW(AffineMap::translationBy({std::nan(""), 0, 0}), InvalidArgument);
  AffineMap flat;
  flat.linear(2, 2) = 0;  // projects onto z = 0
  EXPECT_THROW(flat.validate(), InvalidArgument);
  // 1e-300 is a valid scale but its cube is 0: the map cannot be undone.
  EXPECT_THROW(AffineMap::scalingAbout(1e-300, Vec3::Zero()).validate(), InvalidArgument);
}

// ---------------------------------------------------------------------------------------
// Vertex frames

VertexFrameModel isotropicLattice(std::mt19937& rng) {
  testing::LatticeOptions o;
  o.rows = 3;
  o.cols = 4;
  o.noise = 0.2;
  o.randomOrientation = true;
  VertexFrameModel m = testing::latticeModel(o, rng);
  std::uniform_real_distribution<double> param(0.3, 3.0);
  for (Frame& f : m.frames) {
    f.a1 = Vec3::Constant(param(rng));
    f.a2 = Vec3::Constant(param(rng));
  }
  m.frames[1].forces.push_back({{0.5, -1, 3}, {0.2, 0.7, 0.1, 0.6}});
  m.frames[5].forces.push_back({{0, 0, -2}, {}});
  m.forces.push_back({{1, 1, 1}, {2, 3, 7}});
  return m;
}

TEST(TransformFrames, WithAlikeA1A2TheSurfaceIsTheTransformedSurface) {
  std::mt19937 rng(7);
  const VertexFrameModel m = isotropicLattice(rng);
  EXPECT_LT(framesDeviation(m, similarity()), kFramesTransformTolerance);
  EXPECT_LT(framesDeviation(m, general()), kFramesTransformTolerance);
}

TEST(TransformFrames, MovesVerticesAndTurnsForces) {
  std::mt19937 rng(3);
  const VertexFrameModel m = isotropicLattice(rng);
  const AffineMap map = similarity();
  const VertexFrameModel t = transformModel(m, map);
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    EXPECT_EQ(t.vertices[i], map.point(m.vertices[i]));
  EXPECT_EQ(t.frames[1].forces[0].f0, map.vector(m.frames[1].forces[0].f0));
  EXPECT_EQ(t.frames[1].forces[0].region.u1, 0.7);
  EXPECT_EQ(t.forces[0].f0, map.vector(m.forces[0].f0));
  EXPECT_EQ(t.forces[0].frames, m.forces[0].frames);
  EXPECT_EQ(t.frames[0].a1, m.frames[0].a1);
}

TEST(TransformFrames, WithPerComponentA1A2TheSurfaceIsTheSolveOfTheTransformedFrames) {
  std::mt19937 rng(11);
  testing::LatticeOptions o;
  o.randomParameters = true;  // a1, a2 differ per component
  o.noise = 0.1;
  const VertexFrameModel m = testing::latticeModel(o, rng);
  ASSERT_FALSE(isotropic(m));
  // A translation commutes with any of these PDEs; a turn does not, in general.
  EXPECT_LT(framesDeviation(m, AffineMap::translationBy({3, -1, 2})), kFramesTransformTolerance);
  EXPECT_GT(framesDeviation(m, similarity()), 1e-6);
  // What holds: the transformed model interpolates the transformed vertices, exactly C0.
  const VertexFrameModel t = transformModel(m, similarity());
  const VertexFrameSurface s = solve(t);
  constexpr double kParams[8][2] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5},
                                    {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};
  const double diag = surfaceBounds(s).diagonal();
  for (std::size_t k = 0; k < t.frames.size(); ++k)
    for (int i = 0; i < 8; ++i)
      EXPECT_LT((s.patches[k].position(kParams[i][0], kParams[i][1]) -
                 t.vertices[t.frames[k].vertices[i]])
                        .norm() /
                    diag,
                kFramesTransformTolerance);
  EXPECT_LT(measureC0Gap(s).maxGap / diag, kFramesTransformTolerance);
}

TEST(TransformFrames, EveryExampleIsTransformedAsDocumented) {
  for (const std::string& file : exampleFiles()) {
    const AnyModel any = loadModel(file);
    const auto* m = any.as<VertexFrameModel>();
    if (!m) continue;
    SCOPED_TRACE(file);
    EXPECT_NO_THROW(checkTransform(*m, similarity()));
    EXPECT_LT(framesDeviation(*m, AffineMap::translationBy({1, 2, 3})), kFramesTransformTolerance);
    if (isotropic(*m)) EXPECT_LT(framesDeviation(*m, similarity()), kFramesTransformTolerance);
  }
}

TEST(TransformFrames, ATurnedForceWithoutSolutionIsRefusedWithItsPath) {
  // a1.z/1 + a2.z/1 = 0: the force may push in x and y only.
  const VertexFrameModel m = parseVertexFrameModel(
      R"({"type": "vertex-frames", "vertices": [[0,0,0],[1,0,0],[2,0,0],[2,1,0],[2,2,0],[1,2,0],
          [0,2,0],[0,1,0]], "frames": [{"vertices": [0,1,2,3,4,5,6,7], "a1": [1, 1, 1],
          "a2": [1, 1, -1], "forces": [{"f0": [0.5, 0, 0]}]}]})",
      "m");
  EXPECT_NO_THROW(checkTransform(m, AffineMap::rotationAbout({0, 0, 1}, 0.3, Vec3::Zero())));
  try {
    checkTransform(m, AffineMap::rotationAbout({0, 1, 0}, 0.3, Vec3::Zero()));
    FAIL() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.file(), "transform");
    EXPECT_EQ(e.jsonPath(), "$.frames[0].forces[0]");
    EXPECT_NE(e.problem().find("f0.z"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------
// Spectral and cross-section models

TEST(TransformSpectral, EveryExampleSolvesToTheTransformedSurface) {
  int checked = 0;
  for (const std::string& file : exampleFiles()) {
    const AnyModel any = loadModel(file);
    if (!any.is<SpectralModel>() && !any.is<CrossSectionModel>()) continue;
    SCOPED_TRACE(file);
    EXPECT_LT(spectralDeviation(any, similarity()), kSpectralTransformTolerance);
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

/// Fourier curves, a derivative condition without u, a spine edit: every kind of data.
constexpr const char* kTube = R"({"type": "spectral", "name": "tube", "operator": "ugail",
  "N": 2, "modes": 4, "placement": "chord-length", "conditions": [
    {"curve": {"fourier": {"a0": [0, 0, 0], "a": [[1, 0, 0], [0, 0, 0.1]], "b": [[0, 1, 0]]}}},
    {"derivative": 1, "curve": {"fourier": {"a0": [0.2, 0, 2], "a": [[0, 0.3, 0]]}}},
    {"curve": {"points": [[0.5, 0, 1], [0, 0.5, 1.1], [-0.5, 0, 1], [0, -0.5, 0.9],
                          [0.4, 0.3, 1], [-0.3, 0.4, 1], [-0.4, -0.3, 1], [0.3, -0.4, 1],
                          [0.45, -0.2, 1]]}},
    {"derivative": 1, "curve": {"fourier": {"a0": [0, 0, 2]}}}],
  "spine": [{"u": [0.3, 0.7], "moved": [[0.2, 0.1, 0.35], [0.1, -0.1, 0.7]]}]})";

TEST(TransformSpectral, DerivativeConditionsAndSpineEditsFollowTheMap) {
  const AnyModel any = parseModel(kTube, "tube");
  const AffineMap map = similarity();
  EXPECT_LT(spectralDeviation(any, map), kSpectralTransformTolerance);
  const SpectralModel& m = any.get<SpectralModel>();
  const SpectralModel t = transformModel(m, map);
  const auto& d = std::get<FourierCurve>(t.conditions[1].curve);
  EXPECT_LT((d.a0 - map.vector({0.2, 0, 2})).norm(), 1e-15);  // linear: no translation
  const auto& p = std::get<FourierCurve>(t.conditions[0].curve);
  EXPECT_LT((p.a0 - map.point(Vec3::Zero())).norm(), 1e-15);
  EXPECT_LT((p.a[0] - map.vector({1, 0, 0})).norm(), 1e-15);
  EXPECT_LT((t.spineEdits[0].moved[1] - map.point({0.1, -0.1, 0.7})).norm(), 1e-15);
  EXPECT_EQ(t.spineEdits[0].u, m.spineEdits[0].u);
}

TEST(TransformSpectral, WrittenModelsReadBackToTheSameModel) {
  std::vector<std::string> texts = {kTube};
  for (const std::string& file : exampleFiles()) {
    std::ifstream in(file);
    texts.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  for (const std::string& text : texts) {
    const AnyModel any = parseModel(text, "m");
    if (any.is<BSplinePdeModel>()) continue;  // not written yet
    const AnyModel moved = transformModel(any, similarity());
    const std::string written = serializeModel(moved);
    EXPECT_EQ(serializeModel(parseModel(written, "written")), written);
    EXPECT_EQ(&moved.method(), &any.method());
  }
}

TEST(TransformSpectral, SessionTransformsUndoesAndRedoes) {
  ModelSession session(parseModel(kTube, "tube"), "tube");
  EXPECT_FALSE(session.hasEditableParts());
  const std::string original = serializeModel(session.model());
  const Vec3 before = session.solved().spectral()->patchAt(0).position(0.5, 1.0);
  const AffineMap map = AffineMap::translationBy({0, 0, 2});
  session.transform(map);
  EXPECT_EQ(session.revision(), 1u);
  EXPECT_LT((session.solved().spectral()->patchAt(0).position(0.5, 1.0) - map.point(before)).norm(),
            1e-12);
  EXPECT_EQ(session.undoDepth(), 1u);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(serializeModel(session.model()), original);
  EXPECT_EQ(session.solved().spectral()->patchAt(0).position(0.5, 1.0), before);
  EXPECT_FALSE(session.undo());
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(serializeModel(session.model()),
            serializeModel(transformModel(parseModel(kTube, "tube"), map)));
  EXPECT_EQ(session.revision(), 3u);
}

TEST(TransformFrames, SessionTransformIsOneUndoStep) {
  std::mt19937 rng(5);
  const VertexFrameModel m = isotropicLattice(rng);
  ModelSession session(m);
  session.apply(TransformModel{similarity()});
  EXPECT_EQ(session.frames()->vertices[3], similarity().point(m.vertices[3]));
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(serializeVertexFrameModel(*session.frames()), serializeVertexFrameModel(m));
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.frames()->vertices[3], similarity().point(m.vertices[3]));
}

// ---------------------------------------------------------------------------------------
// B-spline PDE models

/// max |map(x(u, v)) − x'(u, v)| over every piece, relative to the transformed extent.
double bsplineDeviation(const BSplinePdeModel& model, const AffineMap& map) {
  const SolvedBSplinePde s = solve(model, "test");
  const SolvedBSplinePde t = solve(transformModel(model, map), "test");
  EXPECT_EQ(s.pieces.size(), t.pieces.size());
  double worst = 0;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (std::size_t k = 0; k < s.pieces.size(); ++k)
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const Vec3 got = t.pieces[k].position(i / 8.0, j / 8.0);
        worst = std::max(worst, (map.point(s.pieces[k].position(i / 8.0, j / 8.0)) - got).norm());
        lo = lo.cwiseMin(got);
        hi = hi.cwiseMax(got);
      }
  return worst / (hi - lo).norm();
}

/// A 7 × 6 net on a wavy sheet: the boundary rows and columns the PDE needs.
ControlNet wavyNet() {
  ControlNet net(6, 5);
  for (std::uint32_t i = 0; i <= 6; ++i)
    for (std::uint32_t j = 0; j <= 5; ++j)
      net(i, j) = Vec3(i, j, 0.4 * std::sin(1.3 * i) * std::cos(0.9 * j));
  return net;
}

TEST(TransformBSplinePde, EveryExampleSolvesToTheTransformedSurface) {
  for (const std::string& file : exampleFiles()) {
    const AnyModel any = loadModel(file);
    const auto* m = any.as<BSplinePdeModel>();
    if (!m) continue;
    SCOPED_TRACE(file);
    EXPECT_LT(bsplineDeviation(*m, similarity()), kSpectralTransformTolerance);
  }
}

TEST(TransformBSplinePde, NetAndBoundaryModelsSolveToTheTransformedSurface) {
  BSplinePdeModel net;
  net.form = BSplinePdeModel::Form::Net;
  net.net = wavyNet();
  EXPECT_LT(bsplineDeviation(net, similarity()), kSpectralTransformTolerance);
  EXPECT_LT(bsplineDeviation(net, general()), kSpectralTransformTolerance);

  // The same sheet from boundary curves, the second column as a tangent function.
  const ControlNet p = wavyNet();
  BSplinePdeModel b;
  b.form = BSplinePdeModel::Form::Boundary;
  b.boundary.nu = 6;
  b.boundary.nv = 5;
  BSplineCurve uMin, uMax, vMin, vMax;
  std::vector<Vec3> row1;
  for (std::uint32_t j = 0; j <= 5; ++j) {
    uMin.points.push_back(p(0, j));
    uMax.points.push_back(p(6, j));
    row1.push_back(p(1, j));
  }
  for (std::uint32_t i = 0; i <= 6; ++i) {
    vMin.points.push_back(p(i, 0));
    vMax.points.push_back(p(i, 5));
  }
  b.boundary.uMin = uMin;
  b.boundary.uMax = uMax;
  b.boundary.vMin = vMin;
  b.boundary.vMax = vMax;
  b.boundary.uMinSecond = row1;
  // The tangent (0, 1.5, 0.3u) as a cubic B-spline of vectors: a linear function's control
  // points are its values at the Greville abscissae 0, 1/3, 2/3, 1.
  BSplineCurve tangent;
  for (double g : {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0}) tangent.points.push_back(Vec3(0, 1.5, 0.3 * g));
  b.boundary.vMinSecond = TangentCurve{tangent};
  EXPECT_LT(bsplineDeviation(b, similarity()), kSpectralTransformTolerance);
  const BSplinePdeModel t = transformModel(b, similarity());
  const auto& moved = std::get<BSplineCurve>(std::get<TangentCurve>(t.boundary.vMinSecond).vectors);
  EXPECT_LT((moved.evaluate(0.5) - similarity().vector(Vec3(0, 1.5, 0.15))).norm(), 1e-15);
}

// ---------------------------------------------------------------------------------------
// The studio's JSON

TEST(ParseTransform, BuildsScaleThenRotateThenTranslate) {
  const AffineMap m = parseTransform(
      R"({"scale": 2, "center": [1, 2, 3], "rotate": {"axis": [0, 0, 1], "degrees": 90},
          "translate": [0, 0, 1]})");
  EXPECT_LT((m.point({2, 2, 3}) - Vec3(1, 4, 4)).norm(), 1e-14);
  const AffineMap r =
      parseTransform(R"({"rotate": {"axis": [1, 0, 0], "degrees": 180, "center": [0, 1, 0]}})");
  EXPECT_LT((r.point({0, 2, 0}) - Vec3(0, 0, 0)).norm(), 1e-14);
  EXPECT_EQ(parseTransform(R"({"translate": [1, 2, 3]})").point(Vec3::Zero()), Vec3(1, 2, 3));
}

TEST(ParseTransform, ErrorsNameTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({})", "$: a transform needs"},
      {R"([1])", "$: expected an object"},
      {R"({"scale": 0})", "$.scale: scale 0 is not a finite number above 0"},
      {R"({"scale": -2})", "$.scale: scale -2"},
      {R"({"scale": "2"})", "$.scale: expected a number"},
      {R"({"scale": 1e999})", "$.scale: number is not finite"},
      {R"({"scale": 1e-300})", "$.scale: the map is singular"},
      {R"({"translate": [1, 2]})", "$.translate: expected 3 numbers"},
      {R"({"rotate": {"axis": [0, 0, 0], "degrees": 10}})", "$.rotate.axis: rotation axis"},
      {R"({"rotate": {"axis": [0, 0, 1]}})", "$.rotate: missing required field \"degrees\""},
      {R"({"rotate": {"axis": [0, 0, 1], "degrees": 1, "turns": 2}})", "$.rotate: unknown field"},
      {R"({"rotate": [0, 0, 1]})", "$.rotate: expected an object"},
      {R"({"center": [0, 0, null], "scale": 2})", "$.center[2]: expected a number"},
      {R"({"move": [1, 0, 0]})", "$: unknown field \"move\""},
  };
  for (const auto& [json, message] : cases) {
    try {
      parseTransform(json);
      ADD_FAILURE() << json << ": no error";
    } catch (const ModelError& e) {
      EXPECT_EQ(e.file(), "transform");
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
          << json << " gave " << e.what();
    }
  }
}

}  // namespace
}  // namespace pdesurf
