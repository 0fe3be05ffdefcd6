// The B-spline PDE engine (seed 004; docs/derivations.md §3): the basis and its mask rows against
// the seed's closed forms, polynomial reproduction, the sixth mixed derivative on every span, the
// Kronecker solve against a dense solve, invertibility over a range of n, untouched given points,
// errors, boundaries from curves, the seed's examples 1–4 and tessellation.
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "bspline_pde/internal.hpp"
#include "pdesurf/bspline_pde.hpp"
#include "support/mesh_checks.hpp"

namespace pdesurf {
namespace {

constexpr double kPi = std::numbers::pi;

/// Bounds |∂⁶x/∂u³∂v³| on a span relative to Σ_{r,q} |t_r t̃_q| |P| over its 16 points (the
/// size of the terms that cancel): rounding of 16 products, and of the solve.
constexpr double kSixthDerivativeTolerance = 1e-11;
/// Bounds the difference between two solves of the same system (Kronecker, dense LU),
/// relative to the net's extent.
constexpr double kSolveAgreementTolerance = 1e-10;
/// Bounds ‖M x - b‖ / (‖M‖ ‖x‖) of the banded solve: backward stability, a few hundred ulps.
constexpr double kBackwardErrorTolerance = 1e-13;
/// Bounds basis-level agreement (mask rows, polynomial reproduction) relative to the size of
/// the quantities compared.
constexpr double kBasisTolerance = 1e-12;
/// Bounds the length error of a tessellation normal (stored as float).
constexpr double kUnitNormalTolerance = 1e-6;

using Mask = std::array<double, 4>;

std::vector<Mask> masks(KnotType type, std::uint32_t n) {
  const std::vector<double> knots = cubicKnots(type, n);
  std::vector<Mask> out;
  for (std::uint32_t s = 3; s <= n; ++s) out.push_back(thirdDerivativeMask(knots, s));
  return out;
}

/// A net with random given points (inner points NaN: the solve must not read them).
ControlNet randomBoundary(std::uint32_t nu, std::uint32_t nv, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  ControlNet net(nu, nv);
  for (std::uint32_t i = 0; i <= nu; ++i)
    for (std::uint32_t j = 0; j <= nv; ++j)
      net(i, j) = net.given(i, j) ? Vec3(i + 0.3 * d(rng), j + 0.3 * d(rng), d(rng))
                                  : Vec3::Constant(std::nan(""));
  return net;
}

/// max over spans of |Σ t t̃ P| / Σ |t t̃| |P| (the mask residual) and of the evaluated
/// ∂⁶x/∂u³∂v³ at the span's centre over the same scale.
std::pair<double, double> sixthDerivativeResidual(const BSplineSurface& s) {
  const ControlNet& net = s.net();
  const std::vector<Mask> tu = masks(s.uKnotType(), net.nu), tv = masks(s.vKnotType(), net.nv);
  double worstMask = 0.0, worstEval = 0.0;
  for (std::uint32_t a = 0; a < s.uSpans(); ++a)
    for (std::uint32_t b = 0; b < s.vSpans(); ++b) {
      Vec3 sum = Vec3::Zero();
      double scale = 0.0;
      for (std::uint32_t r = 0; r < 4; ++r)
        for (std::uint32_t q = 0; q < 4; ++q) {
          const double w = tu[a][r] * tv[b][q];
          sum += w * net(a + r, b + q);
          scale += std::abs(w) * net(a + r, b + q).norm();
        }
      const double u = (a + 0.5) / s.uSpans(), v = (b + 0.5) / s.vSpans();
      worstMask = std::max(worstMask, sum.norm() / scale);
      worstEval = std::max(worstEval, s.derivative(u, v, 3, 3).norm() / scale);
    }
  return {worstMask, worstEval};
}

/// The blossom of u^a (a ≤ 3) at (x, y, z): control point of u^a on a cubic B-spline.
double blossom(int a, double x, double y, double z) {
  switch (a) {
    case 0:
      return 1.0;
    case 1:
      return (x + y + z) / 3.0;
    case 2:
      return (x * y + y * z + z * x) / 3.0;
    default:
      return x * y * z;
  }
}

/// f(u,v) = Σ c[a][b] u^a v^b, bicubic.
struct Polynomial {
  std::array<std::array<Vec3, 4>, 4> c;
  Vec3 operator()(double u, double v, int du = 0, int dv = 0) const {
    const auto term = [](int a, int d, double x) {
      if (d > a) return 0.0;
      double f = 1.0;
      for (int k = 0; k < d; ++k) f *= a - k;
      return f * std::pow(x, a - d);
    };
    Vec3 sum = Vec3::Zero();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) sum += c[a][b] * term(a, du, u) * term(b, dv, v);
    return sum;
  }
  /// The exact control net of f on the given knots.
  ControlNet net(std::uint32_t nu, std::uint32_t nv, KnotType ku, KnotType kv) const {
    const std::vector<double> tu = cubicKnots(ku, nu), tv = cubicKnots(kv, nv);
    ControlNet out(nu, nv);
    for (std::uint32_t i = 0; i <= nu; ++i)
      for (std::uint32_t j = 0; j <= nv; ++j) {
        Vec3 p = Vec3::Zero();
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            p += c[a][b] * blossom(a, tu[i + 1], tu[i + 2], tu[i + 3]) *
                 blossom(b, tv[j + 1], tv[j + 2], tv[j + 3]);
        out(i, j) = p;
      }
    return out;
  }
};

Polynomial randomPolynomial(std::mt19937& rng, bool inKernel) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Polynomial f;
  for (auto& row : f.c)
    for (Vec3& c : row) c = Vec3(d(rng), d(rng), d(rng));
  if (inKernel) f.c[3][3] = Vec3::Zero();  // ∂⁶/∂u³∂v³ of the rest is 0
  return f;
}

