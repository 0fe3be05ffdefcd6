// Cubic knots, basis functions and their derivatives, the mask rows and M (seed 004 §2).
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bspline_pde/internal.hpp"

namespace pdesurf {

std::vector<double> cubicKnots(KnotType type, std::uint32_t n) {
  if (n < 3)
    throw InvalidArgument("cubicKnots: n = " + std::to_string(n) +
                          " (last control index) must be at least 3");
  const double spans = static_cast<double>(n - 2);
  std::vector<double> knots(n + 5);
  for (std::uint32_t k = 0; k < n + 5; ++k) {
    const double t = (static_cast<double>(k) - 3.0) / spans;
    knots[k] = type == KnotType::Uniform ? t : std::clamp(t, 0.0, 1.0);
  }
  // Exact ends (the domain is [0, 1] whatever the rounding of (k-3)/spans).
  knots[3] = 0.0;
  knots[n + 1] = 1.0;
  return knots;
}

namespace bspline {

std::uint32_t findSpan(std::span<const double> knots, std::uint32_t n, double t) {
  // The last span whose left knot is ≤ t, within 3..n (also for NaN: the caller validated).
  const auto first = knots.begin() + 4, last = knots.begin() + n + 1;
  const auto it = std::upper_bound(first, last, t);
  return static_cast<std::uint32_t>(it - knots.begin()) - 1;
}

CubicBasis cubicBasis(std::span<const double> knots, std::uint32_t n, double t) {
  constexpr int p = 3;
  CubicBasis out;
  const std::uint32_t i = findSpan(knots, n, t);
  out.span = i;
  double ndu[p + 1][p + 1];
  double left[p + 1], right[p + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[i + 1 - static_cast<std::uint32_t>(j)];
    right[j] = knots[i + static_cast<std::uint32_t>(j)] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // a knot difference ≥ the span's length
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) out.d[0][j] = ndu[j][p];
  double a[2][p + 1];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= p; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      out.d[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= p; ++k) {
    for (int j = 0; j <= p; ++j) out.d[k][j] *= factor;
    factor *= p - k;
  }
  return out;
}

}  // namespace bspline

std::array<double, 4> thirdDerivativeMask(std::span<const double> knots, std::uint32_t span) {
  if (knots.size() < 8 || span < 3 || span + 5 > knots.size())
    throw InvalidArgument("thirdDerivativeMask: span " + std::to_string(span) +
                          " is not one of 3..n for " + std::to_string(knots.size()) + " knots");
  if (!(knots[span + 1] > knots[span]))
    throw InvalidArgument("thirdDerivativeMask: span " + std::to_string(span) + " has zero length");
  const auto n = static_cast<std::uint32_t>(knots.size() - 5);
  // The third derivative is constant on the span: take it at the midpoint (away from the
  // knots, so findSpan lands on `span`).
  const double mid = 0.5 * (knots[span] + knots[span + 1]);
  const CubicBasis basis = bspline::cubicBasis(knots, n, mid);
  return basis.d[3];
}

Eigen::MatrixXd pdeSystemMatrix(KnotType type, std::uint32_t n) {
  const std::vector<double> knots = cubicKnots(type, n);
  const int m = static_cast<int>(n) - 2;
  Eigen::MatrixXd matrix = Eigen::MatrixXd::Zero(m, m);
  for (int a = 0; a < m; ++a) {
    const std::array<double, 4> t = thirdDerivativeMask(knots, static_cast<std::uint32_t>(a) + 3);
    // Span a+3 acts on points a..a+3; the unknowns are 2..n-1 (column c = point - 2).
    for (int r = 0; r < 4; ++r) {
      const int c = a + r - 2;
      if (c >= 0 && c < m) matrix(a, c) = t[static_cast<std::size_t>(r)];
    }
  }
  return matrix;
}

}  // namespace pdesurf
