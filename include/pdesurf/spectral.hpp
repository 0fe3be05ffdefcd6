// Periodic spectral PDE patches (seed 003, Ugail 2007; seed 002, Fu et al. 2021) as one
// engine: docs/spectral.md and docs/derivations.md §2. A patch is
//   X(u,v) = A0(u) + Σ_{n=1..M} [An(u) cos nv + Bn(u) sin nv] + R(u,v)
// where each mode solves the ODE its operator gives it and R is the remainder that makes
// conditions which are not finite Fourier series hold exactly.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/geometry.hpp"  // Vec3, SurfacePoint
#include "pdesurf/mesh.hpp"

namespace pdesurf {

// ---------------------------------------------------------------------------------------
// Tolerances.

/// Relative size (to the curve's extent) below which all points of a closed curve count
/// as one point: a collapsed section (a shell tip) rather than a curve.
constexpr double kDegenerateCurveTolerance = 1e-12;

/// Relative size (to the model's extent) of |S_u × S_v| below which a tessellation
/// normal is not taken from the analytic derivatives (collapsed rows, poles).
constexpr double kDegenerateNormalTolerance = 1e-10;

// ---------------------------------------------------------------------------------------
// Closed curves (periodic in v ∈ [0, 2π)).

/// x(v) = a0 + Σ_{n=1..N} [a_n cos nv + b_n sin nv], per component (the seeds'
/// "generalised elliptic curve"; a[n-1], b[n-1] hold mode n).
struct FourierCurve {
  Vec3 a0 = Vec3::Zero();
  std::vector<Vec3> a, b;

  std::uint32_t terms() const { return static_cast<std::uint32_t>(a.size()); }
  /// The k-th v-derivative at v (k = 0: the point).
  Vec3 evaluate(double v, std::uint32_t k = 0) const;
};

/// How v values are given to points that come without them.
enum class VParameterization {
  Uniform,     ///< v_j = 2π j / count
  ChordLength  ///< v proportional to arc length along the closed polygon, mapped to [0, 2π)
};

/// A closed curve as points. `v` is empty (then `VParameterization` decides) or holds one
/// strictly increasing value in [0, 2π) per point. A last point equal to the first (the
/// closing point written twice) is dropped. `closed = false` is rejected: the method is
/// periodic in v.
struct SampledCurve {
  std::vector<Vec3> points;
  std::vector<double> v;
  bool closed = true;
};

/// A curve as the user gave it: points, or Fourier coefficients.
using CurveInput = std::variant<SampledCurve, FourierCurve>;

struct FourierFitOptions {
  VParameterization parameterization = VParameterization::ChordLength;
};

/// A least-squares Fourier fit and its point distance errors (seed 002 Table 1).
struct FourierFit {
  FourierCurve curve;
  std::vector<Vec3> points;  ///< the points fitted (closing duplicate dropped)
  std::vector<double> v;     ///< the parameter of each point
  double maxError = 0.0;     ///< max_j |curve(v_j) - p_j|
  double meanError = 0.0;    ///< mean_j |curve(v_j) - p_j|
};

/// The v values of a sampled curve (given, uniform or chord length), validated: throws
/// InvalidArgument naming the problem (too few points, open curve, v out of range or
/// not increasing, chord length of a curve whose points all coincide).
std::vector<double> curveParameters(const SampledCurve& curve, VParameterization parameterization);

/// Linear least squares for a0, a_n, b_n (n ≤ terms). Needs at least 2·terms + 1 points.
FourierFit fitFourier(const SampledCurve& curve, std::uint32_t terms,
                      const FourierFitOptions& options = {});

// ---------------------------------------------------------------------------------------
// Operators.

enum class OperatorKind {
  Ugail,  ///< (∂²u + a² ∂²v)^N, order 2N (seed 003 eq. 7)
  Fu      ///< ∂⁶u + a ∂⁶v, order 6, a ≠ 0 (seed 002 eq. 2)
};

struct SpectralOperator {
  OperatorKind kind = OperatorKind::Ugail;
  std::uint32_t power = 2;  ///< Ugail's N (≥ 1); 3 for Fu
  double a = 2.0;

