// Boundary curves and second rows to the known rows and columns of a net (seed condition 3.1);
// the rules are in docs/bspline-pde.md §"Boundaries from curves".
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include <Eigen/QR>

#include "bspline_pde/internal.hpp"

namespace pdesurf {

Vec3 BSplineCurve::evaluate(double t, int k) const {
  if (points.size() < 4)
    throw InvalidArgument("BSplineCurve: " + std::to_string(points.size()) +
                          " control points; a cubic needs at least 4");
  if (k < 0 || k > 3)
    throw InvalidArgument("BSplineCurve: derivative order " + std::to_string(k) +
                          " must be within 0..3");
  const auto n = static_cast<std::uint32_t>(points.size() - 1);
  const std::vector<double> knotVector = cubicKnots(knots, n);
  const CubicBasis b = bspline::cubicBasis(knotVector, n, t);
  Vec3 sum = Vec3::Zero();
  for (std::uint32_t r = 0; r < 4; ++r) sum += b.d[k][r] * points[b.span - 3 + r];
  return sum;
}

namespace bspline {

/// Least-squares control points 0..n on `knots` for values at parameters; with `pinEnds`, the
/// first and last control points are the first and last values (clamped ends interpolate).
std::vector<Vec3> fitControlPoints(const std::vector<Vec3>& values,
                                   const std::vector<double>& params, KnotType knots,
                                   std::uint32_t n, bool pinEnds, const std::string& where) {
  const std::vector<double> knotVector = cubicKnots(knots, n);
  const auto rows = static_cast<Eigen::Index>(values.size());
  const Eigen::Index first = pinEnds ? 1 : 0;
  const Eigen::Index cols = static_cast<Eigen::Index>(n) + 1 - 2 * first;
  if (rows < cols + 2 * first)
    throw InvalidArgument(where + ": " + std::to_string(values.size()) +
                          " samples are too few for " + std::to_string(n + 1) + " control points");
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  Eigen::MatrixXd b(rows, 3);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const CubicBasis basis =
        bspline::cubicBasis(knotVector, n, params[static_cast<std::size_t>(k)]);
    Vec3 rhs = values[static_cast<std::size_t>(k)];
    for (std::uint32_t r = 0; r < 4; ++r) {
      const Eigen::Index c = static_cast<Eigen::Index>(basis.span - 3 + r) - first;
      if (c < 0)
        rhs -= basis.d[0][r] * values.front();
      else if (c >= cols)
        rhs -= basis.d[0][r] * values.back();
      else
        a(k, c) = basis.d[0][r];
    }
    b.row(k) = rhs.transpose();
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < cols)
    throw InvalidArgument(where + ": the samples leave some of the " + std::to_string(n + 1) +
                          " control points undetermined (too few samples in some span)");
  const Eigen::MatrixXd x = qr.solve(b);
  std::vector<Vec3> out(n + 1);
  for (Eigen::Index c = 0; c < cols; ++c) out[static_cast<std::size_t>(c + first)] = x.row(c);
  if (pinEnds) {
    out.front() = values.front();
    out.back() = values.back();
  }
  return out;
}

std::vector<Vec3> fitFunction(const std::function<Vec3(double)>& f, KnotType knots, std::uint32_t n,
                              bool pinEnds, const std::string& where) {
  const std::uint32_t m = kBoundaryResampleFactor * (n + 1);
  std::vector<Vec3> values(m + 1);
  std::vector<double> params(m + 1);
  for (std::uint32_t k = 0; k <= m; ++k) {
    params[k] = static_cast<double>(k) / m;
    values[k] = f(params[k]);
    if (!values[k].allFinite())
      throw InvalidArgument(where + ": not finite at parameter " + std::to_string(params[k]));
  }
  return fitControlPoints(values, params, knots, n, pinEnds, where);
}

}  // namespace bspline

namespace {

struct Side {
  const char* name;  // for messages
  std::uint32_t n;   // last control index along the side
  KnotType knots;    // the knots along the side
  const BoundaryCurve* curve;
};

void requireFinite(const std::vector<Vec3>& points, const std::string& where) {
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite())
      throw InvalidArgument(where + ": point " + std::to_string(k) + " is not finite");
}

