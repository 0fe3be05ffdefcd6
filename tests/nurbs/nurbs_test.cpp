// NURBS forms of pdesurf patches: the exact conversions equal the patch they come from, the
// approximations stay within their tolerance, checked by sampling both at points the
// conversion never looked at.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/spectral_io.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/examples.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

/// Relative rounding (to the coefficients' size) of the Bézier and Horner forms: a few
/// dozen operations on doubles.
constexpr double kRoundingTolerance = 1e-12;
/// Random (u, v) per patch for the independent checks.
constexpr int kRandomSamples = 400;

using testing::example;

VertexFramePatch randomPatch(std::mt19937& rng) {
  std::uniform_real_distribution<double> coef(-2.0, 2.0);
  VertexFramePatch patch;
  for (Vec3& c : patch.c) c = {coef(rng), coef(rng), coef(rng)};
  return patch;
}

TEST(BezierPatch, EqualsThePolynomialPatchWithItsDerivatives) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const VertexFramePatch patch = randomPatch(rng);
    const NurbsSurface bezier = bezierPatch(patch);
    ASSERT_EQ(bezier.uCount, 4u);
    ASSERT_EQ(bezier.vCount, 4u);
    double scale = 0.0;
    for (const Vec3& c : patch.c) scale = std::max(scale, c.norm());
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const double u = i / 20.0, v = j / 20.0;
        const SurfacePoint want = patch.evaluate(u, v), got = bezier.evaluate(u, v);
        EXPECT_LE((want.p - got.p).norm(), kRoundingTolerance * scale);
        EXPECT_LE((want.du - got.du).norm(), kRoundingTolerance * scale);
        EXPECT_LE((want.dv - got.dv).norm(), kRoundingTolerance * scale);
      }
    // Bézier corners are the patch's corners.
    EXPECT_LE((bezier.pole(0, 0) - patch.position(0, 0)).norm(), kRoundingTolerance * scale);
    EXPECT_LE((bezier.pole(3, 3) - patch.position(1, 1)).norm(), kRoundingTolerance * scale);
  }
}

TEST(EvaluatePolynomial, EqualsEvaluateWithAUnitNormal) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const VertexFramePatch patch = randomPatch(rng);
    double scale = 0.0;
    for (const Vec3& c : patch.c) scale = std::max(scale, c.norm());
    for (int k = 0; k < 100; ++k) {
      const double u = unit(rng), v = unit(rng);
      const SurfacePoint want = patch.evaluate(u, v);
      const PolynomialPatchPoint got = evaluatePolynomial(patch, u, v);
      EXPECT_LE((want.p - got.p).norm(), kRoundingTolerance * scale);
      EXPECT_LE((want.du - got.du).norm(), kRoundingTolerance * scale);
      EXPECT_LE((want.dv - got.dv).norm(), kRoundingTolerance * scale);
      const Vec3 n = want.du.cross(want.dv).normalized();
      EXPECT_LE((n - got.normal).norm(), 1e-9);
    }
  }
}

TEST(EvaluatePolynomial, TheBatchEqualsOneCallPerPoint) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const VertexFramePatch patch = randomPatch(rng);
  std::vector<double> us(1001), vs(1001);  // not a multiple of any SIMD width
  for (std::size_t i = 0; i < us.size(); ++i) us[i] = unit(rng), vs[i] = unit(rng);
  us[0] = vs[0] = 0.0;
  us[1] = vs[1] = 1.0;
  PolynomialPatchPoints out;
  evaluatePolynomial(patch, us, vs, out);
  ASSERT_EQ(out.size(), us.size());
  for (std::size_t i = 0; i < us.size(); ++i) {
    const PolynomialPatchPoint one = evaluatePolynomial(patch, us[i], vs[i]);
    EXPECT_NEAR(out.x[i], one.p.x(), 1e-13);
    EXPECT_NEAR(out.y[i], one.p.y(), 1e-13);
    EXPECT_NEAR(out.z[i], one.p.z(), 1e-13);
    EXPECT_NEAR(out.ux[i], one.du.x(), 1e-13);
    EXPECT_NEAR(out.vz[i], one.dv.z(), 1e-13);
    EXPECT_NEAR(out.nx[i], one.normal.x(), 1e-12);
    EXPECT_NEAR(out.ny[i], one.normal.y(), 1e-12);
    EXPECT_NEAR(out.nz[i], one.normal.z(), 1e-12);
  }
  // A degenerate point (S_u × S_v = 0) has a zero normal, not NaN.
  VertexFramePatch flat;
  for (Vec3& c : flat.c) c = Vec3::Zero();
  evaluatePolynomial(flat, us, vs, out);
  EXPECT_EQ(out.nx[5], 0.0);
  EXPECT_EQ(out.nz[5], 0.0);
}

