// C1 blends of four PDE pieces from four boundary curves (seed Example 4); the rule for the
// points the seed leaves "chosen" is in docs/bspline-pde.md §"C1 blends".
#include "spectral/eigen_warnings.hpp"  // first: before Eigen

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "bspline_pde/internal.hpp"

namespace pdesurf {
namespace {

/// Boehm's insertion of knot t (once) into a cubic B-spline (knots, points).
void insertKnot(std::vector<double>& knots, std::vector<Vec3>& points, double t) {
  const auto k =
      static_cast<std::size_t>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
  std::vector<Vec3> q(points.size() + 1);
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (i + 3 <= k) {
      q[i] = points[i];
    } else if (i <= k) {
      const double alpha = (t - knots[i]) / (knots[i + 3] - knots[i]);
      q[i] = alpha * points[i] + (1.0 - alpha) * points[i - 1];
    } else {
      q[i] = points[i - 1];
    }
  }
  knots.insert(knots.begin() + static_cast<std::ptrdiff_t>(k) + 1, t);
  points = std::move(q);
}

/// A clamped curve refitted on 2(n-2) uniform spans and split at 1/2 into two clamped halves
/// of n + 1 points each: 2n + 1 points, the halves sharing point n.
std::vector<Vec3> splitCurve(const BSplineCurve& curve, std::uint32_t n, const std::string& name) {
  const std::string where = "blendFourCurves: curve " + name;
  if (curve.points.size() < 4)
    throw std::invalid_argument(where + ": " + std::to_string(curve.points.size()) +
                                " control points; a cubic needs at least 4");
  if (curve.knots != KnotType::Clamped)
    throw std::invalid_argument(where + ": needs clamped knots (it must interpolate its ends)");
  for (std::size_t k = 0; k < curve.points.size(); ++k)
    if (!curve.points[k].allFinite())
      throw std::invalid_argument(where + ": point " + std::to_string(k) + " is not finite");
  const std::uint32_t last = 2 * n - 2;
  std::vector<double> knots = cubicKnots(KnotType::Clamped, last);
  std::vector<Vec3> points;
  if (curve.points.size() == last + 1) {
    points = curve.points;
  } else {
    points = bspline::fitFunction([&curve](double t) { return curve.evaluate(t); },
                                  KnotType::Clamped, last, true, where);
  }
  insertKnot(knots, points, 0.5);
  insertKnot(knots, points, 0.5);
  return points;
}

}  // namespace