  /// Ugail's operator; a defaults to N (seed 003 §3.0.2).
  static SpectralOperator ugail(std::uint32_t n, std::optional<double> a = std::nullopt);
  static SpectralOperator fu(double a);
  std::uint32_t order() const { return kind == OperatorKind::Fu ? 6u : 2u * power; }
  /// Throws InvalidArgument for N < 1, a = 0 (Fu), a not finite or a ≤ 0 (Ugail).
  void validate() const;
};

// ---------------------------------------------------------------------------------------
// One patch.

/// Where the conditions sit along u when they come without a `u`.
enum class UPlacement {
  Given,       ///< every condition has its u
  Uniform,     ///< position curves evenly over [0, 1]
  ChordLength  ///< position curves proportional to the average distance between
               ///< consecutive curves (seed 003 §3.0.1), u = 0 first, u = 1 last
};

/// A linear functional on the patch: ∂^derivative X/∂u^derivative (u, v) = curve(v).
/// Without `u`, a position curve is placed by `UPlacement`, and a derivative condition takes
/// the u of the position condition before it (seed 003 eqs. 32–35).
struct SpectralCondition {
  std::uint32_t derivative = 0;
  std::optional<double> u;
  CurveInput curve;
};

struct SpectralOptions {
  std::uint32_t modes = 6;  ///< M: Fourier modes solved exactly (seed 003: 6 is typical)
  UPlacement placement = UPlacement::Uniform;
  VParameterization parameterization = VParameterization::ChordLength;
  /// Add the remainder R(u,v) so that curves that are not M-mode Fourier series are met
  /// exactly (docs/derivations.md §2.3). Off: the surface meets the M-mode truncation of each
  /// curve.
  bool remainder = true;
};

namespace spectral {
struct SpectralTailData;  // the remainder (src/spectral/internal.hpp)
class ModeBasis;          // per-mode solution basis (src/spectral/basis.hpp)
}  // namespace spectral

/// A natural cubic spline D(u) through knots (linear beyond the end knots): a spine edit.
struct SpineOffset {
  std::vector<double> knots;
  std::vector<Vec3> values, second;
};

/// The arithmetic a mode is solved and evaluated in (docs/spectral.md, "Precision"):
/// double, x87 extended (long double) or quad (__float128), as its conditioning needs.
enum class ModePrecision : std::uint8_t { Double, Extended, Quad };

/// A solved patch: a value, evaluation is const, editing returns a new patch.
class SpectralPatch {
 public:
  /// The condition as solved: its u, derivative order and the curve it meets. The curve
  /// is the curve's M-mode Fourier part plus (with the remainder) its tail.
  struct ResolvedCondition {
    std::uint32_t derivative = 0;
    double u = 0.0;
    FourierCurve fourier;      ///< modes 0..M of the condition's data
    std::vector<Vec3> points;  ///< the given points (empty for Fourier input)
    std::vector<double> v;     ///< their v values
  };

  const SpectralOperator& op() const { return operator_; }
  std::uint32_t modes() const { return modes_; }
  double uStart() const { return uStart_; }
  double uEnd() const { return uEnd_; }
  const std::vector<ResolvedCondition>& conditions() const { return conditions_; }
  bool hasRemainder() const { return tail_ != nullptr; }
  /// The precision mode n (0..M) was solved in and is evaluated in.
  ModePrecision precision(std::uint32_t n) const { return coefficients_.at(n).precision; }

  Vec3 position(double u, double v) const { return derivative(u, v, 0, 0); }
  /// S, S_u, S_v.
  SurfacePoint evaluate(double u, double v) const;
  /// ∂^(ku+kv) X / ∂u^ku ∂v^kv, analytic. The remainder's v-derivatives come from cubic
  /// splines: exact up to kv = 2, piecewise constant for kv = 3, zero above.
  Vec3 derivative(double u, double v, std::uint32_t ku, std::uint32_t kv) const;

  /// The value the condition `i` asks for at v (its curve or derivative curve).
  Vec3 conditionTarget(std::size_t i, double v) const;

  /// The spine A0(u) (seed 003 §4.2), including spine edits.
  Vec3 spine(double u, std::uint32_t k = 0) const;