/// A net of random points around a wavy sheet.
ControlNet randomNet(std::uint32_t nu, std::uint32_t nv, std::mt19937& rng) {
  std::uniform_real_distribution<double> noise(-0.2, 0.2);
  ControlNet net(nu, nv);
  for (std::uint32_t i = 0; i <= nu; ++i)
    for (std::uint32_t j = 0; j <= nv; ++j)
      net(i, j) = Vec3(i, j, std::sin(0.7 * i) * std::cos(0.5 * j)) +
                  Vec3(noise(rng), noise(rng), noise(rng));
  return net;
}

TEST(BSplineToNurbs, UniformAndClampedSurfacesConvertExactly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (KnotType uType : {KnotType::Uniform, KnotType::Clamped})
    for (KnotType vType : {KnotType::Uniform, KnotType::Clamped})
      for (auto [nu, nv] : {std::pair{3u, 3u}, {4u, 7u}, {9u, 5u}}) {
        const BSplineSurface surface(randomNet(nu, nv, rng), uType, vType);
        const NurbsSurface nurbs = toNurbs(surface);
        // Clamped on [0, 1]: four equal end knots, nu + 1 poles along u (the spans of the
        // domain plus 3).
        ASSERT_EQ(nurbs.uKnots.size(), nurbs.uCount + 4);
        EXPECT_EQ(nurbs.uCount, surface.uSpans() + 3);
        EXPECT_EQ(nurbs.vCount, surface.vSpans() + 3);
        for (int k = 0; k < 4; ++k) {
          EXPECT_EQ(nurbs.uKnots[k], 0.0);
          EXPECT_EQ(nurbs.uKnots[nurbs.uKnots.size() - 1 - k], 1.0);
          EXPECT_EQ(nurbs.vKnots[k], 0.0);
          EXPECT_EQ(nurbs.vKnots[nurbs.vKnots.size() - 1 - k], 1.0);
        }
        const double scale = std::max(nu, nv);
        std::vector<std::pair<double, double>> uvs = {{0, 0}, {1, 1}, {0, 1}, {1, 0}};
        for (int k = 0; k < kRandomSamples; ++k) uvs.emplace_back(unit(rng), unit(rng));
        for (auto [u, v] : uvs) {
          const SurfacePoint want = surface.evaluate(u, v), got = nurbs.evaluate(u, v);
          EXPECT_LE((want.p - got.p).norm(), kRoundingTolerance * scale) << u << " " << v;
          EXPECT_LE((want.du - got.du).norm(), kRoundingTolerance * scale * 10);
          EXPECT_LE((want.dv - got.dv).norm(), kRoundingTolerance * scale * 10);
        }
      }
}

/// Deviation of a face from its patch at random points (never the check grid's).
double randomDeviation(const NurbsSurface& face, const PatchFunction& patch, std::mt19937& rng) {
  std::uniform_real_distribution<double> s(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < kRandomSamples; ++k) {
    const double u = patch.u0 + (patch.u1 - patch.u0) * s(rng);
    const double v = patch.v0 + (patch.v1 - patch.v0) * s(rng);
    worst = std::max(worst, (face.position(u, v) - patch.position(u, v)).norm());
  }
  return worst;
}

class VertexFrameExport : public ::testing::TestWithParam<std::string> {};

