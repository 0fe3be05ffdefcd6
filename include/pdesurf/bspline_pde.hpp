// Bicubic B-spline surfaces whose inner control points solve ∂⁶x/∂u³∂v³ = 0 on every span
// (seed 004, Wu & Zhu 2021): docs/bspline-pde.md and docs/derivations.md §3. The operator is
// constant on each bicubic span, so the PDE is one 4×4 mask equation per span pair; with control
// rows 0, 1, n_u and columns 0, 1, n_v given, the inner points solve M X Nᵀ = Y, banded in M, N.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/geometry.hpp"  // Vec3, SurfacePoint
#include "pdesurf/mesh.hpp"

namespace pdesurf {

// ---------------------------------------------------------------------------------------
// Tolerances.

/// Relative distance (to the net's extent) below which two corner points given by two
/// boundary curves count as the same point.
constexpr double kBSplineCornerTolerance = 1e-9;

/// Relative size (to the net's extent squared) of |x_u × x_v| below which a tessellation
/// normal is not taken from the analytic derivatives at that point (poles, collapsed rows).
constexpr double kBSplineDegenerateNormalTolerance = 1e-10;

// ---------------------------------------------------------------------------------------
// Knots.

/// The two knot vectors of seed 004. Both have n + 5 knots for control points 0..n, a
/// parameter domain [t_3, t_{n+1}] = [0, 1] and interior spacing λ = 1/(n-2).
enum class KnotType {
  Uniform,  ///< t_k = (k-3)λ for k = 0..n+4: the domain is the n-2 spans where 4 points act
  Clamped   ///< quasi-uniform (seed §3.2): t_0..t_3 = 0, t_{n+1}..t_{n+4} = 1
};

/// The n + 5 knots of a cubic B-spline with control points 0..n (n ≥ 3).
std::vector<double> cubicKnots(KnotType type, std::uint32_t n);

// ---------------------------------------------------------------------------------------
// Control nets and surfaces.

/// (nu + 1) × (nv + 1) control points P_{i,j}, i along u, stored row by row:
/// P_{i,j} = points[i (nv + 1) + j].
struct ControlNet {
  std::uint32_t nu = 0, nv = 0;  ///< the last indices n_u, n_v
  std::vector<Vec3> points;

  ControlNet() = default;
  /// A net of the given last indices with every point set to `fill`.
  ControlNet(std::uint32_t lastU, std::uint32_t lastV, const Vec3& fill = Vec3::Zero());

  Vec3& operator()(std::uint32_t i, std::uint32_t j) { return points[i * (nv + 1) + j]; }
  const Vec3& operator()(std::uint32_t i, std::uint32_t j) const {
    return points[i * (nv + 1) + j];
  }
  /// Whether P_{i,j} is one of the points the PDE solve keeps (seed condition 3.1): rows
  /// 0, 1, nu and columns 0, 1, nv. The other (nu-2)(nv-2) points are the unknowns.
  bool given(std::uint32_t i, std::uint32_t j) const {
    return i <= 1 || i == nu || j <= 1 || j == nv;
  }
};

/// The values of the 4 cubic basis functions that act at a parameter, and their first three
/// derivatives: basis N_{span-3+r} has derivative k equal to d[k][r].
struct CubicBasis {
  std::uint32_t span = 3;  ///< the knot span [t_span, t_{span+1}), 3 ≤ span ≤ n
  std::array<std::array<double, 4>, 4> d{};
};

/// A bicubic B-spline surface x(u,v) = Σ N_i(u) N_j(v) P_{i,j} on [0,1]² (seed eq. 2.1).
/// A value: construction validates; evaluation is const. Outside [0,1] the end spans'
/// polynomials extend.
class BSplineSurface {
 public:
  /// Throws InvalidArgument for nu or nv < 3, a point count other than
  /// (nu+1)(nv+1), or a non-finite point (naming its (i, j)).
  BSplineSurface(ControlNet net, KnotType uKnots, KnotType vKnots);

  const ControlNet& net() const { return net_; }
  KnotType uKnotType() const { return uType_; }
  KnotType vKnotType() const { return vType_; }
  std::span<const double> uKnots() const { return uKnots_; }
  std::span<const double> vKnots() const { return vKnots_; }
  /// Knot spans per direction: nu - 2 and nv - 2.
  std::uint32_t uSpans() const { return net_.nu - 2; }
  std::uint32_t vSpans() const { return net_.nv - 2; }

  Vec3 position(double u, double v) const;
  /// x, x_u, x_v.
  SurfacePoint evaluate(double u, double v) const;
  /// ∂^(a+b) x / ∂u^a ∂v^b for a, b ≤ 3, from the span containing (u, v) (at a knot: the
  /// span to its right, the last span at 1). (3, 3) is constant on each span.
  Vec3 derivative(double u, double v, int a, int b) const;

