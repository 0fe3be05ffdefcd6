// C1 blends of four PDE pieces from four boundary curves (seed Example 4); the rule for the
// points the seed leaves "chosen" is in docs/bspline-pde.md §"C1 blends".
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

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

/// The curve's control points checked (count, knots, finite) and refitted, when their count
/// is not already 2n - 1, on 2(n-2) uniform clamped spans of [0, 1].
std::vector<Vec3> refitCurve(const BSplineCurve& curve, std::uint32_t n, const std::string& where) {
  if (curve.points.size() < 4)
    throw InvalidArgument(where + ": " + std::to_string(curve.points.size()) +
                          " control points; a cubic needs at least 4");
  if (curve.knots != KnotType::Clamped)
    throw InvalidArgument(where + ": needs clamped knots (it must interpolate its ends)");
  for (std::size_t k = 0; k < curve.points.size(); ++k)
    if (!curve.points[k].allFinite())
      throw InvalidArgument(where + ": point " + std::to_string(k) + " is not finite");
  const std::uint32_t last = 2 * n - 2;
  if (curve.points.size() == last + 1) return curve.points;
  return bspline::fitFunction([&curve](double t) { return curve.evaluate(t); }, KnotType::Clamped,
                              last, true, where);
}

/// 2(n-2) uniform clamped spans split at 1/2 into two clamped halves of n + 1 points each:
/// 2n + 1 points, the halves sharing point n.
std::vector<Vec3> splitAtMiddle(std::vector<Vec3> points, std::uint32_t n) {
  std::vector<double> knots = cubicKnots(KnotType::Clamped, 2 * n - 2);
  insertKnot(knots, points, 0.5);
  insertKnot(knots, points, 0.5);
  return points;
}

/// The linear conditions on a global net of control points, some known, some unknown, and
/// the least-energy solution that meets them (docs/bspline-pde.md §"C1 blends").
class BlendSystem {
 public:
  /// rows × cols points; `periodic`: column cols is column 0 again.
  BlendSystem(int rows, int cols, bool periodic)
      : rows_(rows),
        cols_(cols),
        periodic_(periodic),
        known_(static_cast<std::size_t>(rows * cols), Vec3::Zero()),
        unknown_(static_cast<std::size_t>(rows * cols), -1) {}

  std::size_t at(int i, int j) const {
    if (periodic_) j = ((j % cols_) + cols_) % cols_;
    return static_cast<std::size_t>(i * cols_ + j);
  }
  void setKnown(int i, int j, const Vec3& p) { known_[at(i, j)] = p; }
  void setUnknown(int i, int j) { unknown_[at(i, j)] = m_++; }

  /// Σ c G(i, j) = 0 as a hard constraint (or, for the energy, a residual to minimise); rows
  /// scaled to a largest coefficient of 1; rows over known points only are left out.
  void constrain(const std::vector<std::tuple<int, int, double>>& terms) {
    add(constraints_, terms);
  }
  void penalise(const std::vector<std::tuple<int, int, double>>& terms) { add(energy_, terms); }

