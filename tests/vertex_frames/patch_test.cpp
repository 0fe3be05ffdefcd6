// The single patch: vertex interpolation, the closed form against brute-force least
// squares, particular solutions, analytic derivatives.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "pdesurf/analysis.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {
namespace {

/// Parameters of the 8 frame vertices (seed §3.2).
constexpr double kVertexParams[8][2] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5},
                                        {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};

/// Closed-form coefficients are sums of a few vertices with weights ≤ 5, so a patch
/// reproduces them to a few ulps of the coordinates' size (≈ 1 here).
constexpr double kInterpolationTol = 1e-13;

std::array<Vec3, 8> randomFrame(std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  std::array<Vec3, 8> p;
  for (auto& x : p) x = {d(rng), d(rng), d(rng)};
  return p;
}

TEST(Patch, InterpolatesItsEightVerticesForAnyCubics) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-3.0, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    const auto p = randomFrame(rng);
    VertexFramePatch patch;
    patch.c = patchCoefficients(p, {d(rng), d(rng), d(rng)}, {d(rng), d(rng), d(rng)});
    for (int i = 0; i < 8; ++i) {
      const Vec3 s = patch.position(kVertexParams[i][0], kVertexParams[i][1]);
      EXPECT_LT((s - p[i]).norm(), kInterpolationTol) << "trial " << trial << " vertex P" << i + 1;
    }
  }
}

TEST(Patch, EdgeIsQuadraticThroughItsVerticesPlusCubicTimesT_THalf_TMinus1) {
  std::mt19937 rng(2);
  const auto p = randomFrame(rng);
  const Vec3 c3(0.7, -1.1, 0.3), c6(-0.4, 0.9, 2.0);
  VertexFramePatch patch;
  patch.c = patchCoefficients(p, c3, c6);
  auto quad = [](const Vec3& a, const Vec3& m, const Vec3& b, double t) {
    return a * (2 * t - 1) * (t - 1) + m * 4 * t * (1 - t) + b * t * (2 * t - 1);
  };
  for (double t : {0.1, 0.33, 0.5, 0.8}) {
    const double w = t * (t - 0.5) * (t - 1);
    EXPECT_LT((patch.position(t, 0) - (quad(p[0], p[1], p[2], t) + w * c3)).norm(), 1e-13);
    EXPECT_LT((patch.position(t, 1) - (quad(p[6], p[5], p[4], t) + w * c3)).norm(), 1e-13);
    EXPECT_LT((patch.position(0, t) - (quad(p[0], p[7], p[6], t) + w * c6)).norm(), 1e-13);
    EXPECT_LT((patch.position(1, t) - (quad(p[2], p[3], p[4], t) + w * c6)).norm(), 1e-13);
  }
}

/// min over (C3, C6) of Σ_grid (a1 S_uu + a2 S_vv)², solved as a dense least-squares
/// problem: the residual is affine in (C3, C6), so build it column by column.
std::array<double, 2> bruteForceCubics(const std::array<Vec3, 8>& p, double a1, double a2, int comp,
                                       int m, int n) {
  auto residuals = [&](double c3, double c6) {
    VertexFramePatch patch;
    patch.c = patchCoefficients(p, Vec3::Constant(c3), Vec3::Constant(c6));
    Eigen::VectorXd r(m * n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) {
        const double u = static_cast<double>(i) / (m - 1), v = static_cast<double>(j) / (n - 1);
        const auto& c = patch.c;
        const double suu = 2 * c[2][comp] + 6 * c[3][comp] * u + 2 * c[8][comp] * v;
        const double svv = 2 * c[5][comp] + 6 * c[6][comp] * v + 2 * c[9][comp] * u;
        r[j * m + i] = a1 * suu + a2 * svv;
      }
    return r;
  };
  const Eigen::VectorXd r0 = residuals(0, 0);
  Eigen::MatrixXd a(m * n, 2);
  a.col(0) = residuals(1, 0) - r0;
  a.col(1) = residuals(0, 1) - r0;
  const Eigen::Vector2d x = a.colPivHouseholderQr().solve(-r0);
  return {x[0], x[1]};
}

TEST(Patch, ClosedFormEqualsBruteForceLeastSquaresOnAnyGrid) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> par(-5.0, 5.0);
  for (int trial = 0; trial < 50; ++trial) {
    const auto p = randomFrame(rng);
    Vec3 a1(par(rng), par(rng), par(rng)), a2(par(rng), par(rng), par(rng));
    const auto closed = singlePatchCubics(p, a1, a2);
    for (auto [m, n] : {std::pair{2, 2}, {3, 5}, {11, 7}, {20, 20}}) {
      for (int comp = 0; comp < 3; ++comp) {
        const auto brute = bruteForceCubics(p, a1[comp], a2[comp], comp, m, n);
        const double scale = 1.0 + std::abs(brute[0]) + std::abs(brute[1]);
        EXPECT_NEAR(closed[0][comp], brute[0], 1e-10 * scale) << m << "x" << n;
        EXPECT_NEAR(closed[1][comp], brute[1], 1e-10 * scale) << m << "x" << n;
      }
    }
  }
}

TEST(Patch, ZeroA1LeavesC3FreeAndTakesZero) {
  std::mt19937 rng(4);
  const auto p = randomFrame(rng);
  const auto c = singlePatchCubics(p, Vec3(0, 1, 1), Vec3(1, 0, 1));
  EXPECT_EQ(c[0][0], 0.0);
  EXPECT_EQ(c[1][1], 0.0);
  EXPECT_NE(c[0][2], 0.0);
}

