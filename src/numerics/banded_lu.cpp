// Banded LU with partial pivoting (src/numerics/banded_lu.hpp).
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include "numerics/banded_lu.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pdesurf::numerics {

BandedLu::BandedLu(int m, int kl, int ku)
    : m_(m),
      kl_(kl),
      ku_(ku),
      width_(2 * kl + ku + 1),
      band_(static_cast<std::size_t>(m) * static_cast<std::size_t>(2 * kl + ku + 1), 0.0),
      multipliers_(static_cast<std::size_t>(m) * static_cast<std::size_t>(kl), 0.0),
      pivots_(static_cast<std::size_t>(m), 0) {}

bool BandedLu::factor() {
  for (int k = 0; k < m_; ++k) {
    const int last = std::min(m_ - 1, k + kl_);
    const int lastColumn = std::min(m_ - 1, k + kl_ + ku_);
    int pivot = k;
    for (int r = k + 1; r <= last; ++r)
      if (std::abs(at(r, k)) > std::abs(at(pivot, k))) pivot = r;
    pivots_[static_cast<std::size_t>(k)] = pivot;
    if (at(pivot, k) == 0.0) return false;
    if (pivot != k)
      for (int c = k; c <= lastColumn; ++c) std::swap(at(k, c), at(pivot, c));
    const double diagonal = at(k, k);
    for (int r = k + 1; r <= last; ++r) {
      const double l = at(r, k) / diagonal;
      multipliers_[static_cast<std::size_t>(k * kl_ + (r - k - 1))] = l;
      at(r, k) = 0.0;
      for (int c = k + 1; c <= lastColumn; ++c) at(r, c) -= l * at(k, c);
    }
  }
  return true;
}

void BandedLu::solve(RowMatrix& b) const {
  for (int k = 0; k < m_; ++k) {
    const int pivot = pivots_[static_cast<std::size_t>(k)];
    if (pivot != k) b.row(k).swap(b.row(pivot));
    const int last = std::min(m_ - 1, k + kl_);
    for (int r = k + 1; r <= last; ++r)
      b.row(r) -= multipliers_[static_cast<std::size_t>(k * kl_ + (r - k - 1))] * b.row(k);
  }
  for (int k = m_ - 1; k >= 0; --k) {
    const int lastColumn = std::min(m_ - 1, k + kl_ + ku_);
    for (int c = k + 1; c <= lastColumn; ++c) b.row(k) -= at(k, c) * b.row(c);
    b.row(k) /= at(k, k);
  }
}

}  // namespace pdesurf::numerics