  /// The basis functions acting at u (resp. v): a row of a per-u (per-v) table.
  CubicBasis uBasis(double u) const;
  CubicBasis vBasis(double v) const;
  /// Position and first derivatives from precomputed basis rows (one per u, one per v).
  SurfacePoint evaluate(const CubicBasis& bu, const CubicBasis& bv) const;

  /// x, x_u, x_v at every (us[a], vs[b]), stored out[a * vs.size() + b]; the basis of each
  /// u and each v is computed once.
  void evaluateGrid(std::span<const double> us, std::span<const double> vs,
                    std::vector<SurfacePoint>& out) const;

 private:
  ControlNet net_;
  KnotType uType_, vType_;
  std::vector<double> uKnots_, vKnots_;
};

// ---------------------------------------------------------------------------------------
// The PDE solve.

struct BSplinePdeOptions {
  KnotType uKnots = KnotType::Clamped;
  KnotType vKnots = KnotType::Clamped;
};

/// The surface whose control rows 0, 1, nu and columns 0, 1, nv are those of `net` and whose
/// inner points P_{i,j} (2 ≤ i ≤ nu-1, 2 ≤ j ≤ nv-1; their values in `net` are ignored)
/// make ∂⁶x/∂u³∂v³ = 0 on all (nu-2)(nv-2) spans: one mask equation per span, as many as
/// unknowns, solved as X = M⁻¹ Y N⁻ᵀ with banded LU of M and N, in O(nu nv) (Y has rank ≤ 6).
/// Throws InvalidArgument as BSplineSurface does, the inner points exempt from the
/// finiteness check.
BSplineSurface solve(const ControlNet& net, const BSplinePdeOptions& options = {});

/// The same solve with M and N factored once, for many nets of one size (an editor). The
/// const members keep no scratch state: one solver may serve several threads.
class BSplinePdeSolver {
 public:
  /// Throws InvalidArgument for nu or nv < 3.
  BSplinePdeSolver(std::uint32_t nu, std::uint32_t nv, const BSplinePdeOptions& options = {});
  ~BSplinePdeSolver();
  BSplinePdeSolver(BSplinePdeSolver&&) noexcept;
  BSplinePdeSolver& operator=(BSplinePdeSolver&&) noexcept;

  /// Overwrites the inner points of `net` (validated: size and given points finite).
  void solveInPlace(ControlNet& net) const;
  BSplineSurface solve(const ControlNet& net) const;