double extent(const ControlNet& net) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : net.points) box.extend(p);
  return box.diagonal().norm();
}

const std::array<KnotType, 2> kKnotTypes = {KnotType::Uniform, KnotType::Clamped};

// ---------------------------------------------------------------------------------------
// Basis.

// Seed eqs. 2.7–2.8 (t from α, β, γ of the knot intervals) hold for any knots with distinct
// interior knots: checked against the basis derivatives on random knot vectors.
TEST(BSplineBasis, MaskRowsMatchSeedClosedFormOnRandomKnots) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> gap(0.2, 2.0);
  for (int trial = 0; trial < 20; ++trial) {
    const std::uint32_t n = 3 + static_cast<std::uint32_t>(trial % 8);
    std::vector<double> knots(n + 5);
    knots[0] = -1.0;
    for (std::size_t k = 1; k < knots.size(); ++k) knots[k] = knots[k - 1] + gap(rng);
    const double shift = knots[3], length = knots[n + 1] - knots[3];
    for (double& k : knots) k = (k - shift) / length;  // domain [0, 1], as findSpan expects
    const auto alpha = [&](std::size_t i) { return 1.0 / (knots[i + 1] - knots[i]); };
    const auto beta = [&](std::size_t i) { return 1.0 / (knots[i + 2] - knots[i]); };
    const auto gamma = [&](std::size_t i) { return 1.0 / (knots[i + 3] - knots[i]); };
    for (std::uint32_t s = 3; s <= n; ++s) {
      const double a = alpha(s) * beta(s) * gamma(s), b = alpha(s) * beta(s) * gamma(s - 1),
                   c = alpha(s) * beta(s - 1) * gamma(s - 1),
                   d = alpha(s) * beta(s - 1) * gamma(s - 2);
      const Mask seed = {-6 * d, 6 * (b + c + d), -6 * (a + b + c), 6 * a};
      const Mask mask = thirdDerivativeMask(knots, s);
      const double scale = std::abs(seed[1]) + std::abs(seed[2]);
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(mask[r], seed[r], kBasisTolerance * scale);
    }
  }
}

// The rows derived in docs/bspline-pde.md (λ = 1): clamped spans 3, 4 and n-1, n; uniform
// everywhere (-1, 3, -3, 1) (seed eq. 2.12); the seed's n = 3 and n = 4 matrices (3.14).
TEST(BSplineBasis, ClampedAndUniformMaskRows) {
  for (std::uint32_t n : {6u, 9u, 30u}) {
    const double l3 = std::pow(1.0 / (n - 2), 3);
    const std::vector<Mask> c = masks(KnotType::Clamped, n), u = masks(KnotType::Uniform, n);
    const std::vector<Mask> expectedEnds = {
        {-6, 10.5, -5.5, 1}, {-1.5, 3.5, -3, 1}, {-1, 3, -3.5, 1.5}, {-1, 5.5, -10.5, 6}};
    const std::vector<std::size_t> spans = {0, 1, n - 4, n - 3};
    for (std::size_t k = 0; k < 4; ++k)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(c[spans[k]][r] * l3, expectedEnds[k][r], kBasisTolerance) << n << " " << k;
    for (std::size_t s = 2; s + 2 < c.size(); ++s)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(c[s][r] * l3, (Mask{-1, 3, -3, 1})[r], kBasisTolerance);
    for (const Mask& m : u)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[r] * l3, (Mask{-1, 3, -3, 1})[r], kBasisTolerance);
  }
  // Seed §3.2 (1), (2): T_1 = -18/λ³ (λ = 1 for n = 3), M_2 = (3/λ³)[[-2, 1/2], [2, -7/2]].
  EXPECT_NEAR(pdeSystemMatrix(KnotType::Clamped, 3)(0, 0), -18.0, kBasisTolerance * 18);
  Eigen::Matrix2d seedM2;
  seedM2 << -2, 0.5, 2, -3.5;
  seedM2 *= 3.0 * 8.0;  // λ = 1/2
  EXPECT_LT((pdeSystemMatrix(KnotType::Clamped, 4) - seedM2).norm(), kBasisTolerance * 100);
}

// A bicubic polynomial's blossom control points reproduce it (position and all derivatives,
// the (3,3) one included) on both knot types: checks the basis independently of the solve.
TEST(BSplineBasis, ReproducesBicubicPolynomials) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  for (KnotType ku : kKnotTypes)
    for (KnotType kv : kKnotTypes) {
      const Polynomial f = randomPolynomial(rng, false);
      const BSplineSurface s(f.net(7, 5, ku, kv), ku, kv);
      for (int k = 0; k < 50; ++k) {
        const double u = k == 0 ? 0.0 : k == 1 ? 1.0 : param(rng);
        const double v = k == 0 ? 1.0 : k == 1 ? 0.0 : param(rng);
        for (int a = 0; a <= 3; ++a)
          for (int b = 0; b <= 3; ++b)
            EXPECT_LT((s.derivative(u, v, a, b) - f(u, v, a, b)).norm(), kBasisTolerance * 1e3)
                << a << b;
        const SurfacePoint sp = s.evaluate(u, v);
        EXPECT_LT((sp.p - f(u, v)).norm(), kBasisTolerance);
        EXPECT_LT((sp.du - f(u, v, 1, 0)).norm(), kBasisTolerance * 10);
        EXPECT_LT((sp.dv - f(u, v, 0, 1)).norm(), kBasisTolerance * 10);
      }
      std::vector<SurfacePoint> grid;
      const std::vector<double> us = {0.0, 0.3, 1.0}, vs = {0.1, 0.5, 0.9, 1.0};
      s.evaluateGrid(us, vs, grid);
      ASSERT_EQ(grid.size(), 12u);
      for (std::size_t a = 0; a < us.size(); ++a)
        for (std::size_t b = 0; b < vs.size(); ++b)
          EXPECT_LT((grid[a * vs.size() + b].p - f(us[a], vs[b])).norm(), kBasisTolerance);
    }
}