std::vector<double> sampleParameters(const CurveSamples& s, const std::string& where) {
  const std::size_t m = s.points.size();
  if (m < 2) throw InvalidArgument(where + ": needs at least 2 samples");
  requireFinite(s.points, where);
  if (!s.t.empty()) {
    if (s.t.size() != m)
      throw InvalidArgument(where + ": " + std::to_string(s.t.size()) + " parameters for " +
                            std::to_string(m) + " samples");
    if (s.t.front() != 0.0 || s.t.back() != 1.0)
      throw InvalidArgument(where + ": parameters must start at 0 and end at 1");
    for (std::size_t k = 1; k < m; ++k)
      if (!(s.t[k] > s.t[k - 1]))
        throw InvalidArgument(where + ": parameter " + std::to_string(k) + " does not increase");
    return s.t;
  }
  std::vector<double> t(m, 0.0);
  for (std::size_t k = 1; k < m; ++k) t[k] = t[k - 1] + (s.points[k] - s.points[k - 1]).norm();
  if (!(t.back() > 0.0)) throw InvalidArgument(where + ": all samples coincide (no chord length)");
  for (double& x : t) x /= t.back();
  t.back() = 1.0;
  return t;
}

/// The n + 1 control points of a side from its curve.
std::vector<Vec3> sidePoints(const Side& side) {
  const std::string where = std::string("boundaryNet: curve ") + side.name;
  if (const auto* c = std::get_if<BSplineCurve>(side.curve)) {
    requireFinite(c->points, where);
    if (c->points.size() == side.n + 1 && c->knots == side.knots) return c->points;
    if (side.knots != KnotType::Clamped)
      throw InvalidArgument(where + ": has " + std::to_string(c->points.size()) +
                            " control points on other knots; uniform knots along this "
                            "side need exactly " +
                            std::to_string(side.n + 1) + " on uniform knots");
    if (c->points.size() < 4)
      throw InvalidArgument(where + ": " + std::to_string(c->points.size()) +
                            " control points; a cubic needs at least 4");
    return bspline::fitFunction([c](double t) { return c->evaluate(t); }, side.knots, side.n, true,
                                where);
  }
  const auto& samples = std::get<CurveSamples>(*side.curve);
  if (side.knots != KnotType::Clamped)
    throw InvalidArgument(where +
                          ": sampled curves need clamped knots along the side "
                          "(a uniform-knot surface does not interpolate its boundary)");
  return bspline::fitControlPoints(samples.points, sampleParameters(samples, where), side.knots,
                                   side.n, true, where);
}

/// Row 1 (or column 1): given points, or P_0 + (λ/3) D from a tangent function.
std::vector<Vec3> secondRow(const SecondRow& second, const std::vector<Vec3>& first,
                            KnotType across, std::uint32_t nAcross, KnotType along,
                            const std::string& where) {
  const auto n = static_cast<std::uint32_t>(first.size() - 1);
  if (const auto* given = std::get_if<std::vector<Vec3>>(&second)) {
    if (given->size() != n + 1)
      throw InvalidArgument(where + ": " + std::to_string(given->size()) +
                            " points given, the side has " + std::to_string(n + 1));
    requireFinite(*given, where);
    return *given;
  }
  const auto& tangent = std::get<TangentFunction>(second);
  if (!tangent) throw InvalidArgument(where + ": empty tangent function");
  if (across != KnotType::Clamped)
    throw InvalidArgument(where +
                          ": a tangent function needs clamped knots across the "
                          "side (with uniform knots row 1 does not set the tangent)");
  const std::vector<Vec3> d = bspline::fitFunction(tangent, along, n, false, where + " (tangent)");
  // Clamped: x_u(0, v) = (3/λ) Σ_j (P_{1,j} - P_{0,j}) N_j(v), λ = 1/(n_across - 2).
  const double lambda = 1.0 / static_cast<double>(nAcross - 2);
  std::vector<Vec3> out(n + 1);
  for (std::uint32_t j = 0; j <= n; ++j) out[j] = first[j] + (lambda / 3.0) * d[j];
  return out;
}

}  // namespace