  std::uint32_t nu() const;
  std::uint32_t nv() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// How far a surface is from solving the PDE: the largest, over span pairs, |∂⁶x/∂u³∂v³| at
/// the span's centre over Σ |t_s[k] t̃_r[l]| |P| of the same span (the size of the terms that
/// cancel). Rounding level (≈ 1e-15) for a solved surface; O(1) for an arbitrary one.
double pdeResidual(const BSplineSurface& surface);

/// The mask row of span s (3 ≤ s ≤ n) of a cubic knot vector: t[r] = N'''_{s-3+r} on
/// [t_s, t_{s+1}) (seed eq. 2.7, computed from the basis, not from eq. 3.10).
std::array<double, 4> thirdDerivativeMask(std::span<const double> knots, std::uint32_t span);

/// M (or N): the (n-2)×(n-2) matrix of the unknowns 2..n-1 in the span equations 3..n,
/// M(s-3, k-2) = t_s[k-s+3]. Dense, for tests and documentation; the solver keeps it banded.
Eigen::MatrixXd pdeSystemMatrix(KnotType type, std::uint32_t n);

// ---------------------------------------------------------------------------------------
// Boundaries from curves.

/// A cubic B-spline curve on [0, 1] with control points 0..n (n ≥ 3).
struct BSplineCurve {
  std::vector<Vec3> points;
  KnotType knots = KnotType::Clamped;
  /// The k-th derivative (k ≤ 3) at t. Throws InvalidArgument for fewer than 4 points.
  Vec3 evaluate(double t, int k = 0) const;
};

/// A curve as samples: points in order and their parameters in [0, 1] (strictly
/// increasing, first 0 and last 1), or no parameters (then chord length).
struct CurveSamples {
  std::vector<Vec3> points;
  std::vector<double> t;
};

using BoundaryCurve = std::variant<BSplineCurve, CurveSamples>;

/// A cross-boundary derivative along a side, as a function of the side's parameter in [0, 1].
using TangentFunction = std::function<Vec3(double)>;

/// The second row (or column) of the net: its control points as given (nv + 1, resp. nu + 1
/// of them), or the cross-boundary derivative the surface should have along that side.
using SecondRow = std::variant<std::vector<Vec3>, TangentFunction>;

/// Four boundary curves and the two second rows the PDE needs (seed condition 3.1).
/// Curve `uMin` is x(0, v) (nv + 1 control points), `uMax` x(1, v), `vMin` x(u, 0)
/// (nu + 1 control points), `vMax` x(u, 1); each runs with its own parameter increasing.
struct BSplineBoundary {
  std::uint32_t nu = 3, nv = 3;
  BSplinePdeOptions knots;
  BoundaryCurve uMin, uMax, vMin, vMax;
  SecondRow uMinSecond;  ///< row 1: P_{1,j}, or ∂x/∂u (0, v)
  SecondRow vMinSecond;  ///< column 1: P_{i,1}, or ∂x/∂v (u, 0)
};

/// How many samples per control point a curve given with another control point count is
/// resampled at before the least-squares fit.
constexpr std::uint32_t kBoundaryResampleFactor = 8;

/// The known rows and columns (0, 1, nu; 0, 1, nv) of a net built from a boundary; the inner
/// points are zero. Rules (docs/bspline-pde.md): a B-spline curve with the right count and
/// knot type is copied; any other curve is fitted by least squares on the side's knots, its
/// ends interpolated (clamped knots only). A tangent function T gives P_{1,j} = P_{0,j} +
/// (λ/3) D_j with D the least-squares fit of T (clamped knots only: x_u(0,v) = (3/λ) Σ (P_{1,j}
/// - P_{0,j}) N_j(v)). The boundary curves win where they own a point (P_{1,0}, P_{0,1},
/// P_{1,nv}, P_{nu,1}); P_{1,1} is the mean of what the row and the column give. Throws
/// InvalidArgument naming the side for corners that disagree, wrong counts, non-finite
/// values, samples too few or badly parameterized, or a tangent on uniform knots.
ControlNet boundaryNet(const BSplineBoundary& boundary);

// ---------------------------------------------------------------------------------------
// C1 blends (seed Examples 4 and 5).

/// Clamped bicubic pieces on a global parameter domain made of unit squares: piece k covers
/// [origin[k][0], +1] × [origin[k][1], +1] with local (u, v) = (U − origin₀, V − origin₁).
struct C1Blend {
  std::vector<BSplineSurface> pieces;
  std::vector<std::array<std::uint32_t, 2>> origin;
  /// The global V direction closes on itself (Example 5): V = 2 is V = 0.
  bool closedV = false;
  /// max |mask or C1 equation| (rows scaled to a largest coefficient of 1) / extent
  double maxConstraintResidual = 0.0;
  double maxC1Gap = 0.0;  ///< max |∂x/∂U (or ∂V) left − right| over the seams / max |∂x|
  /// The same per seam: "U = 1", "V = 1" (Example 4); "V = 1", "V = 0" (Example 5, where
  /// V = 0 is V = 2).
  std::vector<std::pair<std::string, double>> seamGaps;
};

/// Example 4. The four curves of a 4-sided region on [0, 2]² (each clamped, any point count;
/// corners shared) become one surface made of 2 × 2 PDE pieces with n + 1 control points a
/// side (n ≥ 3), C1 across the seams U = 1 and V = 1; piece (p, q) is pieces[2p + q]. The rule
/// for the seam and second-row points the seed leaves "chosen" (docs/bspline-pde.md): every
/// piece solves the PDE on every span, the seams are C1 (equal spans: P_{n-1} + P_{n+1} =
/// 2 P_n across each), the boundary is the curves (refitted on 2(n-2) uniform spans and split
/// at 1/2 by knot insertion), and the remaining freedom minimises the global net's discrete
/// thin-plate energy. Dense: O(n⁶). Throws InvalidArgument naming the curve for fewer
/// than 4 points, knots other than clamped, a non-finite point, corners that do not meet; and
/// for n < 3.
C1Blend blendFourCurves(const BSplineCurve& uMin, const BSplineCurve& uMax,
                        const BSplineCurve& vMin, const BSplineCurve& vMax, std::uint32_t n);

/// Example 5. Two closed curves (clamped, first point = last point) become a closed tube of
/// 1 × 2 PDE pieces, x(0, V) on `start` and x(1, V) on `end`, V ∈ [0, 2] once around; each
/// curve is refitted on 2(n-2) spans, made C1 where it closes (the two end legs replaced by
/// their mean) and split at 1/2. The seams V = 1 and V = 0 ≡ 2 are C1; the other points follow
/// the same rule as blendFourCurves (PDE on every span, least thin-plate energy, periodic in
/// V). Throws InvalidArgument as blendFourCurves does, and for a curve that is not closed.
C1Blend blendClosedCurves(const BSplineCurve& start, const BSplineCurve& end, std::uint32_t n);

// ---------------------------------------------------------------------------------------
// Tessellation.

/// A grid mesh over [0,1]²: (uSpans·s + 1) × (vSpans·s + 1) vertices for s segments per knot
/// span, the fewest that give at least options.resolution − 1 segments along the side with
/// more spans; row by row in u, with analytic unit normals x_u × x_v (at a degenerate point:
/// taken just inside the domain, else the mean of the adjacent faces). patchIds[t] = the
/// span (a, b) of triangle t as a·vSpans + b. Throws InvalidArgument as checkTessellateOptions.
Mesh tessellate(const BSplineSurface& surface, const TessellateOptions& options = {});

}  // namespace pdesurf