TEST(Patch, AnalyticDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(5);
  const auto p = randomFrame(rng);
  VertexFramePatch patch;
  patch.c = patchCoefficients(p, Vec3(0.3, -0.2, 0.5), Vec3(-0.6, 0.1, 0.2));
  patch.forces.push_back({Vec3(0.2, -0.4, 0.7), Region{0.2, 0.7, 0.1, 0.9}});
  patch.forces.push_back({Vec3(-0.3, 0.1, 0.2), Region{}});
  const double h = 1e-6;
  // Central differences of a smooth function: error O(h²·|S'''|) + O(eps/h) ≈ 1e-9.
  constexpr double kFdTol = 1e-7;
  for (double u : {0.15, 0.4, 0.66}) {
    for (double v : {0.3, 0.5, 0.85}) {
      const SurfacePoint s = patch.evaluate(u, v);
      const Vec3 du = (patch.position(u + h, v) - patch.position(u - h, v)) / (2 * h);
      const Vec3 dv = (patch.position(u, v + h) - patch.position(u, v - h)) / (2 * h);
      EXPECT_LT((s.du - du).norm(), kFdTol);
      EXPECT_LT((s.dv - dv).norm(), kFdTol);
      EXPECT_EQ(s.p, patch.position(u, v));
    }
  }
}

/// The particular solution of a force on a region satisfies a1 S_uu + a2 S_vv = F inside
/// the region, and is exactly 0 on its border and outside.
TEST(Patch, ParticularSolutionSatisfiesThePdeAndVanishesOnItsRegionBorder) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> par(0.2, 4.0), corner(0.0, 0.35), f(-5.0, 5.0);
  for (int trial = 0; trial < 30; ++trial) {
    VertexFrameModel model;
    model.vertices.assign(8, Vec3::Zero());
    Frame fr;
    fr.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
    fr.a1 = {par(rng), -par(rng), par(rng)};  // negative a1 is allowed (seed Fig. 11c)
    fr.a2 = {par(rng), par(rng), par(rng)};
    const double u0 = corner(rng), v0 = corner(rng);
    const Region r{u0, u0 + 0.2 + corner(rng), v0, v0 + 0.2 + corner(rng)};
    const Vec3 f0(f(rng), f(rng), f(rng));
    fr.forces.push_back({f0, r});
    model.frames.push_back(fr);
    const VertexFrameSurface s = solve(model);
    const VertexFramePatch& patch = s.patches[0];
    // Zero vertices: the homogeneous part is 0, S is the particular solution alone.
    const double h = 1e-4;
    // Second differences: truncation O(h²·|S''''|) ≈ 1e-6 relative, rounding O(eps/h²) ≈ 1e-8.
    constexpr double kPdeTol = 1e-5;
    for (double s1 : {0.25, 0.5, 0.7}) {
      for (double s2 : {0.3, 0.6}) {
        const double u = r.u0 + s1 * (r.u1 - r.u0), v = r.v0 + s2 * (r.v1 - r.v0);
        const Vec3 suu =
            (patch.position(u + h, v) - 2 * patch.position(u, v) + patch.position(u - h, v)) /
            (h * h);
        const Vec3 svv =
            (patch.position(u, v + h) - 2 * patch.position(u, v) + patch.position(u, v - h)) /
            (h * h);
        const Vec3 lhs = (fr.a1.array() * suu.array() + fr.a2.array() * svv.array()).matrix();
        const Vec3 rhs = f0 * std::sin(M_PI * s1) * std::sin(M_PI * s2);
        EXPECT_LT((lhs - rhs).norm(), kPdeTol * (1 + f0.norm())) << "trial " << trial;
      }
    }
    for (double t : {0.0, 0.3, 0.77, 1.0}) {
      const double u = r.u0 + t * (r.u1 - r.u0), v = r.v0 + t * (r.v1 - r.v0);
      EXPECT_EQ(patch.position(r.u0, v), Vec3::Zero());
      EXPECT_EQ(patch.position(r.u1, v), Vec3::Zero());
      EXPECT_EQ(patch.position(u, r.v0), Vec3::Zero());
      EXPECT_EQ(patch.position(u, r.v1), Vec3::Zero());
      EXPECT_EQ(patch.position(t, 0.0), Vec3::Zero());  // patch border
      EXPECT_EQ(patch.position(1.0, t), Vec3::Zero());
    }
  }
}

TEST(Patch, WholePatchForceMatchesSeedEquation12) {
  VertexFrameModel model;
  model.vertices.assign(8, Vec3::Zero());
  Frame fr;
  fr.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
  fr.a1 = {1, 2, 3};
  fr.a2 = {0.5, 1, -1};
  fr.forces.push_back({Vec3(20, 1, 1), Region{}});
  model.frames.push_back(fr);
  const VertexFramePatch patch = solve(model).patches[0];
  const double u = 0.3, v = 0.6;
  for (int c = 0; c < 3; ++c) {
    const double expected = -fr.forces[0].f0[c] / (M_PI * M_PI * (fr.a1[c] + fr.a2[c])) *
                            std::sin(M_PI * u) * std::sin(M_PI * v);
    EXPECT_NEAR(patch.position(u, v)[c], expected, 1e-15);
  }
}

}  // namespace
}  // namespace pdesurf
