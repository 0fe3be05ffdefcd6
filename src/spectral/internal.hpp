// Private pieces of the spectral engine shared by its source files.
#pragma once

#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral.hpp"
#include "spectral/basis.hpp"

namespace pdesurf::spectral {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A number for an error message (nine significant digits).
inline std::string numberText(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

/// The k-th derivative (k ≤ 3) of one cubic spline segment from its end values y0, y1 and
/// second derivatives m0, m1, at distances a = x1 − x and b = x − x0 in a segment of length
/// h (the natural and the periodic splines share it).
inline Vec3 cubicSegment(const Vec3& y0, const Vec3& y1, const Vec3& m0, const Vec3& m1, double h,
                         double a, double b, std::uint32_t k) {
  switch (k) {
    case 0:
      return m0 * a * a * a / (6 * h) + m1 * b * b * b / (6 * h) + (y0 / h - m0 * h / 6) * a +
             (y1 / h - m1 * h / 6) * b;
    case 1:
      return -m0 * a * a / (2 * h) + m1 * b * b / (2 * h) - (y0 / h - m0 * h / 6) +
             (y1 / h - m1 * h / 6);
    case 2:
      return m0 * a / h + m1 * b / h;
    case 3:
      return (m1 - m0) / h;
    default:
      return Vec3::Zero();
  }
}

/// A periodic (period 2π) interpolating cubic spline through (v_j, y_j), C2.
class PeriodicSpline {
 public:
  PeriodicSpline(std::vector<double> v, std::vector<Vec3> y);
  /// k-th derivative (k ≤ 3; zero above).
  Vec3 evaluate(double v, std::uint32_t k = 0) const;

 private:
  std::vector<double> v_;
  std::vector<Vec3> y_, m_;  // values, second derivatives
};

/// A natural cubic spline (linear beyond the end knots), for spine edits.
Vec3 evaluateNaturalSpline(const SpineOffset& s, double u, std::uint32_t k);
SpineOffset naturalSpline(std::vector<double> u, std::vector<Vec3> y);

/// One term of a condition's tail: weight × (a spline, or the modes > M of a Fourier curve).
struct TailTerm {
  double weight = 1.0;
  std::shared_ptr<const PeriodicSpline> spline;
  std::shared_ptr<const FourierCurve> fourier;  ///< modes ≤ M zeroed
  Vec3 evaluate(double v, std::uint32_t k) const {
    return weight * (spline ? spline->evaluate(v, k) : fourier->evaluate(v, k));
  }
};

/// A condition ready to solve: u-space data (derivative curves are u-derivatives).
struct ConditionData {
  std::uint32_t derivative = 0;
  double u = 0.0;
  FourierCurve fourier;  ///< exactly M modes
  std::vector<TailTerm> tail;
  std::vector<Vec3> points;
  std::vector<double> v;
  bool collapsed = false;  ///< all points coincide (a section collapsed to a point)
};

/// A mode's coefficients (order × 3, row-major) in precision T (double, Real or Quad; a
/// quad mode's are the exact sums hi + lo of its two long-double vectors).
template <typename T>
Eigen::Matrix<T, Eigen::Dynamic, 3, Eigen::RowMajor> coefficientMatrix(
    const std::vector<Real>& hi, const std::vector<Real>& lo) {
  if constexpr (std::is_same_v<T, Quad>) {
    Eigen::Matrix<T, Eigen::Dynamic, 3, Eigen::RowMajor> c(static_cast<Eigen::Index>(hi.size() / 3),
                                                           3);
    for (std::size_t k = 0; k < hi.size(); ++k)
      c(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) =
          lo.empty() ? Quad(hi[k]) : join(hi[k], lo[k]);
    return c;
  } else {
    return coefficients(hi).template cast<T>();
  }
}

/// R(t, v) = Σ_i ψ_i(t) d_i(v), ψ = φ_{M+1} · cardinal (ψ_i meets condition i only).
struct SpectralTailData {
  ModeBasis basis;
  /// Extended, or Quad when long double cannot invert mode M+1's condition matrix.
  ModePrecision precision = ModePrecision::Extended;
  MatrixR cardinal;   ///< order × order (Extended)
  MatrixQ cardinalQ;  ///< order × order (Quad)
  /// Rows first..last of the t-derivatives of ψ at t, in the tail's precision.
  MatrixR psi(double t, std::uint32_t first, std::uint32_t last) const;
  std::vector<std::vector<TailTerm>> terms;  ///< per condition, u-space
  std::vector<double> scale;                 ///< per condition: length^{k_i} (u → t space)
  /// d_i^{(k)}(v) in t-space.
  Vec3 difference(std::size_t i, double v, std::uint32_t k) const {
    Vec3 d = Vec3::Zero();
    for (const TailTerm& term : terms[i]) d += term.evaluate(v, k);
    return scale[i] * d;
  }
};

/// Fits or truncates a curve to M modes and builds its tail (when `remainder`).
/// `what` prefixes error messages ("condition 3", "curve 2").
ConditionData resolveCurve(const CurveInput& curve, std::uint32_t modes,
                           VParameterization parameterization, bool remainder,
                           const std::string& what);

/// Solves a patch from resolved conditions on u ∈ [uStart, uEnd].
SpectralPatch solveResolved(const SpectralOperator& op, std::uint32_t modes, double uStart,
                            double uEnd, std::vector<ConditionData> conditions);

/// Keeps the conditions a patch was solved from (SpectralPatch::conditions()).
void storeConditions(SpectralPatch& patch, std::vector<ConditionData> conditions);

/// The k-th t-derivative curve of a patch at local t (t-space; chain patches have length 1):
/// its Fourier part and the tail terms of the remainder.
ConditionData derivativeCondition(const SpectralPatch& patch, double t, std::uint32_t k);

/// Largest distance of a point set from its first point.
double spread(const std::vector<Vec3>& points);

}  // namespace pdesurf::spectral