// ---------------------------------------------------------------------------------------
// The solve.

TEST(BSplinePde, SixthMixedDerivativeVanishesOnEverySpan) {
  std::mt19937 rng(3);
  for (KnotType ku : kKnotTypes)
    for (KnotType kv : kKnotTypes)
      for (auto [nu, nv] : {std::pair{3u, 3u}, {4u, 9u}, {12u, 5u}, {25u, 25u}}) {
        const BSplineSurface s = solve(randomBoundary(nu, nv, rng), {ku, kv});
        const auto [mask, eval] = sixthDerivativeResidual(s);
        EXPECT_LT(mask, kSixthDerivativeTolerance) << nu << "x" << nv;
        EXPECT_LT(eval, kSixthDerivativeTolerance) << nu << "x" << nv;
        // Independently of the derivative code: the third difference of a cubic with step h
        // is h³ times its third derivative, so 16 positions inside a span give ∂⁶ exactly.
        const double hu = 0.25 / s.uSpans(), hv = 0.25 / s.vSpans();
        const Mask w = {-1, 3, -3, 1};
        for (std::uint32_t a : {0u, s.uSpans() - 1})
          for (std::uint32_t b : {0u, s.vSpans() - 1}) {
            Vec3 sum = Vec3::Zero();
            double scale = 0.0;
            for (int r = 0; r < 4; ++r)
              for (int q = 0; q < 4; ++q) {
                const Vec3 p =
                    s.position((a + 0.1) / s.uSpans() + r * hu, (b + 0.1) / s.vSpans() + q * hv);
                sum += w[r] * w[q] * p;
                scale += std::abs(w[r] * w[q]) * p.norm();
              }
            EXPECT_LT(sum.norm(), 1e-12 * scale) << "span " << a << "," << b;
          }
      }
}

// The full mask system (one equation per span pair over all (nu+1)(nv+1) points), built
// densely here and solved by Eigen's LU for the unknowns, equals the Kronecker solve.
TEST(BSplinePde, KroneckerSolveEqualsDenseSolve) {
  std::mt19937 rng(5);
  for (KnotType ku : kKnotTypes)
    for (KnotType kv : kKnotTypes)
      for (auto [nu, nv] : {std::pair{3u, 3u}, {4u, 6u}, {7u, 5u}, {9u, 9u}, {3u, 8u}}) {
        const ControlNet boundary = randomBoundary(nu, nv, rng);
        const BSplineSurface s = solve(boundary, {ku, kv});
        const std::vector<Mask> tu = masks(ku, nu), tv = masks(kv, nv);
        const int mu = static_cast<int>(nu) - 2, mv = static_cast<int>(nv) - 2;
        Eigen::MatrixXd t = Eigen::MatrixXd::Zero(mu * mv, mu * mv);
        Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(mu * mv, 3);
        for (int a = 0; a < mu; ++a)
          for (int b = 0; b < mv; ++b)
            for (int r = 0; r < 4; ++r)
              for (int q = 0; q < 4; ++q) {
                const auto i = static_cast<std::uint32_t>(a + r),
                           j = static_cast<std::uint32_t>(b + q);
                const double w = tu[a][r] * tv[b][q];
                if (boundary.given(i, j))
                  rhs.row(a * mv + b) -= w * boundary(i, j).transpose();
                else
                  t(a * mv + b, static_cast<int>(i - 2) * mv + static_cast<int>(j - 2)) += w;
              }
        const Eigen::MatrixXd x = t.fullPivLu().solve(rhs);
        const double size = extent(s.net());
        for (int a = 0; a < mu; ++a)
          for (int b = 0; b < mv; ++b)
            EXPECT_LT((x.row(a * mv + b).transpose() - s.net()(static_cast<std::uint32_t>(a + 2),
                                                               static_cast<std::uint32_t>(b + 2)))
                          .norm(),
                      kSolveAgreementTolerance * size)
                << nu << "x" << nv << " point " << a + 2 << "," << b + 2;
      }
}

// M is invertible for n = 3..60 on both knot types (docs: its 1-D kernel is the quadratics,
// fixed by points 0, 1, n); the banded solve is backward stable; for uniform knots
// det(λ³ M) = (-1)^m (m+1)(m+2)/2 with m = n - 2 (the seed's L_n).
TEST(BSplinePde, SystemInvertibleOverRangeOfN) {
  std::mt19937 rng(9);
  std::normal_distribution<double> d;
  for (KnotType type : kKnotTypes)
    for (std::uint32_t n = 3; n <= 60; ++n) {
      const Eigen::MatrixXd m = pdeSystemMatrix(type, n);
      const int size = static_cast<int>(m.rows());
      ASSERT_EQ(m.fullPivLu().rank(), size) << n;
      bspline::BandedLu lu(size, 2, 1);
      for (int r = 0; r < size; ++r)
        for (int c = std::max(0, r - 2); c <= std::min(size - 1, r + 1); ++c) lu.at(r, c) = m(r, c);
      ASSERT_TRUE(lu.factor()) << n;
      bspline::RowMatrix b(size, 3);
      for (int r = 0; r < size; ++r)
        for (int c = 0; c < 3; ++c) b(r, c) = d(rng);
      bspline::RowMatrix x = b;
      lu.solve(x);
      const double backward = (m * x - b).norm() / (m.norm() * x.norm());
      EXPECT_LT(backward, kBackwardErrorTolerance) << n;
      if (type == KnotType::Uniform) {
        const double l3 = std::pow(1.0 / (n - 2), 3);
        const double det = (m * l3).determinant();
        const double expected = (size % 2 ? -1.0 : 1.0) * (size + 1) * (size + 2) / 2.0;
        EXPECT_NEAR(det, expected, 1e-9 * std::abs(expected)) << n;
      }
    }
}

