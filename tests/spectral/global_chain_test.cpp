// The global C4 cross-section chain (docs/spectral.md, "The global chain"): C4 joints,
// natural ends, convergence on closed-form surfaces as the section count grows, stability
// at 200 sections, and the short-patch series basis it relies on.
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral.hpp"
#include "spectral/basis.hpp"

namespace pdesurf {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Bounds C0, C1 and C2 gaps at joints relative to the chain's extent: positions and the
/// shared derivatives are conditions of both patches, met to ~1e-14.
constexpr double kJointTolerance = 1e-9;
/// Bounds the jump of ∂³u and ∂⁴u at an interior joint relative to the largest ∂³u (∂⁴u)
/// over the joints: the banded system is solved in double with rows equilibrated, so its
/// equations hold to ~1e-13 of their largest term; 1e-7 leaves room for the patches' own
/// re-solve of the same data.
constexpr double kHigherJointTolerance = 1e-7;

/// A star-shaped tube: ρ(z, θ) = R(z)(1 + 0.15 cos 3θ), R(z) = 1 + 0.3 sin 2z + 0.1 z, z ∈ [0, 3].
/// Its section at z is a 4-mode Fourier curve in θ, so a chain with M ≥ 4 carries it exactly
/// around v and every error is the chain's, along u.
double radius(double z) { return 1.0 + 0.3 * std::sin(2.0 * z) + 0.1 * z; }

Vec3 starTube(double z, double theta) {
  const double rho = radius(z) * (1.0 + 0.15 * std::cos(3.0 * theta));
  return {rho * std::cos(theta), rho * std::sin(theta), z};
}

FourierCurve starSection(double z, std::uint32_t modes) {
  const double r = radius(z);
  FourierCurve c;
  c.a0 = Vec3(0, 0, z);
  c.a.assign(modes, Vec3::Zero());
  c.b.assign(modes, Vec3::Zero());
  // cos θ (1 + ε cos 3θ) = cos θ + ε/2 (cos 2θ + cos 4θ); sin θ (1 + ε cos 3θ) = sin θ +
  // ε/2 (sin 4θ − sin 2θ), ε = 0.15.
  c.a[0] = Vec3(r, 0, 0);
  c.b[0] = Vec3(0, r, 0);
  c.a[1] = Vec3(0.075 * r, 0, 0);
  c.b[1] = Vec3(0, -0.075 * r, 0);
  c.a[3] = Vec3(0.075 * r, 0, 0);
  c.b[3] = Vec3(0, 0.075 * r, 0);
  return c;
}

/// A bent tube: centre c(s) = (0.8 sin 2s, 0, 2s), radius r(s) = 0.4 + 0.1 cos 3s, sections
/// in the planes normal to the centre line (y is always normal to it), s ∈ [0, 1.5].
Vec3 bentTube(double s, double theta, Vec3* centreOut = nullptr) {
  const Vec3 centre(0.8 * std::sin(2.0 * s), 0.0, 2.0 * s);
  const Vec3 tangent = Vec3(1.6 * std::cos(2.0 * s), 0.0, 2.0).normalized();
  const Vec3 n1 = Vec3::UnitY(), n2 = tangent.cross(n1);
  if (centreOut) *centreOut = centre;
  const double r = 0.4 + 0.1 * std::cos(3.0 * s);
  return centre + r * (std::cos(theta) * n2 + std::sin(theta) * n1);
}

FourierCurve bentSection(double s, std::uint32_t modes) {
  Vec3 centre;
  const Vec3 x0 = bentTube(s, 0.0, &centre), x1 = bentTube(s, 0.5 * std::numbers::pi);
  FourierCurve c;
  c.a0 = centre;
  c.a.assign(modes, Vec3::Zero());
  c.b.assign(modes, Vec3::Zero());
  c.a[0] = x0 - centre;
  c.b[0] = x1 - centre;
  return c;
}

struct Case {
  const char* name;
  double from, to;
  Vec3 (*surface)(double, double);
  FourierCurve (*section)(double, std::uint32_t);
};
Vec3 bentSurface(double s, double theta) { return bentTube(s, theta); }
const Case kStar{"star tube", 0.0, 3.0, starTube, starSection};
const Case kBent{"bent tube", 0.0, 1.5, bentSurface, bentSection};

CrossSectionChain chainOf(const Case& c, int count, const CrossSectionOptions& base) {
  std::vector<CurveInput> curves;
  CrossSectionOptions o = base;
  o.u.clear();
  for (int i = 0; i < count; ++i) {
    const double s = c.from + (c.to - c.from) * i / (count - 1);
    curves.push_back(c.section(s, o.modes));
    o.u.push_back(s);  // the surface's own parameter: errors are parametric
  }
  return solve(curves, o);
}

/// max over a grid of |chain(u, v) − surface(s(u), v)|: an upper bound of the distance.
double parametricError(const Case& c, const CrossSectionChain& chain) {
  double worst = 0.0;
  for (const ChainPatch& p : chain.patches) {
    const double u0 = chain.curveU[p.firstCurve], u1 = chain.curveU[p.lastCurve];
    for (int r = 0; r <= 8; ++r) {
      const double t = r / 8.0, u = u0 + (u1 - u0) * t;
      for (int j = 0; j < 24; ++j) {
        const double v = kTwoPi * j / 24;
        const Vec3 truth = c.surface(c.from + (c.to - c.from) * u, v);
        worst = std::max(worst, (p.patch.position(t, v) - truth).norm());
      }
    }
  }
  return worst;
}

/// Largest jump of ∂^k u X (k = 3, 4) at interior joints over v, relative to its size.
double higherJointJump(const CrossSectionChain& chain, std::uint32_t k) {
  double jump = 0.0, size = 0.0;
  for (std::size_t i = 0; i + 1 < chain.patches.size(); ++i) {
    const ChainPatch &a = chain.patches[i], &b = chain.patches[i + 1];
    for (int j = 0; j < 32; ++j) {
      const double v = kTwoPi * j / 32;
      const Vec3 da = a.patch.derivative(1.0, v, k, 0) / std::pow(a.length, k);
      const Vec3 db = b.patch.derivative(0.0, v, k, 0) / std::pow(b.length, k);
      jump = std::max(jump, (da - db).norm());
      size = std::max({size, da.norm(), db.norm()});
    }
  }
  return size > 0.0 ? jump / size : jump;
}

TEST(GlobalChain, JointsAreC4AndEndsNatural) {
  for (const Case* c : {&kStar, &kBent})
    for (double a : {1.0, -1.0, 40.0})
      for (int count : {2, 3, 7, 12}) {
        SCOPED_TRACE(std::string(c->name) + " a = " + std::to_string(a) +
                     " K = " + std::to_string(count));
        CrossSectionOptions o;
        o.a = a;
        o.modes = 6;
        const CrossSectionChain chain = chainOf(*c, count, o);
        ASSERT_EQ(chain.patches.size(), static_cast<std::size_t>(count - 1));
        for (const JointGap& g : measureJointGaps(chain)) {
          EXPECT_LT(g.c0Relative, kJointTolerance);
          EXPECT_LT(g.c1Relative, kJointTolerance);
          EXPECT_LT(g.c2Relative, kJointTolerance);
        }
        EXPECT_LT(higherJointJump(chain, 3), kHigherJointTolerance);
        EXPECT_LT(higherJointJump(chain, 4), kHigherJointTolerance);
        // Natural ends: ∂³u X = ∂⁴u X = 0 at both ends, relative to ∂³u X in the middle.
        double middle = 0.0, ends = 0.0;
        for (int j = 0; j < 16; ++j) {
          const double v = kTwoPi * j / 16;
          for (const ChainPatch* p : {&chain.patches.front(), &chain.patches.back()}) {
            middle = std::max(middle, p->patch.derivative(0.5, v, 3, 0).norm());
            middle = std::max(middle, p->patch.derivative(0.5, v, 4, 0).norm());
          }
          for (std::uint32_t k : {3u, 4u}) {
            ends = std::max(ends, chain.patches.front().patch.derivative(0.0, v, k, 0).norm());
            ends = std::max(ends, chain.patches.back().patch.derivative(1.0, v, k, 0).norm());
          }
        }
        EXPECT_LT(ends, kHigherJointTolerance * std::max(middle, 1.0));
        // Every curve is met: the position conditions of both neighbours.
        for (const ChainPatch& p : chain.patches)
          for (double e : conditionErrors(p.patch)) EXPECT_LT(e, kJointTolerance);
      }
}

/// The error table of docs/spectral.md ("Convergence"): printed, and checked to fall at
/// every doubling with at least the order each end condition gives.
TEST(GlobalChain, ErrorFallsWithTheSectionCountOnClosedForms) {
  struct Ends {
    ChainEnds ends;
    const char* name;
    double order;  ///< the observed order must reach this over the last two doublings
  };
  // Natural ends impose ∂³u = 0 where the surface has ∂³u ≠ 0: an O(h³) boundary layer
  // (as the natural cubic spline's O(h²)); estimated ends use the end curves' quintic: O(h⁵).
  for (const Ends& e :
       {Ends{ChainEnds::Natural, "natural", 2.5}, Ends{ChainEnds::Estimated, "estimated", 4.0}})
    for (const Case* c : {&kStar, &kBent}) {
      CrossSectionOptions o;
      o.ends = e.ends;
      o.modes = 6;
      std::vector<double> errors;
      std::string table = std::string(c->name) + ", " + e.name + " ends:";
      for (int count : {5, 9, 17, 33, 65}) {
        errors.push_back(parametricError(*c, chainOf(*c, count, o)));
        char cell[64];
        std::snprintf(cell, sizeof cell, " K=%d %.3g", count, errors.back());
        table += cell;
        if (errors.size() > 1) {
          std::snprintf(cell, sizeof cell, " (order %.2f)",
                        std::log2(errors[errors.size() - 2] / errors.back()));
          table += cell;
        }
      }
      std::printf("%s\n", table.c_str());
      for (std::size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], errors[i - 1]) << table;
      const double order = std::log2(errors[errors.size() - 3] / errors.back()) / 2.0;
      EXPECT_GE(order, e.order) << table;
    }
}

