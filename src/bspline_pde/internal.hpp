// Private pieces of the B-spline PDE engine shared by its sources and tests: cubic basis
// evaluation, banded LU with partial pivoting, net validation.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/bspline_pde.hpp"

namespace pdesurf::bspline {

/// The span s (3 ≤ s ≤ n) with knots[s] ≤ t < knots[s+1]; t at or past knots[n] gives n, t
/// below knots[4] gives 3 (the end polynomials extend beyond the domain).
std::uint32_t findSpan(std::span<const double> knots, std::uint32_t n, double t);

/// The 4 non-zero cubic basis functions at t and their derivatives up to the third
/// (Piegl & Tiller, The NURBS Book, A2.3, for degree 3).
CubicBasis cubicBasis(std::span<const double> knots, std::uint32_t n, double t);

/// Throws std::invalid_argument unless nu, nv ≥ 3, the point count is (nu+1)(nv+1) and every
/// point (every given point when `innerExempt`) is finite. `where` starts each message.
void validateNet(const ControlNet& net, bool innerExempt, std::string_view where);

/// Least-squares control points 0..n on cubic knots of `knots` type for values at parameters
/// in [0, 1]; with `pinEnds`, the first and last control points are the first and last values
/// (clamped ends interpolate). Throws std::invalid_argument, starting with `where`, when the
/// samples are too few or leave a control point undetermined.
std::vector<Vec3> fitControlPoints(const std::vector<Vec3>& values,
                                   const std::vector<double>& params, KnotType knots,
                                   std::uint32_t n, bool pinEnds, const std::string& where);

/// fitControlPoints of f sampled at kBoundaryResampleFactor (n + 1) + 1 uniform parameters;
/// throws std::invalid_argument where f is not finite.
std::vector<Vec3> fitFunction(const std::function<Vec3(double)>& f, KnotType knots, std::uint32_t n,
                              bool pinEnds, const std::string& where);

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// LU with partial pivoting of an m×m band matrix with kl sub- and ku super-diagonals
/// (LAPACK's gbtrf scheme: U gets kl + ku super-diagonals, L keeps kl multipliers a column).
class BandedLu {
 public:
  BandedLu() = default;
  BandedLu(int m, int kl, int ku);

  int size() const { return m_; }
  /// Entry (r, c) of the matrix, |c - r| inside the band; set before factor().
  double& at(int r, int c) { return band_[index(r, c)]; }
  double at(int r, int c) const { return band_[index(r, c)]; }

  /// Factors in place. False when a pivot is exactly zero (a singular matrix).
  bool factor();
  /// Solves A X = B for every column of `b` (m rows), overwriting it: O(m (kl+ku) cols).
  void solve(RowMatrix& b) const;

 private:
  std::size_t index(int r, int c) const {
    return static_cast<std::size_t>(r) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(c - r + kl_);
  }
  int m_ = 0, kl_ = 0, ku_ = 0, width_ = 0;
  std::vector<double> band_;         // row r: columns r-kl .. r+kl+ku
  std::vector<double> multipliers_;  // column k: the kl multipliers of rows k+1..k+kl
  std::vector<int> pivots_;          // row exchanged with k at step k
};

}  // namespace pdesurf::bspline
