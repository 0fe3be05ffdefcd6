// Per-mode solution bases of separable periodic operators (docs/derivations.md §2.1–§2.2): for each
// characteristic root μ of multiplicity m, the functions p_k(x) e^{μ(t-c)} (k < m) on the
// local parameter t ∈ [0, 1], where c = 1 and x = 1 - t for Re μ > 0 (growing exponentials
// written as e^{μ(t-1)}, bounded on [0, 1]), c = 0 and x = t otherwise, and the p_k are
// orthonormal for the weight |e^{μ(t-c)}|² = e^{-2|Re μ| x} on [0, 1] (so each group of
// basis functions is L2-orthonormal; for Re μ = 0, e.g. mode 0, they are the Legendre
// polynomials). A complex pair α ± iβ gives the real and imaginary parts.
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/spectral.hpp"
#include "spectral/quad.hpp"

namespace pdesurf::spectral {

/// The engine computes bases, solves and mode sums in extended precision: where the
/// growing and decaying exponentials of a mode overlap (|root| < ~3 × multiplicity) the
/// basis is ill-conditioned (docs/spectral.md), and the 3 extra digits of x87 long double
/// keep conditions to ~1e-11 there. Modes beyond that are solved and evaluated in quad
/// precision (Quad, quad.hpp).
using Real = long double;
using MatrixR = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
using RowVectorR = Eigen::Matrix<Real, 1, Eigen::Dynamic>;
/// Double-precision mode systems live on the stack (orders up to kSmallOrder): no Eigen heap
/// storage of double, whose out-of-line helpers a program may also instantiate with another
/// alignment (the library is built with -march=native, its users need not be), and no
/// allocation per solve.
constexpr int kSmallOrder = 40;
using SmallMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallOrder, kSmallOrder>;

/// A mode's coefficients (order × 3) as a matrix.
inline Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>> coefficients(
    const std::vector<Real>& c) {
  return {c.data(), static_cast<Eigen::Index>(c.size() / 3), 3};
}

/// One characteristic root (Im μ ≥ 0; a complex one stands for its conjugate too), or a
/// whole mode as a power series (`series`): the solutions of y^(p) = c y, p = multiplicity,
/// c = seriesC, spanned by y_k(t) = Σ_m c^m t^{k+pm} / (k+pm)! for k < p. modeRoots uses the
/// series where the roots all lie within kSeriesRadius of 0 (Fu modes with κ < 1 in t): p
/// simple exponentials with nearly equal roots are nearly dependent (their Vandermonde
/// matrix has condition ~κ^{1-p}), while the y_k are close to t^k/k!: as well conditioned
/// as the polynomials of mode 0 (docs/spectral.md, "Short patches").
struct Root {
  std::complex<double> mu;
  std::uint32_t multiplicity = 1;
  bool series = false;
  double seriesC = 0.0;
};

/// Root magnitude |μ| (in t) below which a Fu mode is evaluated as a power series (Root).
/// At |μ| = 1 the exponential basis is a scaled DFT matrix (condition 1) and the series
/// needs 6 terms for 1e-34, so both are exact there.
constexpr double kSeriesRadius = 1.0;

/// The roots of mode n of `op` in the local parameter t = (u - u0) / length.
std::vector<Root> modeRoots(const SpectralOperator& op, std::uint32_t n, double length);

/// Orthonormal polynomials for e^{-2σx} on [0, 1] by their three-term recurrence
/// b_{k+1} p_{k+1} = (x - α_k) p_k - b_k p_{k-1}, p_0 = 1 / b_0 (discretised Stieltjes).
struct Recurrence {
  std::vector<Real> alpha, b;  ///< b[0] = sqrt(∫ w)
  /// The same in double, for the double evaluation path (no long-double loads per point),
  /// and in quad for the quad path (the long-double values converted exactly: any
  /// polynomial factor gives a solution of the mode ODE, so they need no more digits).
  std::vector<double> alphaD, bD;
  std::vector<Quad> alphaQ, bQ;
};
Recurrence weightedRecurrence(double sigma, std::uint32_t count);

class ModeBasis {
 public:
  ModeBasis() = default;
  explicit ModeBasis(std::vector<Root> roots);

  std::uint32_t size() const { return size_; }
  /// Whether this mode needs extended precision: a growing and a decaying group of
  /// multiplicity m ≥ 2 overlap (|root| < 3m), and their near-dependence costs more than
  /// ~6 digits (m ≥ 8 or |root| < m; measured in docs/spectral.md).
  bool extended() const { return extended_ || size_ > kSmallOrder; }
  /// Whether the basis is (near) polynomial of degree < 6: a power series (Root::series) or
  /// the polynomials of a 6-fold (or lower) root 0. Such a basis evaluates accurately in
  /// double, but its systems are solved in long double (solveModeTiered in patch.cpp).
  bool nearPolynomial() const { return nearPolynomial_; }
  /// out(j, k) = d^j φ_k / dt^j at t, for j = 0..maxDerivative (SmallMatrix, MatrixR or
  /// MatrixQ: evaluated in that matrix's precision).
  template <class M>
  void evaluate(double t, std::uint32_t maxDerivative, M& out) const;
  /// Row of the k-th derivative only.
  RowVectorR row(double t, std::uint32_t derivative) const;

 private:
  std::vector<Root> roots_;
  std::vector<Recurrence> recurrences_;  ///< per root
  std::uint32_t size_ = 0;
  bool extended_ = false;
  bool nearPolynomial_ = false;
};

}  // namespace pdesurf::spectral