// Given rows and columns come out bit for bit; a kernel polynomial (no u³v³ term) is
// reproduced: its inner control points are the solution.
TEST(BSplinePde, KeepsGivenPointsAndReproducesKernelPolynomials) {
  std::mt19937 rng(13);
  for (KnotType ku : kKnotTypes)
    for (KnotType kv : kKnotTypes)
      for (auto [nu, nv] : {std::pair{3u, 5u}, {6u, 6u}, {11u, 8u}}) {
        const Polynomial f = randomPolynomial(rng, true);
        const ControlNet exact = f.net(nu, nv, ku, kv);
        ControlNet input = exact;
        for (std::uint32_t i = 0; i <= nu; ++i)
          for (std::uint32_t j = 0; j <= nv; ++j)
            if (!input.given(i, j)) input(i, j) = Vec3::Constant(std::nan(""));
        const BSplineSurface s = solve(input, {ku, kv});
        for (std::uint32_t i = 0; i <= nu; ++i)
          for (std::uint32_t j = 0; j <= nv; ++j) {
            if (input.given(i, j))
              EXPECT_EQ(s.net()(i, j), input(i, j)) << i << "," << j;
            else
              EXPECT_LT((s.net()(i, j) - exact(i, j)).norm(), kSolveAgreementTolerance) << i << j;
          }
      }
}

TEST(BSplinePde, SolverReusesFactorization) {
  std::mt19937 rng(17);
  const BSplinePdeSolver solver(10, 7, {KnotType::Clamped, KnotType::Uniform});
  for (int k = 0; k < 3; ++k) {
    const ControlNet net = randomBoundary(10, 7, rng);
    const BSplineSurface a = solver.solve(net);
    const BSplineSurface b = solve(net, {KnotType::Clamped, KnotType::Uniform});
    EXPECT_EQ(a.net().points, b.net().points);
  }
}