TEST_P(VertexFrameExport, ExactWithoutForcesWithinToleranceWithForces) {
  const AnyModel any = loadModel(example(GetParam()));
  const VertexFrameSurface surface = solve(any.get<VertexFrameModel>());
  const double diagonal = surfaceBounds(surface).diagonal();
  std::mt19937 rng(5);
  for (double relative : {kDefaultRelativeExportTolerance, 1e-6}) {
    NurbsExportOptions options;
    options.tolerance = relative * diagonal;
    const NurbsModel model = toNurbs(surface, options);
    ASSERT_EQ(model.faces.size(), surface.patches.size());
    EXPECT_DOUBLE_EQ(model.tolerance, options.tolerance);
    std::size_t approximated = 0;
    for (const NurbsFace& face : model.faces) {
      const VertexFramePatch& patch = surface.patches[face.patch];
      PatchFunction f;
      f.position = [&](double u, double v) { return patch.position(u, v); };
      const double independent = randomDeviation(face.surface, f, rng);
      EXPECT_EQ(face.exact, patch.forces.empty());
      if (face.exact) {
        EXPECT_LE(face.deviation, kExactNurbsTolerance * diagonal);
        EXPECT_LE(independent, kExactNurbsTolerance * diagonal);
      } else {
        ++approximated;
        EXPECT_LE(face.deviation, kApproximationSafety * model.tolerance);
        EXPECT_LE(independent, model.tolerance) << "patch " << face.patch;
        // Force terms vanish on the border, which is cubic: the fit reproduces it.
        for (int k = 0; k <= 10; ++k) {
          const double t = k / 10.0;
          EXPECT_LE((face.surface.position(t, 0) - patch.position(t, 0)).norm(),
                    kExactNurbsTolerance * diagonal);
          EXPECT_LE((face.surface.position(1, t) - patch.position(1, t)).norm(),
                    kExactNurbsTolerance * diagonal);
        }
      }
    }
    EXPECT_GT(approximated, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, VertexFrameExport,
                         ::testing::Values("sculpt.json", "grid-forces.json"));

TEST(VertexFrameExport, ForceFreeExamplesAreExact) {
  for (const char* name : {"mug.json", "vase.json"}) {
    const VertexFrameSurface surface = solve(loadModel(example(name)).get<VertexFrameModel>());
    const NurbsModel model = toNurbs(surface);
    EXPECT_EQ(model.exactCount(), model.faces.size()) << name;
    EXPECT_LE(model.maxDeviation(), kExactNurbsTolerance * model.diagonal) << name;
    EXPECT_NEAR(model.tolerance, kDefaultRelativeExportTolerance * model.diagonal,
                1e-12 * model.diagonal);
  }
}

class SpectralExport : public ::testing::TestWithParam<std::string> {};

TEST_P(SpectralExport, ApproximatedWithinToleranceAndClosedAroundV) {
  const std::string path = example(GetParam());
  const SolvedSpectral solved = testing::solveSpectralFile(path);
  const NurbsModel model = toNurbs(solved);
  ASSERT_EQ(model.faces.size(), solved.patchCount());
  std::mt19937 rng(9);
  for (const NurbsFace& face : model.faces) {
    EXPECT_FALSE(face.exact);
    const SpectralPatch& patch = solved.patchAt(face.patch);
    PatchFunction f;
    f.position = [&](double u, double v) { return patch.position(u, v); };
    std::tie(f.u0, f.u1) = solved.range(face.patch);
    f.v1 = 2 * std::numbers::pi;
    EXPECT_DOUBLE_EQ(face.surface.uMin(), f.u0);
    EXPECT_DOUBLE_EQ(face.surface.vMax(), f.v1);
    EXPECT_LE(face.deviation, kApproximationSafety * model.tolerance);
    EXPECT_LE(randomDeviation(face.surface, f, rng), model.tolerance);
    // Closed: the rows at v = 0 and v = 2π are the same poles, bit for bit.
    for (std::uint32_t i = 0; i < face.surface.uCount; ++i)
      EXPECT_EQ(face.surface.pole(i, 0), face.surface.pole(i, face.surface.vCount - 1));
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, SpectralExport,
                         ::testing::Values("shell.json", "vase-sections.json"));

TEST(Approximate, RefinesUntilTheToleranceAndReportsFailurePastTheCap) {
  PatchFunction f;
  f.position = [](double u, double v) {
    return Vec3(u, v, std::sin(3 * u) * std::cos(2 * v) + std::exp(u * v));
  };
  ApproximationOptions options;
  options.tolerance = 1e-7;
  const Approximation fine = approximate(f, options);
  EXPECT_TRUE(fine.withinTolerance);
  EXPECT_LE(fine.deviation, kApproximationSafety * options.tolerance);
  EXPECT_GT(fine.surface.uCount, 4u + 3u);  // it had to refine
  std::mt19937 rng(1);
  EXPECT_LE(randomDeviation(fine.surface, f, rng), options.tolerance);

  options.maxSpans = 8;
  const Approximation capped = approximate(f, options);
  EXPECT_FALSE(capped.withinTolerance);
  EXPECT_GT(capped.deviation, kApproximationSafety * options.tolerance);
}

TEST(Approximate, ACreaseGetsATripleKnotAndCostsNoRefinement) {
  // |u - 0.3| has a kink at 0.3: with the crease declared, four spans are exact.
  PatchFunction f;
  f.position = [](double u, double v) { return Vec3(u, v, std::abs(u - 0.3)); };
  f.uCreases = {0.3};
  ApproximationOptions options;
  options.tolerance = 1e-12;
  const Approximation a = approximate(f, options);
  EXPECT_TRUE(a.withinTolerance);
  EXPECT_EQ(std::count(a.surface.uKnots.begin(), a.surface.uKnots.end(), 0.3), 3);
  EXPECT_LE(a.deviation, 1e-13);
}

TEST(VertexFrameExport, AToleranceTooSmallThrowsNamingThePatch) {
  const VertexFrameSurface surface =
      solve(loadModel(example("sculpt.json")).get<VertexFrameModel>());
  NurbsExportOptions options;
  options.tolerance = 1e-15;
  try {
    toNurbs(surface, options);
    FAIL() << "no error";
  } catch (const NurbsToleranceError& e) {
    EXPECT_NE(std::string(e.what()).find("patch 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--tolerance"), std::string::npos) << e.what();
  }
}

TEST(VertexFrameExport, KeepBestWritesTheFinestFitOfAFaceOverTheTolerance) {
  const VertexFrameSurface surface =
      solve(loadModel(example("sculpt.json")).get<VertexFrameModel>());
  NurbsExportOptions options;
  options.tolerance = 1e-15;
  options.maxSpans = 8;
  options.keepBest = true;
  const NurbsModel model = toNurbs(surface, options);
  ASSERT_EQ(model.faces.size(), surface.patches.size());
  std::size_t over = 0;
  for (const NurbsFace& face : model.faces) {
    // exact faces meet any tolerance; approximated ones cannot reach 1e-15 in 8 spans
    EXPECT_EQ(face.withinTolerance, face.exact) << "patch " << face.patch;
    if (face.exact) continue;
    ++over;
    EXPECT_GT(face.deviation, kApproximationSafety * options.tolerance);
    // The finest fit is still a fit: far closer than the patch's size.
    EXPECT_LT(face.deviation, 1e-2 * model.diagonal);
  }
  EXPECT_GT(over, 0u);
  EXPECT_EQ(model.overToleranceCount(), over);
}

TEST(VertexFrameExport, RandomlyOrientedTorusLatticeIsExact) {
  std::mt19937 rng(2);
  testing::LatticeOptions o;
  o.closedU = o.closedV = true;
  o.randomOrientation = true;
  o.rows = 3;
  o.cols = 4;
  const VertexFrameSurface surface = solve(testing::latticeModel(o, rng));
  const NurbsModel model = toNurbs(surface);
  EXPECT_EQ(model.exactCount(), model.faces.size());
  EXPECT_LE(model.maxDeviation(), kExactNurbsTolerance * model.diagonal);
}

}  // namespace
}  // namespace pdesurf