  /// The PDE mask of one n × n clamped piece whose point (0, 0) is G(i0, j0), on every span.
  void pieceMasks(int i0, int j0, std::uint32_t n) {
    const std::vector<double> knots = cubicKnots(KnotType::Clamped, n);
    std::vector<std::array<double, 4>> mask;
    for (std::uint32_t sp = 3; sp <= n; ++sp) mask.push_back(thirdDerivativeMask(knots, sp));
    const int spans = static_cast<int>(n) - 2;
    for (int a = 0; a < spans; ++a)
      for (int b = 0; b < spans; ++b) {
        std::vector<std::tuple<int, int, double>> terms;
        for (int r = 0; r < 4; ++r)
          for (int l = 0; l < 4; ++l)
            terms.emplace_back(i0 + a + r, j0 + b + l,
                               mask[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)] *
                                   mask[static_cast<std::size_t>(b)][static_cast<std::size_t>(l)]);
        constrain(terms);
      }
  }

  /// C1 across the seam row i (equal spans on both sides) and the seam column j.
  void seamRow(int i) {
    for (int j = 0; j < cols_; ++j) constrain({{i - 1, j, 1.0}, {i, j, -2.0}, {i + 1, j, 1.0}});
  }
  void seamColumn(int j) {
    for (int i = 0; i < rows_; ++i) constrain({{i, j - 1, 1.0}, {i, j, -2.0}, {i, j + 1, 1.0}});
  }

  /// The discrete thin-plate energy Σ |Δ²_U G|² + 2 |Δ_U Δ_V G|² + |Δ²_V G|² of the net.
  void thinPlateEnergy() {
    const double root2 = std::sqrt(2.0);
    const int lastJ = periodic_ ? cols_ : cols_ - 1;
    for (int i = 0; i < rows_; ++i)
      for (int j = 0; j < cols_; ++j) {
        if (i > 0 && i < rows_ - 1) penalise({{i - 1, j, 1.0}, {i, j, -2.0}, {i + 1, j, 1.0}});
        if (periodic_ || (j > 0 && j < cols_ - 1))
          penalise({{i, j - 1, 1.0}, {i, j, -2.0}, {i, j + 1, 1.0}});
        if (i < rows_ - 1 && j < lastJ)
          penalise({{i, j, root2}, {i + 1, j, -root2}, {i, j + 1, -root2}, {i + 1, j + 1, root2}});
      }
  }

  /// Solves, writing every unknown; returns max |constraint residual| / extent.
  /// Nullspace method: x = x_p + Z y, x_p the least-norm solution of C x = d (least squares if
  /// the constraints were inconsistent: then the residual says so), Z spanning ker C, y
  /// minimising the energy.
  double solve(double extent) {
    Eigen::MatrixXd c, d, en, ee;
    stack(constraints_, c, d);
    stack(energy_, en, ee);
    Eigen::BDCSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeThinU | Eigen::ComputeFullV);
    svd.setThreshold(1e-11);
    const Eigen::Index rank = svd.rank();
    const Eigen::MatrixXd xp = svd.solve(d);
    const Eigen::MatrixXd z = svd.matrixV().rightCols(m_ - rank);
    Eigen::MatrixXd x = xp;
    if (z.cols() > 0) x += z * (en * z).colPivHouseholderQr().solve(ee - en * xp);
    const double residual = c.rows() ? (c * x - d).rowwise().norm().maxCoeff() / extent : 0.0;
    for (std::size_t k = 0; k < known_.size(); ++k)
      if (unknown_[k] >= 0) known_[k] = x.row(unknown_[k]).transpose();
    return residual;
  }

  /// The n × n clamped piece whose point (0, 0) is G(i0, j0), after solve().
  BSplineSurface piece(int i0, int j0, std::uint32_t n) const {
    ControlNet net(n, n);
    for (std::uint32_t i = 0; i <= n; ++i)
      for (std::uint32_t j = 0; j <= n; ++j)
        net(i, j) = known_[at(i0 + static_cast<int>(i), j0 + static_cast<int>(j))];
    return BSplineSurface(std::move(net), KnotType::Clamped, KnotType::Clamped);
  }

 private:
  struct Rows {
    std::vector<Eigen::RowVectorXd> a;
    std::vector<Eigen::RowVector3d> b;
  };
  void add(Rows& rows, const std::vector<std::tuple<int, int, double>>& terms) const {
    Eigen::RowVectorXd a = Eigen::RowVectorXd::Zero(m_);
    Eigen::RowVector3d b = Eigen::RowVector3d::Zero();
    double scale = 0.0;
    for (const auto& [i, j, c] : terms) scale = std::max(scale, std::abs(c));
    for (const auto& [i, j, c] : terms) {
      const int u = unknown_[at(i, j)];
      if (u >= 0)
        a(u) += c / scale;
      else
        b -= (c / scale) * known_[at(i, j)].transpose();
    }
    if (a.cwiseAbs().maxCoeff() == 0.0) return;  // only known points: holds or not, by input
    rows.a.push_back(a);
    rows.b.push_back(b);
  }
  void stack(const Rows& rows, Eigen::MatrixXd& a, Eigen::MatrixXd& b) const {
    a.resize(static_cast<Eigen::Index>(rows.a.size()), m_);
    b.resize(static_cast<Eigen::Index>(rows.a.size()), 3);
    for (std::size_t r = 0; r < rows.a.size(); ++r) {
      a.row(static_cast<Eigen::Index>(r)) = rows.a[r];
      b.row(static_cast<Eigen::Index>(r)) = rows.b[r];
    }
  }

  int rows_, cols_;
  bool periodic_;
  std::vector<Vec3> known_;
  std::vector<int> unknown_;
  int m_ = 0;
  Rows constraints_, energy_;
};