  // Internal representation (used by src/spectral; not part of the stable API).
  /// Extended precision: in ill-conditioned modes the coefficients cancel (docs/spectral.md).
  /// Plain vectors, not Eigen matrices: the library may be built for another SIMD width
  /// (-march=native) than its users, and dynamic Eigen storage must not cross that line.
  struct ModeCoefficients {
    std::vector<long double> cosine;  ///< order × 3, row-major: An(u) = Σ_k cosine[k] φ_k
    std::vector<long double> sine;    ///< order × 3 (zero for mode 0)
    /// Quad modes only: the quad coefficient is exactly cosine[k] + cosineLow[k].
    std::vector<long double> cosineLow, sineLow;
    ModePrecision precision = ModePrecision::Double;
  };
  SpectralOperator operator_;
  std::uint32_t modes_ = 0;
  double uStart_ = 0.0, uEnd_ = 1.0;
  std::vector<ResolvedCondition> conditions_;
  std::vector<ModeCoefficients> coefficients_;                     ///< modes 0..M
  std::shared_ptr<const std::vector<spectral::ModeBasis>> bases_;  ///< modes 0..M
  std::shared_ptr<const spectral::SpectralTailData> tail_;         ///< null: no remainder
  std::vector<SpineOffset> spineOffsets_;                          ///< spine edits, added to A0
};

/// Solves one patch: resolves u positions, fits sampled curves with M modes, solves each
/// mode's condition system by QR (one factorisation per mode) and builds the remainder.
/// Throws InvalidArgument naming what is wrong (operator, condition count, duplicate
/// u, too few points for M, open or degenerate curves, singular conditions).
SpectralPatch solve(const SpectralOperator& op, std::span<const SpectralCondition> conditions,
                    const SpectralOptions& options = {});

/// The u of each position curve under a placement (curves as Fourier fits or points).
std::vector<double> placeCurves(std::span<const CurveInput> curves, UPlacement placement,
                                VParameterization parameterization);

/// The largest error of each condition over its given points (when it has them) and over
/// `samples` uniform v, relative to the largest |target| among the conditions of the same
/// derivative order (absolute when all are 0).
std::vector<double> conditionErrors(const SpectralPatch& patch, std::uint32_t samples = 97);

// ---------------------------------------------------------------------------------------
// Grids and spine.

/// S, S_u, S_v on a tensor grid, index i·v.size() + j for (u_i, v_j).
struct SpectralGrid {
  std::size_t uCount = 0, vCount = 0;
  std::vector<Vec3> p, du, dv;
};

/// Evaluates with per-u tables (mode functions) and per-v tables (cos, sin, tails).
SpectralGrid evaluateGrid(const SpectralPatch& patch, std::span<const double> us,
                          std::span<const double> vs);
void evaluateGrid(const SpectralPatch& patch, std::span<const double> us,
                  std::span<const double> vs, SpectralGrid& out);

/// The spine sampled at `count` uniform u over the patch (a polyline of A0).
std::vector<Vec3> spinePolyline(const SpectralPatch& patch, std::uint32_t count);

/// Spine editing (seed 003 §4.2): control points of the spine at `u` moved to `moved`.
/// The displacement D(u) is the natural cubic spline through (u_j, moved_j - A0(u_j))
/// (linear beyond the end knots; a constant for one point), and the new surface is
/// X' = X + D(u): the edited spine passes through the moved points and every point of the
/// surface moves by exactly the spine's displacement. Edits compose.
struct SpineEdit {
  std::vector<double> u;
  std::vector<Vec3> moved;
};
SpectralPatch editSpine(const SpectralPatch& patch, const SpineEdit& edit);

// ---------------------------------------------------------------------------------------
// Cross-section chains (seed 002).

enum class ChainMethod {
  /// All joints solved together (docs/spectral.md, "The global chain"): one patch between
  /// each two consecutive curves in the chain parameter u ∈ [0, 1]; position, ∂u and ∂²u
  /// are shared at every joint, and ∂³u, ∂⁴u are continuous at interior joints (C4), with
  /// natural ends ∂³u = ∂⁴u = 0 or ends estimated from the data. For a > 0 this is the
  /// minimum of ∫∫ |X_uuu|² + a |X_vvv|² du dv over surfaces through the curves. Stable for
  /// any number of curves (a banded system, no marching).
  Global,
  /// Method 2: a root patch through 6 curves, then patches through 3 new curves each that
  /// match position, ∂u and ∂²u of their neighbour at the shared curve: exact C2.
  ExactC2,
  /// Method 1: windows of 6 consecutive curves; neighbouring windows share curves and are
  /// trimmed at a shared curve. C0 at curves; C1, C2 only approximate (measure them).
  SharedCurves
};

/// Where the global method puts the curves along its chain parameter u ∈ [0, 1] when
/// `CrossSectionOptions::u` is empty: the cumulative distance between consecutive curves,
/// normalised.
enum class ChainSpacing {
  Centroids,     ///< distance between the curves' centroids (their a0)
  MeanDistance,  ///< mean over v of |C_{i+1}(v) − C_i(v)| (seed 003 §3.0.1)
  Uniform        ///< equal steps
};

/// The global method's conditions at the first and last curve.
enum class ChainEnds {
  /// ∂³u X = ∂⁴u X = 0: the natural boundary conditions of the energy minimum.
  Natural,
  /// ∂u X and ∂²u X of the polynomial in u through the first (last) min(K, 6) curves.
  Estimated
};

struct CrossSectionOptions {
  double a = 1.0;           ///< the Fu operator's a (≠ 0; > 0 or < 0)
  std::uint32_t modes = 6;  ///< M
  ChainMethod method = ChainMethod::Global;
  VParameterization parameterization = VParameterization::ChordLength;
  bool remainder = true;
  // The global method only:
  ChainSpacing spacing = ChainSpacing::Centroids;
  /// The chain parameter of each curve (K strictly increasing values, any scale: they are
  /// mapped to [0, 1]); empty: from `spacing`.
  std::vector<double> u;
  ChainEnds ends = ChainEnds::Natural;
};

/// One patch of a chain: its curves and the part of its local u ∈ [0, 1] that is shown.
struct ChainPatch {
  SpectralPatch patch;
  std::uint32_t firstCurve = 0, lastCurve = 0;  ///< curves it interpolates (inclusive)
  double tStart = 0.0, tEnd = 1.0;              ///< displayed local range
  std::uint32_t shownFirstCurve = 0, shownLastCurve = 0;
  /// The patch's extent in the chain parameter (local t = 1 is this much of it): the number
  /// of curve intervals for methods 1 and 2 (curve i at s = i), u_{last} − u_{first} for the
  /// global method. A k-th chain derivative is the k-th t-derivative / length^k.
  double length = 1.0;
};

/// Patches in chain order (curve 0 first). Consecutive patches meet at a curve: patch p's
/// tEnd and patch p+1's tStart, both at curve patches[p].shownLastCurve.
struct CrossSectionChain {
  ChainMethod method = ChainMethod::Global;
  std::vector<ChainPatch> patches;
  std::uint32_t rootPatch = 0;  ///< the patch the others were built from
  /// The chain parameter of every curve (global method: in [0, 1]; methods 1 and 2: i).
  std::vector<double> curveU;
  /// The operator in the chain parameter (a patch's own operator is in its local t: for the
  /// global method a·h⁶).
  SpectralOperator op;
};

/// The name of a method as model files write it: "global", "c2", "shared-curves".
const char* chainMethodName(ChainMethod method);

/// Solves the chain of patches through K ordered closed curves (global: K ≥ 2; method 2:
/// K ≥ 4; method 1: K ≥ 6). Throws InvalidArgument naming the curve for bad curves, coincident
/// spacing (two consecutive curves at the same u) or a singular system.
CrossSectionChain solve(std::span<const CurveInput> curves,
                        const CrossSectionOptions& options = {});

/// Gaps at one joint: max over v of |ΔX|, |Δ∂uX|, |Δ∂²uX| between the two patches'
/// local parameters, absolute and relative to the chain's extent.
struct JointGap {
  std::uint32_t curve = 0;  ///< the curve the joint sits on
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;
  double c0Relative = 0.0, c1Relative = 0.0, c2Relative = 0.0;
};
std::vector<JointGap> measureJointGaps(const CrossSectionChain& chain, std::uint32_t samples = 128);

// ---------------------------------------------------------------------------------------
// Tessellation.

/// A watertight, consistently oriented mesh of options.resolution rows along u (ends
/// included) and options.aroundResolution distinct columns around v (v = 2π is column 0;
/// TessellateOptions says what 0 means): the v seam shares its vertices, collapsed rows are
/// one vertex, normals come from the analytic derivatives and face away from the spine.
Mesh tessellate(const SpectralPatch& patch, const TessellateOptions& options = {});
/// The same for a chain: consecutive patches share the joint curve's vertices (normals
/// averaged), patchIds give the patch index.
Mesh tessellate(const CrossSectionChain& chain, const TessellateOptions& options = {});

}  // namespace pdesurf
