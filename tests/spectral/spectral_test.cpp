// The spectral engine (seeds 002, 003; docs/derivations.md §2): conditions, PDE residuals, an
// independent ODE check of the mode bases, remainder, chains, fitting, spine, errors,
// tessellation.
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <algorithm>
#include <functional>
#include <vector>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral.hpp"
#include "support/mesh_checks.hpp"

namespace pdesurf {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * kPi;

/// Bounds every condition error (relative, see conditionErrors) of the well-conditioned
/// cases: the acceptance level; the solves reach 1e-13 or better.
constexpr double kConditionTolerance = 1e-9;
/// Bounds |PDE residual| / Σ|terms of the operator| at interior points of band-limited
/// patches: the terms cancel to rounding, so a few hundred ulps of the largest term.
constexpr double kPdeResidualTolerance = 1e-9;
/// Bounds the difference between a mode function and the independent RK4 shooting
/// solution of its ODE (4000 steps: RK4 error ~ h⁴ κ⁵ ≈ 1e-12), relative to its size.
constexpr double kShootingTolerance = 1e-8;
/// Bounds C0, C1 and C2 gaps at method-2 joins relative to the chain's extent.
constexpr double kJointTolerance = 1e-9;

FourierCurve ring(double radius, const Vec3& centre, std::uint32_t modes, double wobble = 0.0,
                  double tilt = 0.0) {
  FourierCurve c;
  c.a0 = centre;
  c.a.assign(modes, Vec3::Zero());
  c.b.assign(modes, Vec3::Zero());
  c.a[0] = Vec3(radius, 0.0, tilt);
  c.b[0] = Vec3(0.0, radius, 0.0);
  if (modes >= 2) c.a[1] = Vec3(wobble, 0.5 * wobble, 0.0);
  if (modes >= 3) c.b[2] = Vec3(0.0, 0.3 * wobble, 0.2 * wobble);
  return c;
}

/// A rounded square (superellipse, exponent 4) at height z: not a finite Fourier series.
SampledCurve squircle(double size, double z, int points, double twist = 0.0) {
  SampledCurve c;
  for (int j = 0; j < points; ++j) {
    const double t = kTwoPi * j / points;
    const double ct = std::cos(t), st = std::sin(t);
    const double x = size * std::copysign(std::sqrt(std::abs(ct)), ct);
    const double y = size * std::copysign(std::sqrt(std::abs(st)), st);
    c.points.emplace_back(x * std::cos(twist) - y * std::sin(twist),
                          x * std::sin(twist) + y * std::cos(twist), z);
  }
  return c;
}

double maxOf(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, x);
  return m;
}

std::vector<SpectralCondition> positions(const std::vector<FourierCurve>& curves) {
  std::vector<SpectralCondition> c;
  for (const FourierCurve& f : curves) c.push_back({0, std::nullopt, f});
  return c;
}

// ---------------------------------------------------------------------------------------
// Mode bases against an independent shooting solution of the mode ODE.

// Plain arrays, not dynamic Eigen types: the library is built with -march=native and this
// test without, and Eigen's out-of-line heap helpers must not mix the two alignments.
using Rows = std::vector<std::vector<double>>;