/// The bounding-box diagonal of some point sets (at least a tiny positive number).
double extentOf(std::initializer_list<const std::vector<Vec3>*> sets) {
  Eigen::AlignedBox3d box;
  for (const auto* c : sets)
    for (const Vec3& p : *c) box.extend(p);
  return std::max(box.diagonal().norm(), 1e-300);
}

/// Measured C1 gap over the seams: for each (a, b, across U?) the derivative across the seam
/// from piece a (at its far side) against piece b (at its near side), 65 points each.
double measureC1Gap(const std::vector<BSplineSurface>& pieces,
                    const std::vector<std::tuple<std::size_t, std::size_t, bool>>& seams) {
  double gap = 0.0, scale = 0.0;
  constexpr int kSamples = 64;
  for (const auto& [a, b, acrossU] : seams)
    for (int k = 0; k <= kSamples; ++k) {
      const double t = static_cast<double>(k) / kSamples;
      const SurfacePoint pa = acrossU ? pieces[a].evaluate(1.0, t) : pieces[a].evaluate(t, 1.0);
      const SurfacePoint pb = acrossU ? pieces[b].evaluate(0.0, t) : pieces[b].evaluate(t, 0.0);
      const Vec3 da = acrossU ? pa.du : pa.dv, db = acrossU ? pb.du : pb.dv;
      gap = std::max(gap, (da - db).norm());
      scale = std::max(scale, da.norm());
    }
  return gap / std::max(scale, 1e-300);
}

}  // namespace

C1Blend blendFourCurves(const BSplineCurve& uMin, const BSplineCurve& uMax,
                        const BSplineCurve& vMin, const BSplineCurve& vMax, std::uint32_t n) {
  if (n < 3)
    throw InvalidArgument("blendFourCurves: n = " + std::to_string(n) +
                          " (last index of a piece) must be at least 3");
  const auto split = [n](const BSplineCurve& c, const char* name) {
    return splitAtMiddle(refitCurve(c, n, std::string("blendFourCurves: curve ") + name), n);
  };
  const std::vector<Vec3> w = split(uMin, "uMin"), e = split(uMax, "uMax"), s = split(vMin, "vMin"),
                          nn = split(vMax, "vMax");
  const double extent = extentOf({&w, &e, &s, &nn});
  const auto corner = [&](const Vec3& a, const char* an, const Vec3& b, const char* bn) {
    if ((a - b).norm() > kBSplineCornerTolerance * extent)
      throw InvalidArgument(std::string("blendFourCurves: curves ") + an + " and " + bn +
                            " do not meet at their shared corner");
  };
  corner(w.front(), "uMin", s.front(), "vMin");
  corner(w.back(), "uMin", nn.front(), "vMax");
  corner(e.front(), "uMax", s.back(), "vMin");
  corner(e.back(), "uMax", nn.back(), "vMax");

  // The global net G(i, j), 0 ≤ i, j ≤ 2n; piece (p, q) is G[pn .. pn+n][qn .. qn+n].
  const int ni = static_cast<int>(n), size = 2 * ni + 1, last = size - 1;
  BlendSystem sys(size, size, false);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      const auto k = static_cast<std::size_t>(i == 0 || i == last ? j : i);
      if (i == 0)
        sys.setKnown(i, j, w[k]);
      else if (i == last)
        sys.setKnown(i, j, e[k]);
      else if (j == 0)
        sys.setKnown(i, j, s[k]);
      else if (j == last)
        sys.setKnown(i, j, nn[k]);
      else
        sys.setUnknown(i, j);
    }
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) sys.pieceMasks(p * ni, q * ni, n);
  sys.seamRow(ni);
  sys.seamColumn(ni);
  sys.thinPlateEnergy();
  C1Blend blend;
  blend.maxConstraintResidual = sys.solve(extent);
  for (std::uint32_t p = 0; p < 2; ++p)
    for (std::uint32_t q = 0; q < 2; ++q) {
      blend.pieces.push_back(sys.piece(static_cast<int>(p) * ni, static_cast<int>(q) * ni, n));
      blend.origin.push_back({p, q});
    }
  // ∂/∂U across U = 1 and ∂/∂V across V = 1 (unit spans: local = global derivatives).
  blend.seamGaps = {{"U = 1", measureC1Gap(blend.pieces, {{0, 2, true}, {1, 3, true}})},
                    {"V = 1", measureC1Gap(blend.pieces, {{0, 1, false}, {2, 3, false}})}};
  blend.maxC1Gap = std::max(blend.seamGaps[0].second, blend.seamGaps[1].second);
  return blend;
}