ControlNet boundaryNet(const BSplineBoundary& bd) {
  if (bd.nu < 3 || bd.nv < 3)
    throw InvalidArgument("boundaryNet: nu = " + std::to_string(bd.nu) + ", nv = " +
                          std::to_string(bd.nv) + "; both last indices must be at least 3");
  const KnotType ku = bd.knots.uKnots, kv = bd.knots.vKnots;
  const std::vector<Vec3> uMin = sidePoints({"uMin", bd.nv, kv, &bd.uMin});
  const std::vector<Vec3> uMax = sidePoints({"uMax", bd.nv, kv, &bd.uMax});
  const std::vector<Vec3> vMin = sidePoints({"vMin", bd.nu, ku, &bd.vMin});
  const std::vector<Vec3> vMax = sidePoints({"vMax", bd.nu, ku, &bd.vMax});

  Eigen::AlignedBox3d box;
  for (const auto* side : {&uMin, &uMax, &vMin, &vMax})
    for (const Vec3& p : *side) box.extend(p);
  const double tolerance = kBSplineCornerTolerance * std::max(box.diagonal().norm(), 1e-300);
  const auto corner = [&](const Vec3& a, const char* aName, const Vec3& b, const char* bName,
                          const char* label) {
    if ((a - b).norm() > tolerance)
      throw InvalidArgument(std::string("boundaryNet: corner ") + label + ": curve " + aName +
                            " and curve " + bName + " end " + std::to_string((a - b).norm()) +
                            " apart");
    return (0.5 * (a + b)).eval();
  };
  ControlNet net(bd.nu, bd.nv);
  const std::uint32_t nu = bd.nu, nv = bd.nv;
  for (std::uint32_t j = 0; j <= nv; ++j) {
    net(0, j) = uMin[j];
    net(nu, j) = uMax[j];
  }
  for (std::uint32_t i = 0; i <= nu; ++i) {
    net(i, 0) = vMin[i];
    net(i, nv) = vMax[i];
  }
  net(0, 0) = corner(uMin.front(), "uMin", vMin.front(), "vMin", "(u,v) = (0,0)");
  net(0, nv) = corner(uMin.back(), "uMin", vMax.front(), "vMax", "(0,1)");
  net(nu, 0) = corner(uMax.front(), "uMax", vMin.back(), "vMin", "(1,0)");
  net(nu, nv) = corner(uMax.back(), "uMax", vMax.back(), "vMax", "(1,1)");

  std::vector<Vec3> row0(nv + 1), column0(nu + 1);
  for (std::uint32_t j = 0; j <= nv; ++j) row0[j] = net(0, j);
  for (std::uint32_t i = 0; i <= nu; ++i) column0[i] = net(i, 0);
  const std::vector<Vec3> row1 =
      secondRow(bd.uMinSecond, row0, ku, nu, kv, "boundaryNet: uMinSecond (row 1)");
  const std::vector<Vec3> column1 =
      secondRow(bd.vMinSecond, column0, kv, nv, ku, "boundaryNet: vMinSecond (column 1)");
  // Given rows must agree with the curves where both own a point; tangent rows yield to them.
  const bool rowGiven = std::holds_alternative<std::vector<Vec3>>(bd.uMinSecond);
  const bool columnGiven = std::holds_alternative<std::vector<Vec3>>(bd.vMinSecond);
  if (rowGiven) {
    corner(row1.front(), "uMinSecond", vMin[1], "vMin", "P(1,0)");
    corner(row1.back(), "uMinSecond", vMax[1], "vMax", "P(1,nv)");
  }
  if (columnGiven) {
    corner(column1.front(), "vMinSecond", uMin[1], "uMin", "P(0,1)");
    corner(column1.back(), "vMinSecond", uMax[1], "uMax", "P(nu,1)");
  }
  for (std::uint32_t j = 2; j < nv; ++j) net(1, j) = row1[j];
  for (std::uint32_t i = 2; i < nu; ++i) net(i, 1) = column1[i];
  net(1, 1) = 0.5 * (row1[1] + column1[1]);
  return net;
}

}  // namespace pdesurf