C1Blend blendFourCurves(const BSplineCurve& uMin, const BSplineCurve& uMax,
                        const BSplineCurve& vMin, const BSplineCurve& vMax, std::uint32_t n) {
  if (n < 3)
    throw std::invalid_argument("blendFourCurves: n = " + std::to_string(n) +
                                " (last index of a piece) must be at least 3");
  const std::vector<Vec3> w = splitCurve(uMin, n, "uMin"), e = splitCurve(uMax, n, "uMax"),
                          s = splitCurve(vMin, n, "vMin"), nn = splitCurve(vMax, n, "vMax");
  const int size = 2 * static_cast<int>(n) + 1, last = size - 1;
  Eigen::AlignedBox3d box;
  for (const auto* c : {&w, &e, &s, &nn})
    for (const Vec3& p : *c) box.extend(p);
  const double extent = std::max(box.diagonal().norm(), 1e-300);
  const auto corner = [&](const Vec3& a, const char* an, const Vec3& b, const char* bn) {
    if ((a - b).norm() > kBSplineCornerTolerance * extent)
      throw std::invalid_argument(std::string("blendFourCurves: curves ") + an + " and " + bn +
                                  " do not meet at their shared corner");
  };
  corner(w.front(), "uMin", s.front(), "vMin");
  corner(w.back(), "uMin", nn.front(), "vMax");
  corner(e.front(), "uMax", s.back(), "vMin");
  corner(e.back(), "uMax", nn.back(), "vMax");

  // The global net G(i, j), 0 ≤ i, j ≤ 2n; piece (p, q) is G[pn .. pn+n][qn .. qn+n].
  std::vector<Vec3> known(static_cast<std::size_t>(size * size), Vec3::Zero());
  std::vector<int> unknown(static_cast<std::size_t>(size * size), -1);
  const auto at = [&](int i, int j) { return static_cast<std::size_t>(i * size + j); };
  int m = 0;
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      if (i == 0)
        known[at(i, j)] = w[static_cast<std::size_t>(j)];
      else if (i == last)
        known[at(i, j)] = e[static_cast<std::size_t>(j)];
      else if (j == 0)
        known[at(i, j)] = s[static_cast<std::size_t>(i)];
      else if (j == last)
        known[at(i, j)] = nn[static_cast<std::size_t>(i)];
      else
        unknown[at(i, j)] = m++;
    }
  // A linear equation Σ c G(i, j) = 0 as a row over the unknowns and a right-hand side.
  struct Rows {
    std::vector<Eigen::RowVectorXd> a;
    std::vector<Eigen::RowVector3d> b;
  };
  const auto addRow = [&](Rows& rows, const std::vector<std::tuple<int, int, double>>& terms) {
    Eigen::RowVectorXd a = Eigen::RowVectorXd::Zero(m);
    Eigen::RowVector3d b = Eigen::RowVector3d::Zero();
    double scale = 0.0;
    for (const auto& [i, j, c] : terms) scale = std::max(scale, std::abs(c));
    for (const auto& [i, j, c] : terms) {
      const int u = unknown[at(i, j)];
      if (u >= 0)
        a(u) += c / scale;
      else
        b -= (c / scale) * known[at(i, j)].transpose();
    }
    if (a.cwiseAbs().maxCoeff() == 0.0) return;  // only known points: holds or not, by input
    rows.a.push_back(a);
    rows.b.push_back(b);
  };
  Rows constraints, energy;
  const std::vector<double> knots = cubicKnots(KnotType::Clamped, n);
  std::vector<std::array<double, 4>> mask;
  for (std::uint32_t sp = 3; sp <= n; ++sp) mask.push_back(thirdDerivativeMask(knots, sp));
  const int spans = static_cast<int>(n) - 2, ni = static_cast<int>(n);
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q)
      for (int a = 0; a < spans; ++a)
        for (int b = 0; b < spans; ++b) {
          std::vector<std::tuple<int, int, double>> terms;
          for (int r = 0; r < 4; ++r)
            for (int l = 0; l < 4; ++l)
              terms.emplace_back(
                  p * ni + a + r, q * ni + b + l,
                  mask[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)] *
                      mask[static_cast<std::size_t>(b)][static_cast<std::size_t>(l)]);
          addRow(constraints, terms);
        }
  for (int k = 1; k < last; ++k) {
    addRow(constraints, {{ni - 1, k, 1.0}, {ni, k, -2.0}, {ni + 1, k, 1.0}});
    addRow(constraints, {{k, ni - 1, 1.0}, {k, ni, -2.0}, {k, ni + 1, 1.0}});
  }
  const double root2 = std::sqrt(2.0);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      if (i > 0 && i < last) addRow(energy, {{i - 1, j, 1.0}, {i, j, -2.0}, {i + 1, j, 1.0}});
      if (j > 0 && j < last) addRow(energy, {{i, j - 1, 1.0}, {i, j, -2.0}, {i, j + 1, 1.0}});
      if (i < last && j < last)
        addRow(energy,
               {{i, j, root2}, {i + 1, j, -root2}, {i, j + 1, -root2}, {i + 1, j + 1, root2}});
    }
  const auto stack = [&](const Rows& rows, Eigen::MatrixXd& a, Eigen::MatrixXd& b) {
    a.resize(static_cast<Eigen::Index>(rows.a.size()), m);
    b.resize(static_cast<Eigen::Index>(rows.a.size()), 3);
    for (std::size_t r = 0; r < rows.a.size(); ++r) {
      a.row(static_cast<Eigen::Index>(r)) = rows.a[r];
      b.row(static_cast<Eigen::Index>(r)) = rows.b[r];
    }
  };
  Eigen::MatrixXd c, d, en, ee;
  stack(constraints, c, d);
  stack(energy, en, ee);
  // Nullspace method: x = x_p + Z y, x_p the least-norm solution of C x = d (least squares if
  // the constraints were inconsistent: reported below), Z spanning ker C, y minimising energy.
  Eigen::BDCSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeThinU | Eigen::ComputeFullV);
  svd.setThreshold(1e-11);
  const Eigen::Index rank = svd.rank();
  const Eigen::MatrixXd xp = svd.solve(d);
  const Eigen::MatrixXd z = svd.matrixV().rightCols(m - rank);
  Eigen::MatrixXd x = xp;
  if (z.cols() > 0) x += z * (en * z).colPivHouseholderQr().solve(ee - en * xp);
  const double residual = (c * x - d).rowwise().norm().maxCoeff() / extent;

  std::vector<Vec3> g = known;
  for (std::size_t k = 0; k < g.size(); ++k)
    if (unknown[k] >= 0) g[k] = x.row(unknown[k]).transpose();
  std::vector<BSplineSurface> pieces;
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) {
      ControlNet net(n, n);
      for (std::uint32_t i = 0; i <= n; ++i)
        for (std::uint32_t j = 0; j <= n; ++j)
          net(i, j) = g[at(p * ni + static_cast<int>(i), q * ni + static_cast<int>(j))];
      pieces.emplace_back(std::move(net), KnotType::Clamped, KnotType::Clamped);
    }
  // Measured C1 gaps: ∂/∂U across U = 1 and ∂/∂V across V = 1 (unit spans: local = global).
  double gap = 0.0, scale = 0.0;
  constexpr int kSamples = 64;
  for (int q = 0; q < 2; ++q)
    for (int k = 0; k <= kSamples; ++k) {
      const double t = static_cast<double>(k) / kSamples;
      const SurfacePoint a0 = pieces[static_cast<std::size_t>(q)].evaluate(1.0, t);
      const SurfacePoint b0 = pieces[static_cast<std::size_t>(2 + q)].evaluate(0.0, t);
      const SurfacePoint a1 = pieces[static_cast<std::size_t>(2 * q)].evaluate(t, 1.0);
      const SurfacePoint b1 = pieces[static_cast<std::size_t>(2 * q + 1)].evaluate(t, 0.0);
      gap = std::max({gap, (a0.du - b0.du).norm(), (a1.dv - b1.dv).norm()});
      scale = std::max({scale, a0.du.norm(), a1.dv.norm()});
    }
  return C1Blend{
      {pieces[0], pieces[1], pieces[2], pieces[3]}, residual, gap / std::max(scale, 1e-300)};
}

}  // namespace pdesurf