TEST(GlobalChain, TwoHundredSectionsLoseNoAccuracy) {
  CrossSectionOptions o;
  o.modes = 6;
  for (const Case* c : {&kStar, &kBent}) {
    SCOPED_TRACE(c->name);
    const double at65 = parametricError(*c, chainOf(*c, 65, o));
    const CrossSectionChain dense = chainOf(*c, 200, o);
    EXPECT_LE(parametricError(*c, dense), at65);
    for (const JointGap& g : measureJointGaps(dense, 32)) {
      EXPECT_LT(g.c0Relative, kJointTolerance);
      EXPECT_LT(g.c1Relative, kJointTolerance);
      EXPECT_LT(g.c2Relative, kJointTolerance);
    }
    for (const ChainPatch& p : dense.patches)
      for (double e : conditionErrors(p.patch, 33)) EXPECT_LT(e, kJointTolerance);
  }
}

TEST(GlobalChain, SpacingFollowsCentroidsAndIsRefusedWhenItCollapses) {
  std::vector<CurveInput> curves;
  for (double z : {0.0, 0.5, 2.0}) curves.push_back(starSection(z, 4));
  const CrossSectionChain chain = solve(curves, {});
  ASSERT_EQ(chain.curveU.size(), 3u);
  EXPECT_DOUBLE_EQ(chain.curveU[0], 0.0);
  EXPECT_NEAR(chain.curveU[1], 0.25, 1e-15);
  EXPECT_DOUBLE_EQ(chain.curveU[2], 1.0);
  curves[1] = starSection(0.0, 4);  // same centroid as curve 0
  try {
    solve(curves, {});
    FAIL() << "coincident centroids accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("curves 0 and 1 have the same centroid"),
              std::string::npos)
        << e.what();
  }
  CrossSectionOptions uniform;
  uniform.spacing = ChainSpacing::Uniform;  // then the same curves are fine
  EXPECT_NEAR(solve(curves, uniform).curveU[1], 0.5, 1e-15);
  CrossSectionOptions given;
  given.u = {0.0, 2.0, 1.0};
  EXPECT_THROW(solve(curves, given), InvalidArgument);
}

