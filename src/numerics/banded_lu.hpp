// Banded LU with partial pivoting, shared by the engines whose systems are banded: the
// B-spline PDE mask equations (src/bspline_pde/solve.cpp) and the global cross-section
// chain (src/spectral/chain.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace pdesurf::numerics {

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

}  // namespace pdesurf::numerics