template <class F>
void expectInvalid(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning \"" << fragment << "\"";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(BSplinePde, RejectsBadNets) {
  std::mt19937 rng(19);
  expectInvalid([] { solve(ControlNet(2, 5)); }, "at least 3");
  expectInvalid([] { BSplineSurface(ControlNet(5, 1), KnotType::Uniform, KnotType::Uniform); },
                "at least 3");
  ControlNet wrong = randomBoundary(5, 6, rng);
  wrong.points.pop_back();
  expectInvalid([&] { solve(wrong); }, "has 42 points, got 41");
  ControlNet nan = randomBoundary(5, 6, rng);
  nan(0, 2) = Vec3(0, std::nan(""), 0);
  expectInvalid([&] { solve(nan); }, "control point (0, 2) is not finite");
  nan(0, 2) = Vec3::Zero();
  nan(5, 6).x() = INFINITY;
  expectInvalid([&] { solve(nan); }, "(5, 6)");
  // Inner points are ignored by the solve, but a surface must be finite everywhere.
  const ControlNet innerNan = randomBoundary(5, 6, rng);
  EXPECT_NO_THROW(solve(innerNan));
  expectInvalid([&] { BSplineSurface(innerNan, KnotType::Uniform, KnotType::Uniform); },
                "control point (2, 2) is not finite");
  expectInvalid([] { BSplinePdeSolver(4, 2); }, "at least 3");
  const BSplinePdeSolver solver(5, 5);
  ControlNet other = randomBoundary(5, 6, rng);
  expectInvalid([&] { solver.solveInPlace(other); }, "factored for nu = 5, nv = 5");
  expectInvalid([] { cubicKnots(KnotType::Clamped, 2); }, "at least 3");
  const BSplineSurface s = solve(randomBoundary(5, 5, rng));
  expectInvalid([&] { s.derivative(0.5, 0.5, 4, 0); }, "within 0..3");
  expectInvalid([&] { tessellate(s, {1}); }, "resolution must be at least 2");
}

// ---------------------------------------------------------------------------------------
// Boundaries from curves.

/// Boundary data of a bicubic polynomial on clamped knots: exact curves and tangents.
BSplineBoundary polynomialBoundary(const Polynomial& f, std::uint32_t nu, std::uint32_t nv) {
  const ControlNet exact = f.net(nu, nv, KnotType::Clamped, KnotType::Clamped);
  BSplineBoundary bd;
  bd.nu = nu;
  bd.nv = nv;
  BSplineCurve uMin, uMax, vMin, vMax;
  for (std::uint32_t j = 0; j <= nv; ++j) {
    uMin.points.push_back(exact(0, j));
    uMax.points.push_back(exact(nu, j));
  }
  for (std::uint32_t i = 0; i <= nu; ++i) {
    vMin.points.push_back(exact(i, 0));
    vMax.points.push_back(exact(i, nv));
  }
  bd.uMin = uMin;
  bd.uMax = uMax;
  bd.vMin = vMin;
  bd.vMax = vMax;
  bd.uMinSecond = TangentFunction([f](double v) { return f(0.0, v, 1, 0); });
  bd.vMinSecond = TangentFunction([f](double u) { return f(u, 0.0, 0, 1); });
  return bd;
}

// Exact curves and tangents of a bicubic polynomial give exactly its known rows and columns;
// the solved surface then interpolates the boundary curves and the tangent along u = 0.
TEST(BSplineBoundary, TangentRuleAndCurvesGiveTheExactRows) {
  std::mt19937 rng(23);
  const Polynomial f = randomPolynomial(rng, true);
  const std::uint32_t nu = 8, nv = 6;
  const ControlNet exact = f.net(nu, nv, KnotType::Clamped, KnotType::Clamped);
  const ControlNet net = boundaryNet(polynomialBoundary(f, nu, nv));
  for (std::uint32_t i = 0; i <= nu; ++i)
    for (std::uint32_t j = 0; j <= nv; ++j)
      if (net.given(i, j)) {
        EXPECT_LT((net(i, j) - exact(i, j)).norm(), kSolveAgreementTolerance) << i << "," << j;
      }
  const BSplineSurface s = solve(net);
  for (double t = 0.0; t <= 1.0; t += 0.05) {
    EXPECT_LT((s.position(0.0, t) - f(0.0, t)).norm(), kSolveAgreementTolerance);
    EXPECT_LT((s.position(1.0, t) - f(1.0, t)).norm(), kSolveAgreementTolerance);
    EXPECT_LT((s.position(t, 0.0) - f(t, 0.0)).norm(), kSolveAgreementTolerance);
    EXPECT_LT((s.position(t, 1.0) - f(t, 1.0)).norm(), kSolveAgreementTolerance);
    EXPECT_LT((s.evaluate(0.0, t).du - f(0.0, t, 1, 0)).norm(), kSolveAgreementTolerance * 10);
    EXPECT_LT((s.evaluate(t, 0.0).dv - f(t, 0.0, 0, 1)).norm(), kSolveAgreementTolerance * 10);
  }
}

// Sampled curves and curves with other control point counts are fitted with their ends
// kept; a cubic curve (in every clamped spline space) is fitted exactly.
TEST(BSplineBoundary, FitsSampledAndResampledCurves) {
  std::mt19937 rng(29);
  const Polynomial f = randomPolynomial(rng, true);
  const std::uint32_t nu = 7, nv = 9;
  BSplineBoundary bd = polynomialBoundary(f, nu, nv);
  const ControlNet reference = boundaryNet(bd);
  CurveSamples samples;
  for (int k = 0; k <= 40; ++k) {
    samples.t.push_back(k / 40.0);
    samples.points.push_back(f(samples.t.back(), 0.0));
  }
  bd.vMin = samples;
  // uMax as a 4-point Bézier (a clamped cubic with n = 3): resampled and refitted.
  const ControlNet bezier = f.net(3, 3, KnotType::Clamped, KnotType::Clamped);
  BSplineCurve coarse;
  for (std::uint32_t j = 0; j <= 3; ++j) coarse.points.push_back(bezier(3, j));
  bd.uMax = coarse;
  const ControlNet net = boundaryNet(bd);
  for (std::uint32_t i = 0; i <= nu; ++i)
    for (std::uint32_t j = 0; j <= nv; ++j)
      if (net.given(i, j)) {
        EXPECT_LT((net(i, j) - reference(i, j)).norm(), kSolveAgreementTolerance) << i << "," << j;
      }
  // Given second rows are used as they are.
  std::vector<Vec3> row1(nv + 1), column1(nu + 1);
  for (std::uint32_t j = 0; j <= nv; ++j) row1[j] = reference(1, j);
  for (std::uint32_t i = 0; i <= nu; ++i) column1[i] = reference(i, 1);
  bd.uMinSecond = row1;
  bd.vMinSecond = column1;
  const ControlNet given = boundaryNet(bd);
  for (std::size_t k = 0; k < net.points.size(); ++k)
    EXPECT_LT((given.points[k] - net.points[k]).norm(), kSolveAgreementTolerance) << k;
}

TEST(BSplineBoundary, RejectsInconsistentInput) {
  std::mt19937 rng(31);
  const Polynomial f = randomPolynomial(rng, true);
  const BSplineBoundary good = polynomialBoundary(f, 6, 6);
  BSplineBoundary bd = good;
  std::get<BSplineCurve>(bd.vMax).points.back() += Vec3(0.1, 0, 0);
  expectInvalid([&] { boundaryNet(bd); }, "corner (1,1): curve uMax and curve vMax");
  bd = good;
  std::get<BSplineCurve>(bd.uMin).points[3].z() = std::nan("");
  expectInvalid([&] { boundaryNet(bd); }, "curve uMin: point 3 is not finite");
  bd = good;
  bd.uMinSecond = std::vector<Vec3>(4, Vec3::Zero());
  expectInvalid([&] { boundaryNet(bd); }, "uMinSecond (row 1): 4 points given, the side has 7");
  bd = good;
  bd.knots.uKnots = KnotType::Uniform;
  bd.vMin = CurveSamples{{Vec3::Zero(), Vec3::Ones()}, {}};
  expectInvalid([&] { boundaryNet(bd); }, "sampled curves need clamped knots");
  bd = good;
  bd.knots.uKnots = KnotType::Uniform;
  std::vector<Vec3> vMin(7);
  for (std::uint32_t i = 0; i <= 6; ++i) vMin[i] = std::get<BSplineCurve>(good.vMin).points[i];
  bd.vMin = BSplineCurve{vMin, KnotType::Uniform};
  bd.vMax = BSplineCurve{std::get<BSplineCurve>(good.vMax).points, KnotType::Uniform};
  expectInvalid([&] { boundaryNet(bd); }, "tangent function needs clamped knots");
  bd = good;
  bd.vMin = CurveSamples{{Vec3::Zero(), Vec3::Zero()}, {}};
  expectInvalid([&] { boundaryNet(bd); }, "all samples coincide");
  bd = good;
  bd.vMin =
      CurveSamples{{Vec3::Zero(), Vec3::Ones(), Vec3::Ones(), Vec3::Ones()}, {0.0, 0.5, 0.5, 1.0}};
  expectInvalid([&] { boundaryNet(bd); }, "parameter 2 does not increase");
  bd = good;
  bd.nu = 2;
  expectInvalid([&] { boundaryNet(bd); }, "at least 3");
}

// ---------------------------------------------------------------------------------------
// The seed's examples (Figures 1–3) and tessellation.

/// Example 1 (n = 5, uniform): a boundary of the kind of Fig. 1(a), a wavy square net.
ControlNet example1() {
  ControlNet net(5, 5);
  for (std::uint32_t i = 0; i <= 5; ++i)
    for (std::uint32_t j = 0; j <= 5; ++j)
      net(i, j) = net.given(i, j) ? Vec3(i, j, std::sin(1.3 * i) * std::cos(0.9 * j) + 0.1 * i * j)
                                  : Vec3::Zero();
  return net;
}

/// Example 2 (n = 7, uniform): given points on the catenoid (cosh t cos s, cosh t sin s, t),
/// s ∈ [0, π], t ∈ [0, acosh 2], at a uniform parameter grid.
Vec3 catenoid(double s, double t) {
  return {std::cosh(t) * std::cos(s), std::cosh(t) * std::sin(s), t};
}
ControlNet example2() {
  ControlNet net(7, 7);
  for (std::uint32_t i = 0; i <= 7; ++i)
    for (std::uint32_t j = 0; j <= 7; ++j)
      net(i, j) = catenoid(kPi * i / 7.0, std::acosh(2.0) * j / 7.0);
  return net;
}

/// Example 3 (n = 10, clamped): given points on (u sin u cos v, u cos u cos v, u sin v),
/// (u, v) ∈ [0, π] × [0, 2π], at the Greville abscissae of the clamped knots.
Vec3 example3Surface(double u, double v) {
  return {u * std::sin(u) * std::cos(v), u * std::cos(u) * std::cos(v), u * std::sin(v)};
}
ControlNet example3() {
  const std::uint32_t n = 10;
  const std::vector<double> knots = cubicKnots(KnotType::Clamped, n);
  ControlNet net(n, n);
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j <= n; ++j) {
      const double gu = (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0;
      const double gv = (knots[j + 1] + knots[j + 2] + knots[j + 3]) / 3.0;
      net(i, j) = example3Surface(kPi * gu, 2 * kPi * gv);
    }
  return net;
}

void expectUnitNormals(const Mesh& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const Eigen::Vector3d n(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
    ASSERT_TRUE(n.allFinite()) << v;
    EXPECT_NEAR(n.norm(), 1.0, kUnitNormalTolerance) << v;
  }
}

TEST(BSplineExamples, SeedExamplesSolveThePde) {
  struct Case {
    const char* name;
    ControlNet net;
    KnotType knots;
  };
  for (const Case& c : {Case{"example 1", example1(), KnotType::Uniform},
                        Case{"example 2", example2(), KnotType::Uniform},
                        Case{"example 3", example3(), KnotType::Clamped}}) {
    const BSplineSurface s = solve(c.net, {c.knots, c.knots});
    const auto [mask, eval] = sixthDerivativeResidual(s);
    EXPECT_LT(mask, kSixthDerivativeTolerance) << c.name;
    EXPECT_LT(eval, kSixthDerivativeTolerance) << c.name;
    for (std::uint32_t i = 0; i <= s.net().nu; ++i)
      for (std::uint32_t j = 0; j <= s.net().nv; ++j)
        if (c.net.given(i, j)) {
          EXPECT_EQ(s.net()(i, j), c.net(i, j));
        }
    const Mesh mesh = tessellate(s);
    expectUnitNormals(mesh);
  }
  // Example 3 on clamped knots interpolates its boundary: the pole u = 0 and the
  // B-spline curves of the given rows 0 and n (a clamped surface's boundary is its rows).
  const BSplineSurface s3 = solve(example3());
  for (double v = 0.0; v <= 1.0; v += 0.125) {
    EXPECT_LT(s3.position(0.0, v).norm(), 1e-14);
    BSplineCurve last;
    for (std::uint32_t j = 0; j <= 10; ++j) last.points.push_back(s3.net()(10, j));
    EXPECT_LT((s3.position(1.0, v) - last.evaluate(v)).norm(), 1e-12);
  }
  // Example 2: the PDE surface stays near the catenoid it was sampled from (the given points
  // fix only rows/columns 0, 1, 7): inner control points within 5% of the extent.
  const BSplineSurface s2 = solve(example2(), {KnotType::Uniform, KnotType::Uniform});
  double worst = 0.0;
  for (std::uint32_t i = 2; i < 7; ++i)
    for (std::uint32_t j = 2; j < 7; ++j)
      worst = std::max(worst, (s2.net()(i, j) - example2()(i, j)).norm());
  EXPECT_LT(worst, 0.05 * extent(s2.net()));
  RecordProperty("example2_inner_point_deviation", std::to_string(worst));
}

TEST(BSplineTessellate, WatertightGridWithUnitAnalyticNormals) {
  const BSplineSurface s = solve(example1(), {KnotType::Uniform, KnotType::Uniform});
  const Mesh mesh = tessellate(s, {.resolution = 3 * 5 + 1});  // 3 spans a side: 5 segments each
  const std::uint32_t cu = 3 * 5, cv = 3 * 5;
  ASSERT_EQ(mesh.vertexCount(), static_cast<std::size_t>(cu + 1) * (cv + 1));
  ASSERT_EQ(mesh.triangleCount(), 2u * cu * cv);
  ASSERT_EQ(mesh.patchIds.size(), mesh.triangleCount());
  EXPECT_EQ(*std::max_element(mesh.patchIds.begin(), mesh.patchIds.end()), 8u);
  const testing::EdgeStats e = testing::edgeStats(mesh);
  EXPECT_EQ(e.boundaryEdges, 2u * (cu + cv));
  EXPECT_EQ(e.nonManifoldEdges, 0u);
  EXPECT_EQ(e.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
  expectUnitNormals(mesh);
  // Normals are x_u × x_v, on the side the triangles face.
  EXPECT_GT(testing::minCornerNormalAgreement(mesh), 0.9);
  for (std::size_t v = 0; v < mesh.vertexCount(); v += 7) {
    const double u = static_cast<double>(v / (cv + 1)) / cu,
                 w = static_cast<double>(v % (cv + 1)) / cv;
    const SurfacePoint sp = s.evaluate(u, w);
    const Vec3 n = sp.du.cross(sp.dv).normalized();
    EXPECT_NEAR(n.x(), mesh.normals[3 * v], 1e-6);
    EXPECT_NEAR(sp.p.z(), mesh.positions[3 * v + 2], 1e-6);
  }
  // Example 3 has a pole (row 0 is one point, x_u × x_v = 0 there): its normals come out unit,
  // and at the pole they take the limit of the nearby ones, x_u(0,v) × x_uv(0,v) ∝ +x.
  // (Its solved interior folds near u ≈ 0.52, where x_u × x_v changes sign: a property of the
  // PDE surface from these rows, not of the mesh, so face/corner agreement is not asserted.)
  const Mesh pole = tessellate(solve(example3()), {.resolution = 8 * 6 + 1});  // 6 a span
  expectUnitNormals(pole);
  for (std::size_t v = 0; v <= 8 * 6; ++v) EXPECT_GT(pole.normals[3 * v], 0.9) << v;
}

}  // namespace
}  // namespace pdesurf