/// Short patches: the series basis (basis.hpp) is y_k with y_k^(j)(0) = δ_jk, which the
/// six simple exponentials give independently as y_k(t) = (1/6) Σ_j μ_j^{-k} e^{μ_j t}, μ_j the
/// sixth roots of c (evaluated here in complex long double where they are well conditioned).
TEST(GlobalChain, SeriesBasisMatchesTheExponentials) {
  using Complex = std::complex<long double>;
  for (double a : {1.0, -1.0})
    for (double length : {0.1, 0.25, 0.3}) {
      const std::uint32_t n = 3;
      const auto roots = spectral::modeRoots(SpectralOperator::fu(a), n, length);
      ASSERT_EQ(roots.size(), 1u);
      ASSERT_TRUE(roots[0].series);
      const spectral::ModeBasis basis(roots);
      const long double kappa = n * length;  // |a| = 1
      for (double t : {0.0, 0.3, 1.0}) {
        spectral::MatrixR table;
        basis.evaluate(t, 5, table);
        for (int k = 0; k < 6; ++k)
          for (int d = 0; d < 6; ++d) {
            Complex sum = 0;
            for (int j = 0; j < 6; ++j) {
              const long double arg = (a > 0 ? 0.0L : std::numbers::pi_v<long double> / 6) +
                                      j * std::numbers::pi_v<long double> / 3;
              const Complex mu = std::polar(kappa, arg);
              sum += std::pow(mu, d - k) * std::exp(mu * static_cast<long double>(t));
            }
            const long double expected = sum.real() / 6;
            // The exponentials lose κ^{-5} ≈ 1e3..1e5 ulps of long double; 1e-12 is far
            // above that and far below any wrong coefficient.
            EXPECT_NEAR(static_cast<double>(table(d, k)), static_cast<double>(expected), 1e-12)
                << "a " << a << " length " << length << " t " << t << " y_" << k << "^(" << d
                << ")";
          }
      }
    }
  // At κ ≥ 1 the exponentials are used.
  EXPECT_FALSE(spectral::modeRoots(SpectralOperator::fu(1.0), 3, 0.34)[0].series);
}

}  // namespace
}  // namespace pdesurf