C1Blend blendClosedCurves(const BSplineCurve& start, const BSplineCurve& end, std::uint32_t n) {
  if (n < 3)
    throw InvalidArgument("blendClosedCurves: n = " + std::to_string(n) +
                          " (last index of a piece) must be at least 3");
  const auto closedSplit = [n](const BSplineCurve& c, const char* name) {
    const std::string where = std::string("blendClosedCurves: curve ") + name;
    std::vector<Vec3> points = refitCurve(c, n, where);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : c.points) box.extend(p);
    const double size = std::max(box.diagonal().norm(), 1e-300);
    if ((c.points.front() - c.points.back()).norm() > kBSplineCornerTolerance * size)
      throw InvalidArgument(where + " is not closed: its first and last points differ");
    // C1 where it closes: the first and last legs (equal spans) become their mean.
    const Vec3 leg = 0.5 * ((points[1] - points[0]) + (points.back() - points[points.size() - 2]));
    points.back() = points.front();
    points[1] = points.front() + leg;
    points[points.size() - 2] = points.back() - leg;
    return splitAtMiddle(std::move(points), n);
  };
  const std::vector<Vec3> a = closedSplit(start, "start"), b = closedSplit(end, "end");
  const double extent = extentOf({&a, &b});
  // The global net G(i, j), 0 ≤ i ≤ n, 0 ≤ j < 2n periodic; piece q is G[0..n][qn .. qn+n].
  const int ni = static_cast<int>(n), cols = 2 * ni;
  BlendSystem sys(ni + 1, cols, true);
  for (int i = 0; i <= ni; ++i)
    for (int j = 0; j < cols; ++j) {
      if (i == 0)
        sys.setKnown(i, j, a[static_cast<std::size_t>(j)]);
      else if (i == ni)
        sys.setKnown(i, j, b[static_cast<std::size_t>(j)]);
      else
        sys.setUnknown(i, j);
    }
  sys.pieceMasks(0, 0, n);
  sys.pieceMasks(0, ni, n);
  sys.seamColumn(0);
  sys.seamColumn(ni);
  sys.thinPlateEnergy();
  C1Blend blend;
  blend.closedV = true;
  blend.maxConstraintResidual = sys.solve(extent);
  for (std::uint32_t q = 0; q < 2; ++q) {
    blend.pieces.push_back(sys.piece(0, static_cast<int>(q) * ni, n));
    blend.origin.push_back({0, q});
  }
  blend.seamGaps = {{"V = 1", measureC1Gap(blend.pieces, {{0, 1, false}})},
                    {"V = 0", measureC1Gap(blend.pieces, {{1, 0, false}})}};
  blend.maxC1Gap = std::max(blend.seamGaps[0].second, blend.seamGaps[1].second);
  return blend;
}

}  // namespace pdesurf