namespace pdesurf {
namespace {

/// Bounds the measured C1 gap of a blend (relative to the largest cross derivative) and its
/// constraint residual (relative to the extent): the constraints hold to rounding.
constexpr double kBlendTolerance = 1e-9;

BSplineCurve curveOf(const std::function<Vec3(double)>& f, int points) {
  // Control points of the interpolating shape are not needed: the blend refits any curve.
  BSplineCurve c;
  for (int k = 0; k < points; ++k) c.points.push_back(f(static_cast<double>(k) / (points - 1)));
  return c;
}

// Seed Example 4: four boundary curves, 2 × 2 PDE pieces, C1 across both seams. Each piece
// satisfies the PDE on every span, the blend interpolates the (refitted) curves, and the
// measured C1 gap across the seams is at rounding level.
TEST(BSplineBlend, FourPiecesAreC1AndSolveThePde) {
  const auto wave = [](double x, double y) {
    return Vec3(x, y, 0.4 * std::sin(2.0 * x) * std::cos(1.5 * y) + 0.2 * x * y);
  };
  const BSplineCurve uMin = curveOf([&](double t) { return wave(0.0, 2.0 * t); }, 9);
  const BSplineCurve uMax = curveOf([&](double t) { return wave(2.0, 2.0 * t); }, 7);
  const BSplineCurve vMin = curveOf([&](double t) { return wave(2.0 * t, 0.0); }, 8);
  const BSplineCurve vMax = curveOf([&](double t) { return wave(2.0 * t, 2.0); }, 10);
  for (std::uint32_t n : {4u, 7u}) {
    const C1Blend blend = blendFourCurves(uMin, uMax, vMin, vMax, n);
    EXPECT_LT(blend.maxConstraintResidual, kBlendTolerance) << n;
    EXPECT_LT(blend.maxC1Gap, kBlendTolerance) << n;
    ASSERT_EQ(blend.seamGaps.size(), 2u);  // every seam measured and reported
    EXPECT_EQ(blend.seamGaps[0].first, "U = 1");
    EXPECT_EQ(blend.seamGaps[1].first, "V = 1");
    for (const auto& [where, gap] : blend.seamGaps) EXPECT_LE(gap, blend.maxC1Gap) << where;
    char gap[32];
    std::snprintf(gap, sizeof gap, "%.3e", blend.maxC1Gap);
    RecordProperty("c1_gap_n" + std::to_string(n), gap);
    for (const BSplineSurface& piece : blend.pieces) {
      const auto [mask, eval] = sixthDerivativeResidual(piece);
      EXPECT_LT(mask, kSixthDerivativeTolerance) << n;
      EXPECT_LT(eval, kSixthDerivativeTolerance) << n;
    }
    // C0 along the seams and the corners of the region.
    for (double t = 0.0; t <= 1.0; t += 0.125) {
      EXPECT_LT((blend.pieces[0].position(1.0, t) - blend.pieces[2].position(0.0, t)).norm(),
                1e-12);
      EXPECT_LT((blend.pieces[0].position(t, 1.0) - blend.pieces[1].position(t, 0.0)).norm(),
                1e-12);
    }
    EXPECT_LT((blend.pieces[0].position(0, 0) - uMin.points.front()).norm(), 1e-12);
    EXPECT_LT((blend.pieces[3].position(1, 1) - vMax.points.back()).norm(), 1e-12);
    // The boundary is the curves' least-squares refit: near the input curves.
    for (double t = 0.0; t <= 1.0; t += 0.0625) {
      EXPECT_LT((blend.pieces[0].position(0.0, t) - uMin.evaluate(0.5 * t)).norm(), 1e-2);
      EXPECT_LT((blend.pieces[1].position(0.0, t) - uMin.evaluate(0.5 + 0.5 * t)).norm(), 1e-2);
    }
  }
  // A curve that is cubic lies in every refit space: reproduced exactly.
  const auto line = [](double t) { return Vec3(0.0, 2.0 * t, 0.3 * t * t * t); };
  const C1Blend exact = blendFourCurves(
      curveOf(line, 4), curveOf([](double t) { return Vec3(2.0, 2.0 * t, 0.3 * t * t * t); }, 4),
      curveOf([](double t) { return Vec3(2.0 * t, 0, 0); }, 4),
      curveOf([](double t) { return Vec3(2.0 * t, 2.0, 0.3); }, 4), 5);
  EXPECT_LT(exact.maxC1Gap, kBlendTolerance);
  EXPECT_EQ(exact.pieces.size(), 4u);
}

// Seed Example 5: two closed curves, a tube of 1 × 2 PDE pieces, C1 across both seams
// (V = 1 and the wrap V = 0 ≡ 2), interpolating the refitted curves.
TEST(BSplineBlend, ClosedTubeIsC1AllAround) {
  const auto ring = [](double r, double z, double wobble) {
    return [=](double t) {
      const double a = 2.0 * std::numbers::pi * t;
      return Vec3(r * std::cos(a), r * (1.0 + wobble * std::sin(2.0 * a)) * std::sin(a), z);
    };
  };
  const BSplineCurve end = curveOf(ring(1.5, 2.0, 0.2), 17);
  for (std::uint32_t n : {4u, 6u}) {
    // A start curve that is closed and C1 where it closes, with the blend's own point count
    // (2n - 1): the blend keeps it exactly.
    BSplineCurve start;
    const std::uint32_t last = 2 * n - 2;
    start.points.resize(last + 1);
    for (std::uint32_t k = 1; k < last; ++k)
      start.points[k] = ring(1.0, 0.0, 0.0)((k - 0.5) / (last - 1.0));
    start.points[0] = start.points[last] = 0.5 * (start.points[1] + start.points[last - 1]);
    const C1Blend blend = blendClosedCurves(start, end, n);
    ASSERT_EQ(blend.pieces.size(), 2u);
    ASSERT_EQ(blend.seamGaps.size(), 2u);
    EXPECT_EQ(blend.seamGaps[1].first, "V = 0");
    EXPECT_LT(blend.seamGaps[1].second, kBlendTolerance) << n;  // the wrap seam too
    EXPECT_TRUE(blend.closedV);
    EXPECT_LT(blend.maxConstraintResidual, kBlendTolerance) << n;
    EXPECT_LT(blend.maxC1Gap, kBlendTolerance) << n;
    for (const BSplineSurface& piece : blend.pieces) {
      const auto [mask, eval] = sixthDerivativeResidual(piece);
      EXPECT_LT(mask, kSixthDerivativeTolerance) << n;
      EXPECT_LT(eval, kSixthDerivativeTolerance) << n;
    }
    for (double t = 0.0; t <= 1.0; t += 0.0625) {
      // C0 at both seams; the ends are the start curve and lie in the end ring's plane.
      EXPECT_LT((blend.pieces[0].position(t, 1.0) - blend.pieces[1].position(t, 0.0)).norm(),
                1e-12);
      EXPECT_LT((blend.pieces[1].position(t, 1.0) - blend.pieces[0].position(t, 0.0)).norm(),
                1e-12);
      EXPECT_LT((blend.pieces[0].position(0.0, t) - start.evaluate(0.5 * t)).norm(), 1e-12);
      EXPECT_LT((blend.pieces[1].position(0.0, t) - start.evaluate(0.5 + 0.5 * t)).norm(), 1e-12);
      EXPECT_NEAR(blend.pieces[1].position(1.0, t).z(), 2.0, 1e-12);
    }
  }
  const BSplineCurve start = curveOf(ring(1.0, 0.0, 0.0), 13);
  BSplineCurve open = start;
  open.points.back().x() += 0.5;
  expectInvalid([&] { blendClosedCurves(open, end, 5); }, "curve start is not closed");
  expectInvalid([&] { blendClosedCurves(start, end, 2); }, "at least 3");
}

TEST(BSplineBlend, RejectsBadCurves) {
  const auto line = [](double t) { return Vec3(2.0 * t, 0, 0); };
  const BSplineCurve a = curveOf([](double t) { return Vec3(0, 2.0 * t, 0); }, 5);
  const BSplineCurve b = curveOf([](double t) { return Vec3(2.0, 2.0 * t, 0); }, 5);
  const BSplineCurve c = curveOf(line, 5);
  const BSplineCurve d = curveOf([](double t) { return Vec3(2.0 * t, 2.0, 0); }, 5);
  expectInvalid([&] { blendFourCurves(a, b, c, d, 2); }, "at least 3");
  BSplineCurve off = d;
  off.points.back().z() = 1.0;
  expectInvalid([&] { blendFourCurves(a, b, c, off, 5); }, "curves uMax and vMax do not meet");
  BSplineCurve uniform = c;
  uniform.knots = KnotType::Uniform;
  expectInvalid([&] { blendFourCurves(a, b, uniform, d, 5); }, "vMin: needs clamped knots");
  BSplineCurve nan = a;
  nan.points[2].x() = std::nan("");
  expectInvalid([&] { blendFourCurves(nan, b, c, d, 5); }, "uMin: point 2 is not finite");
}

}  // namespace
}  // namespace pdesurf