/// y^(m) = Σ_j q[j] y^(j): fundamental solutions from t = 0 by RK4, sampled at `ts`
/// (multiples of the step). Returns out[t index][solution j].
Rows shoot(const std::vector<double>& q, const std::vector<double>& ts, int steps) {
  const std::size_t m = q.size();
  Rows out(ts.size(), std::vector<double>(m, 0.0));
  const double h = 1.0 / steps;
  using State = std::vector<double>;
  auto f = [&](const State& s) {
    State d(m, 0.0);
    for (std::size_t i = 0; i + 1 < m; ++i) d[i] = s[i + 1];
    for (std::size_t i = 0; i < m; ++i) d[m - 1] += q[i] * s[i];
    return d;
  };
  auto axpy = [](const State& y, double a, const State& x) {
    State r = y;
    for (std::size_t i = 0; i < r.size(); ++i) r[i] += a * x[i];
    return r;
  };
  for (std::size_t j = 0; j < m; ++j) {
    State y(m, 0.0);
    y[j] = 1.0;
    std::size_t next = 0;
    for (int k = 0; k <= steps; ++k) {
      while (next < ts.size() && std::abs(ts[next] - k * h) < 0.5 * h) out[next++][j] = y[0];
      if (k == steps) break;
      const State k1 = f(y), k2 = f(axpy(y, 0.5 * h, k1)), k3 = f(axpy(y, 0.5 * h, k2)),
                  k4 = f(axpy(y, h, k3));
      for (std::size_t i = 0; i < m; ++i) y[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
  }
  return out;
}

/// Gaussian elimination with partial pivoting.
std::vector<double> solveDense(Rows a, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    std::swap(a[c], a[p]);
    std::swap(b[c], b[p]);
    for (std::size_t r = c + 1; r < n; ++r) {
      const double f = a[r][c] / a[c][c];
      for (std::size_t k = c; k < n; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  std::vector<double> x(n);
  for (std::size_t r = n; r-- > 0;) {
    double s = b[r];
    for (std::size_t k = r + 1; k < n; ++k) s -= a[r][k] * x[k];
    x[r] = s / a[r][r];
  }
  return x;
}

/// Solves a patch whose data live in mode n only (x-component, cos nv) at the given u with
/// position conditions, and compares A_n(t) with the shooting solution.
void checkModeAgainstShooting(const SpectralOperator& op, std::uint32_t n,
                              const std::vector<double>& q) {
  constexpr int kSteps = 4000;
  const std::uint32_t order = op.order();
  std::vector<double> tc;  // condition u's on the RK4 step grid
  for (std::uint32_t i = 0; i < order; ++i)
    tc.push_back(std::round(kSteps * static_cast<double>(i) / (order - 1)) / kSteps);
  std::vector<SpectralCondition> conds;
  std::vector<double> g;
  for (std::uint32_t i = 0; i < order; ++i) {
    FourierCurve f;
    f.a.assign(n, Vec3::Zero());
    f.b.assign(n, Vec3::Zero());
    g.push_back(std::sin(1.0 + 2.3 * i) + 0.5);
    f.a[n - 1] = Vec3(g.back(), 0.0, 0.0);
    conds.push_back({0, tc[i], f});
  }
  const SpectralPatch patch =
      solve(op, conds, {n, UPlacement::Given, VParameterization::Uniform, false});
  std::vector<double> ts = tc;
  for (int k = 1; k < 20; ++k) ts.push_back(std::round(kSteps * (k / 20.0 + 0.013)) / kSteps);
  std::sort(ts.begin(), ts.end());
  const Rows y = shoot(q, ts, kSteps);
  Rows a;
  for (std::uint32_t i = 0; i < order; ++i) {
    const auto it =
        std::find_if(ts.begin(), ts.end(), [&](double t) { return std::abs(t - tc[i]) < 1e-12; });
    ASSERT_NE(it, ts.end());
    a.push_back(y[static_cast<std::size_t>(it - ts.begin())]);
  }
  const std::vector<double> c = solveDense(a, g);
  double worst = 0.0, size = 0.0;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    double ref = 0.0;
    for (std::uint32_t j = 0; j < order; ++j) ref += y[k][j] * c[j];
    worst = std::max(worst, std::abs(patch.position(ts[k], 0.0).x() - ref));
    size = std::max(size, std::abs(ref));
  }
  EXPECT_LT(worst / size, kShootingTolerance) << "mode " << n;
}

TEST(SpectralBasis, FuModesMatchShootingForBothSignsOfA) {
  for (double a : {1.5, -1.5, 40.0, -40.0})
    for (std::uint32_t n : {1u, 2u}) {
      std::vector<double> q(6, 0.0);
      q[0] = a * std::pow(static_cast<double>(n), 6.0);  // y⁽⁶⁾ = a n⁶ y
      SCOPED_TRACE("a = " + std::to_string(a));
      checkModeAgainstShooting(SpectralOperator::fu(a), n, q);
    }
}

TEST(SpectralBasis, UgailModesMatchShooting) {
  for (std::uint32_t big : {2u, 3u})
    for (std::uint32_t n : {1u, 2u}) {
      const double a = 1.3, lambda2 = a * a * n * n;
      // (r² - λ²)^N = Σ_k C(N,k) r^{2k} (-λ²)^{N-k}: y^{(2N)} = -Σ_{k<N} C(N,k)(-λ²)^{N-k}
      // y^{(2k)}.
      std::vector<double> q(2 * big, 0.0);
      double binom = 1.0;
      for (std::uint32_t k = 0; k < big; ++k) {
        q[2 * k] = -binom * std::pow(-lambda2, static_cast<double>(big - k));
        binom = binom * (big - k) / (k + 1);
      }
      SCOPED_TRACE("N = " + std::to_string(big));
      checkModeAgainstShooting(SpectralOperator::ugail(big, a), n, q);
    }
}

// ---------------------------------------------------------------------------------------
// Conditions and PDE residuals.

TEST(SpectralPatch, PositionAndDerivativeConditionsAreMet) {
  // Seed 003 §4.1 style: positions at the ends and two interior curves, derivative curves
  // at the interior ones (order 8).
  const std::uint32_t m = 6;
  std::vector<SpectralCondition> c = {{0, 0.0, ring(1.0, Vec3(0, 0, 0), m, 0.1)},
                                      {0, std::nullopt, ring(1.4, Vec3(0.2, 0, 1), m, 0.2, 0.1)},
                                      {1, std::nullopt, ring(0.3, Vec3(0, 0, 1), m, 0.05)},
                                      {2, std::nullopt, ring(0.2, Vec3(0.1, 0, 0), m, 0.02)},
                                      {0, std::nullopt, ring(1.1, Vec3(0, 0.3, 2), m, -0.1)},
                                      {1, std::nullopt, ring(-0.2, Vec3(0, 0, 1), m, 0.05)},
                                      {2, std::nullopt, ring(0.1, Vec3(0, 0.1, 0), m)},
                                      {0, 1.0, ring(0.9, Vec3(0, 0, 3), m, 0.1)}};
  c[1].u = 1.0 / 3.0;
  c[4].u = 2.0 / 3.0;
  const SpectralPatch p = solve(SpectralOperator::ugail(4), c,
                                {m, UPlacement::Given, VParameterization::Uniform, true});
  EXPECT_FALSE(p.hasRemainder());
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
  EXPECT_DOUBLE_EQ(p.conditions()[2].u, 1.0 / 3.0);  // derivative takes its position's u
}

TEST(SpectralPatch, FuConditionsMetForManyModes) {
  for (double a : {1.0, -1.0, 50.0, -50.0})
    for (std::uint32_t m : {6u, 32u}) {
      std::vector<FourierCurve> curves;
      for (int i = 0; i < 6; ++i) {
        FourierCurve f = ring(1.0 + 0.2 * std::sin(i), Vec3(0.1 * i * i, 0, i), m, 0.1);
        for (std::uint32_t n = 4; n <= m; ++n) f.a[n - 1] = Vec3(0.3 / (n * n), 0.1 / n, 0.05);
        curves.push_back(f);
      }
      const SpectralPatch p =
          solve(SpectralOperator::fu(a), positions(curves), {m, UPlacement::Uniform});
      EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance) << "a " << a << " M " << m;
    }
}

/// |L X| / Σ|terms| at interior points, L expanded into mixed derivatives.
double pdeResidual(const SpectralPatch& p) {
  const SpectralOperator& op = p.op();
  double worst = 0.0;
  for (double u : {0.13, 0.41, 0.77})
    for (double v : {0.3, 2.0, 4.4}) {
      Vec3 sum = Vec3::Zero();
      double scale = 0.0;
      auto add = [&](double coef, std::uint32_t ku, std::uint32_t kv) {
        const Vec3 term = coef * p.derivative(u, v, ku, kv);
        sum += term;
        scale += term.norm();
      };
      if (op.kind == OperatorKind::Fu) {
        add(1.0, 6, 0);
        add(op.a, 0, 6);
      } else {
        double binom = 1.0;  // (∂u² + a²∂v²)^N = Σ C(N,i) a^{2(N-i)} ∂u^{2i} ∂v^{2(N-i)}
        for (std::uint32_t i = 0; i <= op.power; ++i) {
          add(binom * std::pow(op.a, 2.0 * (op.power - i)), 2 * i, 2 * (op.power - i));
          binom = binom * (op.power - i) / (i + 1);
        }
      }
      worst = std::max(worst, sum.norm() / scale);
    }
  return worst;
}

TEST(SpectralPatch, PdeResidualVanishesForBandLimitedInput) {
  const std::uint32_t m = 4;
  for (const SpectralOperator& op : {SpectralOperator::ugail(2), SpectralOperator::ugail(3, 1.5),
                                     SpectralOperator::fu(2.0), SpectralOperator::fu(-2.0)}) {
    std::vector<FourierCurve> curves;
    for (std::uint32_t i = 0; i < op.order(); ++i)
      curves.push_back(ring(1.0 + 0.3 * std::cos(i), Vec3(0.2 * i, 0.1 * i * i, i), m, 0.15, 0.1));
    const SpectralPatch p = solve(op, positions(curves), {m, UPlacement::Uniform});
    EXPECT_LT(pdeResidual(p), kPdeResidualTolerance) << "order " << op.order();
  }
}

/// Seed 003 eqs. 29–31 (the Klein bottle, α = 6, β = 16, γ = 4(1 − cos s / 2)) at section
/// parameter s ∈ [0, 2π]: each section is a circle (modes 0 and 1 in v); the two branches
/// meet at s = π (scripts/make_spectral_examples.py, klein_bottle).
FourierCurve kleinSection(double s) {
  const double g = 4 * (1 - std::cos(s) / 2);
  FourierCurve f;
  f.a0 = Vec3(6 * std::cos(s) * (1 + std::sin(s)), 16 * std::sin(s), 0.0);
  f.a = {s < kPi ? Vec3(g * std::cos(s), g * std::sin(s), 0.0) : Vec3(-g, 0.0, 0.0)};
  f.b = {Vec3(0.0, 0.0, g)};
  return f;
}

/// The seed's Klein bottle recipe (seed 003 Table 1): 40 sections at equispaced s, placed at
/// uniform u, Ugail N = 20 (order 40), M = 6.
std::vector<SpectralCondition> kleinConditions() {
  std::vector<FourierCurve> curves;
  for (int k = 0; k < 40; ++k) curves.push_back(kleinSection(kTwoPi * k / 39));
  return positions(curves);
}

TEST(SpectralPatch, SeedKleinBottleAtOrderFortyIsSolvedInQuadPrecision) {
  // a = N = 20 (the default): mode 1's roots ±20 of multiplicity 20 give a condition matrix
  // of condition ~1e23, beyond long double; the engine redoes that mode in quad.
  const SpectralPatch p =
      solve(SpectralOperator::ugail(20), kleinConditions(), {6, UPlacement::Uniform});
  EXPECT_EQ(p.precision(1), ModePrecision::Quad);
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
  // The grid and tessellation paths evaluate the quad mode as position() does.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> us, vs;
  for (int i = 0; i < 9; ++i) us.push_back(unit(rng));
  for (int j = 0; j < 5; ++j) vs.push_back(kTwoPi * unit(rng));
  const SpectralGrid grid = evaluateGrid(p, us, vs);
  double size = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < us.size(); ++i)
    for (std::size_t j = 0; j < vs.size(); ++j) {
      const std::size_t k = i * vs.size() + j;
      size = std::max({size, grid.p[k].norm(), grid.du[k].norm(), grid.dv[k].norm()});
      worst = std::max({worst, (grid.p[k] - p.position(us[i], vs[j])).norm(),
                        (grid.du[k] - p.derivative(us[i], vs[j], 1, 0)).norm(),
                        (grid.dv[k] - p.derivative(us[i], vs[j], 0, 1)).norm()});
    }
  EXPECT_LT(worst, 1e-12 * size);
  const TessellateOptions o{.resolution = 11, .aroundResolution = 8};
  const Mesh mesh = tessellate(p, o);
  ASSERT_EQ(mesh.vertexCount(), 11u * 8u);
  double meshWorst = 0.0, meshSize = 0.0;
  for (std::uint32_t r = 0; r < 11; ++r)
    for (std::uint32_t j = 0; j < 8; ++j) {
      const std::size_t k = r * 8 + j;
      const Vec3 vertex(mesh.positions[3 * k], mesh.positions[3 * k + 1],
                        mesh.positions[3 * k + 2]);
      const Vec3 x = p.position(r / 10.0, kTwoPi * j / 8);
      meshWorst = std::max(meshWorst, (vertex - x).norm());
      meshSize = std::max(meshSize, x.norm());
    }
  EXPECT_LT(meshWorst, 1e-6 * meshSize);  // float vertices
}

TEST(SpectralPatch, OrderFortyWithSmoothDataIsSolvedInThePrecisionItNeeds) {
  // Interior curves with smooth data in modes 1–3 at order 40, a = N. Mode 1's system is as
  // ill-conditioned as the Klein bottle's, but these data need no large cancelling
  // coefficients, and long double meets them: the residual decides, not an estimate.
  std::vector<FourierCurve> curves;
  for (int i = 0; i < 40; ++i)
    curves.push_back(
        ring(1.0 + 0.2 * std::sin(0.3 * i), Vec3(std::cos(0.1 * i), 0, 0.1 * i), 6, 0.1));
  const SpectralPatch p =
      solve(SpectralOperator::ugail(20), positions(curves), {6, UPlacement::Uniform});
  EXPECT_EQ(p.precision(1), ModePrecision::Extended);
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
}

TEST(SpectralPatch, ModesLongDoubleCanSolveStayInLongDoubleOrDouble) {
  // No silent slowdown: the seed's order-10 set-up (N = a = 5, 10 interior curves) stays in
  // double, and a mode whose basis overlaps (a n = 3 < m = 5) is solved in long double
  // without going on to quad.
  std::vector<FourierCurve> curves;
  for (int i = 0; i < 10; ++i)
    curves.push_back(ring(1.0 + 0.3 * std::sin(0.7 * i), Vec3(0.2 * i, 0, i), 6, 0.1, 0.05));
  const SpectralPatch p =
      solve(SpectralOperator::ugail(5), positions(curves), {6, UPlacement::Uniform});
  for (std::uint32_t n = 0; n <= 6; ++n) EXPECT_EQ(p.precision(n), ModePrecision::Double) << n;
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
  const SpectralPatch q =
      solve(SpectralOperator::ugail(5, 3.0), positions(curves), {6, UPlacement::Uniform});
  EXPECT_EQ(q.precision(1), ModePrecision::Extended);
  for (std::uint32_t n = 0; n <= 6; ++n) EXPECT_NE(q.precision(n), ModePrecision::Quad) << n;
  EXPECT_LT(maxOf(conditionErrors(q)), kConditionTolerance);
}

TEST(SpectralPatch, RemainderOfAnIllConditionedModeIsEvaluatedInQuad) {
  // M = 1 at order 40: the remainder lives on mode 2 (roots ±40, 20-fold), whose cardinal
  // functions long double cannot invert to the conditions' accuracy.
  std::vector<SpectralCondition> c;
  for (int k = 0; k < 40; ++k) {
    const FourierCurve f = kleinSection(kTwoPi * k / 39);
    SampledCurve s;
    for (int j = 0; j < 24; ++j) {
      const double v = kTwoPi * j / 24;
      s.points.push_back(f.evaluate(v) + Vec3(0.0, 0.0, 0.3 * std::cos(2 * v + 0.1 * k)));
      s.v.push_back(v);
    }
    c.push_back({0, std::nullopt, s});
  }
  const SpectralPatch p = solve(SpectralOperator::ugail(20), c, {1, UPlacement::Uniform});
  EXPECT_TRUE(p.hasRemainder());
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
}

TEST(SpectralPatch, TooIllConditionedModesAreRefusedNotReturned) {
  // Order 40 with 40 interior curves at a = N/2 = 10: mode 1's roots ±10 of multiplicity 20
  // overlap beyond what even quad precision can carry (docs/spectral.md); the solver must
  // say so rather than return a surface that misses its curves.
  std::vector<FourierCurve> curves;
  for (int k = 0; k < 40; ++k) curves.push_back(kleinSection(kTwoPi * k / 39));
  try {
    const SpectralPatch p =
        solve(SpectralOperator::ugail(20, 10.0), positions(curves), {6, UPlacement::Uniform});
    EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);  // if it solves, it must be right
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("do not determine mode 1"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------
// Remainder.

TEST(SpectralPatch, RemainderMeetsSampledCurvesAtEverySample) {
  std::vector<SpectralCondition> c;
  for (int i = 0; i < 4; ++i)
    c.push_back({0, std::nullopt, squircle(1.0 + 0.2 * i, i, 80, 0.2 * i)});
  for (bool remainder : {true, false}) {
    const SpectralPatch p =
        solve(SpectralOperator::ugail(2), c,
              {6, UPlacement::Uniform, VParameterization::ChordLength, remainder});
    EXPECT_EQ(p.hasRemainder(), remainder);
    const double err = maxOf(conditionErrors(p));
    if (remainder)
      EXPECT_LT(err, kConditionTolerance);
    else
      EXPECT_GT(err, 1e-3);  // the 6-mode truncation of a rounded square misses its points
    // Interior points are finite and near the curves' scale.
    EXPECT_LT(p.position(0.5, 1.0).norm(), 10.0);
  }
}

TEST(SpectralPatch, RemainderCarriesFourierTailsBeyondM) {
  std::vector<FourierCurve> curves;
  for (int i = 0; i < 6; ++i) {
    FourierCurve f = ring(1.0, Vec3(0, 0, i), 12, 0.1);
    f.a[10] = Vec3(0.05, 0.01 * i, 0.0);  // mode 11 > M = 6
    curves.push_back(f);
  }
  const SpectralPatch p =
      solve(SpectralOperator::fu(1.0), positions(curves), {6, UPlacement::Uniform});
  EXPECT_TRUE(p.hasRemainder());
  EXPECT_LT(maxOf(conditionErrors(p)), kConditionTolerance);
}

// ---------------------------------------------------------------------------------------
// Placement, fitting, spine.

TEST(SpectralPlacement, ChordLengthFollowsAverageCurveDistances) {
  std::vector<CurveInput> curves = {ring(1, Vec3(0, 0, 0), 3), ring(1, Vec3(0, 0, 1), 3),
                                    ring(1, Vec3(0, 0, 4), 3)};
  const std::vector<double> u =
      placeCurves(curves, UPlacement::ChordLength, VParameterization::Uniform);
  ASSERT_EQ(u.size(), 3u);
  EXPECT_NEAR(u[1], 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(u[2], 1.0);
  EXPECT_DOUBLE_EQ(SpectralOperator::ugail(7).a, 7.0);  // seed 003 §3.0.2 default
}

TEST(SpectralFourier, ErrorFallsAsTermsGrow) {
  const SampledCurve star = [] {
    SampledCurve c;
    for (int j = 0; j < 200; ++j) {
      const double t = kTwoPi * j / 200;
      const double r = 1.0 + 0.3 * std::cos(5 * t) + 0.1 * std::sin(9 * t);
      c.points.emplace_back(r * std::cos(t) + 0.2 * std::cos(2 * t), r * std::sin(t),
                            0.1 * std::sin(3 * t));
    }
    return c;
  }();
  double previous = 1e300, first = 0.0;
  for (std::uint32_t terms : {1u, 3u, 5u, 7u, 10u, 20u}) {
    const FourierFit fit = fitFourier(star, terms);  // chord-length v (the default)
    EXPECT_LE(fit.maxError, previous * (1 + 1e-12)) << terms;
    EXPECT_LE(fit.meanError, fit.maxError);
    if (terms == 1) first = fit.maxError;
    previous = fit.maxError;
  }
  EXPECT_LT(previous, 0.1 * first);
  // Uniform v recovers the generating series exactly.
  EXPECT_LT(fitFourier(star, 10, {VParameterization::Uniform}).maxError, 1e-12);
}

TEST(SpectralSpine, EditMovesTheSurfaceByExactlyTheSpineDifference) {
  std::vector<FourierCurve> curves;
  for (int i = 0; i < 6; ++i) curves.push_back(ring(1.0, Vec3(0.1 * i, 0, i), 4, 0.1));
  const SpectralPatch p =
      solve(SpectralOperator::ugail(3), positions(curves), {4, UPlacement::Uniform});
  SpineEdit edit;
  for (double u : {0.0, 0.3, 0.6, 1.0}) {
    edit.u.push_back(u);
    edit.moved.push_back(p.spine(u) + Vec3(0.5 * std::sin(3 * u), 0.2 * u, 0.0));
  }
  const SpectralPatch q = editSpine(p, edit);
  for (std::size_t j = 0; j < edit.u.size(); ++j)
    EXPECT_LT((q.spine(edit.u[j]) - edit.moved[j]).norm(), 1e-12);
  for (double u : {0.05, 0.45, 0.9})
    for (double v : {0.0, 1.7, 5.0}) {
      const Vec3 d = q.spine(u) - p.spine(u);
      EXPECT_LT((q.position(u, v) - p.position(u, v) - d).norm(), 1e-12);
      EXPECT_LT((q.derivative(u, v, 0, 1) - p.derivative(u, v, 0, 1)).norm(), 1e-12);
    }
  EXPECT_GT((q.spine(0.45) - p.spine(0.45)).norm(), 0.1);  // something did move
  const std::vector<Vec3> poly = spinePolyline(q, 5);
  EXPECT_LT((poly[4] - q.spine(1.0)).norm(), 1e-12);
}

// ---------------------------------------------------------------------------------------
// Chains.

std::vector<CurveInput> bentTube(int count, bool sampled) {
  std::vector<CurveInput> curves;
  for (int i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / (count - 1);
    const Vec3 centre(std::sin(2 * s), 0.3 * s * s, 3 * s);
    if (sampled) {
      SampledCurve c = squircle(0.5 + 0.2 * std::cos(3 * s), 0.0, 60, s);
      for (Vec3& p : c.points) p += centre + Vec3(0, 0, 0.2 * p.x());  // spatial, not planar
      curves.push_back(c);
    } else {
      curves.push_back(ring(0.5 + 0.2 * std::cos(3 * s), centre, 6, 0.05 * s, 0.1 * s));
    }
  }
  return curves;
}

TEST(SpectralChain, MethodTwoJoinsAreExactlyC2AndInterpolateEveryCurve) {
  for (int count : {4, 5, 6, 7, 8, 12, 15})
    for (bool sampled : {false, true})
      for (double a : {1.0, -1.0}) {
        SCOPED_TRACE("K = " + std::to_string(count) + (sampled ? " sampled" : " fourier") +
                     " a = " + std::to_string(a));
        const std::vector<CurveInput> curves = bentTube(count, sampled);
        CrossSectionOptions o;
        o.method = ChainMethod::ExactC2;
        o.a = a;
        const CrossSectionChain chain = solve(curves, o);
        for (const JointGap& g : measureJointGaps(chain)) {
          EXPECT_LT(g.c0Relative, kJointTolerance);
          EXPECT_LT(g.c1Relative, kJointTolerance);
          EXPECT_LT(g.c2Relative, kJointTolerance);
        }
        // Every curve is met where its patch places it.
        std::vector<int> met(count, 0);
        for (const ChainPatch& p : chain.patches) {
          EXPECT_LT(maxOf(conditionErrors(p.patch)), kConditionTolerance);
          const std::uint32_t q = p.lastCurve - p.firstCurve;
          for (std::uint32_t j = 0; j <= q; ++j) ++met[p.firstCurve + j];
        }
        for (int i = 0; i < count; ++i) EXPECT_GE(met[i], 1) << "curve " << i;
        EXPECT_EQ(chain.patches.front().firstCurve, 0u);
        EXPECT_EQ(chain.patches.back().lastCurve, static_cast<std::uint32_t>(count - 1));
      }
}

TEST(SpectralChain, MethodOneGapsAreMeasuredNotZero) {
  CrossSectionOptions o;
  o.method = ChainMethod::SharedCurves;
  const CrossSectionChain chain = solve(bentTube(12, false), o);
  ASSERT_EQ(chain.patches.size(), 3u);             // seed 002: C1-C6, C4-C9, C7-C12
  EXPECT_EQ(chain.patches[0].shownLastCurve, 3u);  // shown up to C4 (t = 0.6)
  EXPECT_DOUBLE_EQ(chain.patches[0].tEnd, 0.6);
  EXPECT_EQ(chain.patches[2].shownFirstCurve, 8u);  // from C9 (t = 0.4)
  const std::vector<JointGap> gaps = measureJointGaps(chain);
  ASSERT_EQ(gaps.size(), 2u);
  for (const JointGap& g : gaps) {
    EXPECT_LT(g.c0Relative, kJointTolerance);  // both windows interpolate the joint curve
    EXPECT_GT(g.c1Relative + g.c2Relative, 1e-6);
  }
}

// ---------------------------------------------------------------------------------------
// Errors.

void expectError(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no error, expected one mentioning '" << fragment << "'";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SpectralErrors, BadInputIsNamed) {
  const std::vector<FourierCurve> four = {ring(1, Vec3(0, 0, 0), 2), ring(1, Vec3(0, 0, 1), 2),
                                          ring(1, Vec3(0, 0, 2), 2), ring(1, Vec3(0, 0, 3), 2)};
  expectError([] { SpectralOperator::fu(0.0); }, "a != 0");
  expectError([] { SpectralOperator::ugail(0); }, "N >= 1");
  expectError([&] { solve(SpectralOperator::ugail(3), positions(four)); },
              "needs 6 conditions, got 4");
  expectError(
      [&] {
        auto c = positions(four);
        c[1].u = 0.0;
        c[0].u = 0.0;
        solve(SpectralOperator::ugail(2), c, {2, UPlacement::Given});
      },
      "no u given");
  expectError(
      [&] {
        auto c = positions(four);
        for (auto& x : c) x.u = 0.5;
        c[3].u = 1.0;
        solve(SpectralOperator::ugail(2), c, {2, UPlacement::Given});
      },
      "both fix derivative 0 at u = 0.5");
  expectError(
      [&] {
        auto c = positions(four);
        for (std::size_t i = 0; i < c.size(); ++i) {
          c[i].derivative = 1;
          c[i].u = i / 3.0;
        }
        solve(SpectralOperator::ugail(2), c, {2, UPlacement::Given});
      },
      "do not determine mode 0");
  SampledCurve open = squircle(1, 0, 20);
  open.closed = false;
  expectError([&] { fitFourier(open, 2); }, "open curve");
  SampledCurve two;
  two.points = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  expectError([&] { fitFourier(two, 1); }, "at least 3 points");
  expectError([&] { fitFourier(squircle(1, 0, 10), 6); }, "need at least 13 points");
  SampledCurve badV = squircle(1, 0, 4);
  badV.v = {0.0, 1.0, 1.0, 2.0};
  expectError([&] { fitFourier(badV, 1); }, "increase strictly");
  std::vector<CurveInput> three = {ring(1, Vec3(0, 0, 0), 2), ring(1, Vec3(0, 0, 1), 2),
                                   ring(1, Vec3(0, 0, 2), 2)};
  CrossSectionOptions c2;
  c2.method = ChainMethod::ExactC2;
  expectError([&] { solve(three, c2); }, "at least 4 curves, got 3");
  expectError([&] { solve(std::span(three).first(1)); },
              "(method \"global\") needs at least 2 curves, got 1");
  CrossSectionOptions m1;
  m1.method = ChainMethod::SharedCurves;
  expectError([&] { solve(bentTube(5, false), m1); }, "at least 6");
  std::vector<CurveInput> pinched = bentTube(6, true);
  SampledCurve point;
  point.points.assign(20, Vec3(0, 0, 1.5));
  pinched[2] = point;
  expectError([&] { solve(pinched); }, "curve 2: degenerate section");
  std::vector<CurveInput> same = {ring(1, Vec3(0, 0, 0), 2), ring(1, Vec3(0, 0, 0), 2)};
  expectError([&] { placeCurves(same, UPlacement::ChordLength, VParameterization::Uniform); },
              "coincide");
  expectError(
      [&] {
        editSpine(solve(SpectralOperator::ugail(2), positions(four), {2}),
                  SpineEdit{{0.5, 0.2}, {Vec3::Zero(), Vec3::Zero()}});
      },
      "increase strictly");
}

// ---------------------------------------------------------------------------------------
// Tessellation.

void expectUnitNormals(const Mesh& mesh) {
  for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
    const Vec3 n(mesh.normals[3 * k], mesh.normals[3 * k + 1], mesh.normals[3 * k + 2]);
    ASSERT_TRUE(n.allFinite());
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
  }
}

TEST(SpectralTessellate, TubeIsWatertightAcrossTheSeamWithOutwardNormals) {
  std::vector<FourierCurve> curves;
  for (int i = 0; i < 4; ++i) curves.push_back(ring(1.0 + 0.1 * i, Vec3(0, 0, i), 3, 0.1));
  const SpectralPatch p =
      solve(SpectralOperator::ugail(2), positions(curves), {3, UPlacement::Uniform});
  TessellateOptions o{.resolution = 9, .aroundResolution = 16};
  const Mesh mesh = tessellate(p, o);
  EXPECT_EQ(mesh.vertexCount(), 9u * 16u);  // the seam column is shared
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.boundaryEdges, 2u * 16u);  // only the two open ends
  EXPECT_EQ(stats.nonManifoldEdges, 0u);
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
  expectUnitNormals(mesh);
  EXPECT_GT(testing::minCornerNormalAgreement(mesh), 0.8);
  for (std::size_t k = 0; k < mesh.vertexCount(); ++k) {
    const Vec3 pos(mesh.positions[3 * k], mesh.positions[3 * k + 1], mesh.positions[3 * k + 2]);
    const Vec3 n(mesh.normals[3 * k], mesh.normals[3 * k + 1], mesh.normals[3 * k + 2]);
    const Vec3 radial(pos.x(), pos.y(), 0.0);  // the tube's axis is z
    EXPECT_GT(n.dot(radial), 0.0);
  }
}

TEST(SpectralTessellate, ChainSharesJointVerticesAndTipsCollapse) {
  std::vector<CurveInput> curves = bentTube(9, false);
  SampledCurve tip;
  tip.points.assign(20, Vec3(0, 0, -0.5));
  curves.insert(curves.begin(), tip);  // a collapsed first section: a closed end
  const CrossSectionChain chain = solve(curves);
  TessellateOptions o{.resolution = 5, .aroundResolution = 12};
  const Mesh mesh = tessellate(chain, o);
  const std::size_t rows = chain.patches.size() * 4 + 1;
  EXPECT_EQ(mesh.vertexCount(), (rows - 1) * 12 + 1);  // joints shared, the tip is one vertex
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.boundaryEdges, 12u);  // only the open far end
  EXPECT_EQ(stats.nonManifoldEdges, 0u);
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
  expectUnitNormals(mesh);
  ASSERT_EQ(mesh.patchIds.size(), mesh.triangleCount());
  EXPECT_EQ(mesh.patchIds.back(), chain.patches.size() - 1);
}

}  // namespace
}  // namespace pdesurf
