// Closed curves: Fourier series, parameters of sampled curves, least-squares fitting
// (seed 002 §3.1), periodic splines for tails, natural splines for spine edits.
#include "numerics/eigen_warnings.hpp"  // first: see the file

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/QR>

#include "spectral/internal.hpp"

namespace pdesurf {

namespace {
using spectral::kTwoPi;
using spectral::numberText;

/// Drops a closing duplicate point (the first point written again at the end).
std::vector<Vec3> openPoints(const SampledCurve& curve) {
  std::vector<Vec3> p = curve.points;
  if (p.size() >= 2 && curve.v.empty() && (p.back() - p.front()).norm() == 0.0) p.pop_back();
  return p;
}
}  // namespace

Vec3 FourierCurve::evaluate(double v, std::uint32_t k) const {
  Vec3 x = k == 0 ? a0 : Vec3::Zero();
  const double shift = k * std::numbers::pi / 2.0;  // d^k/dv^k cos(nv) = n^k cos(nv + kπ/2)
  for (std::uint32_t n = 1; n <= terms(); ++n) {
    const double nd = n;
    const double f = std::pow(nd, static_cast<double>(k));
    x += f * (a[n - 1] * std::cos(nd * v + shift) + b[n - 1] * std::sin(nd * v + shift));
  }
  return x;
}

double spectral::spread(const std::vector<Vec3>& points) {
  double s = 0.0;
  for (const Vec3& p : points) s = std::max(s, (p - points.front()).norm());
  return s;
}

std::vector<double> curveParameters(const SampledCurve& curve, VParameterization parameterization) {
  if (!curve.closed)
    throw InvalidArgument("open curve: spectral patches need closed curves (periodic in v)");
  if (!curve.v.empty()) {
    if (curve.v.size() != curve.points.size())
      throw InvalidArgument("curve has " + std::to_string(curve.points.size()) + " points but " +
                            std::to_string(curve.v.size()) + " v values");
    if (curve.points.size() < 3)
      throw InvalidArgument("closed curve needs at least 3 points, has " +
                            std::to_string(curve.points.size()));
    for (std::size_t j = 0; j < curve.v.size(); ++j) {
      const double v = curve.v[j];
      if (!std::isfinite(v) || v < 0.0 || v >= kTwoPi)
        throw InvalidArgument("v[" + std::to_string(j) + "] = " + numberText(v) +
                              " is outside [0, 2π)");
      if (j > 0 && !(v > curve.v[j - 1]))
        throw InvalidArgument("v values must increase strictly: v[" + std::to_string(j) +
                              "] = " + numberText(v) + " after " + numberText(curve.v[j - 1]));
    }
    return curve.v;
  }
  const std::vector<Vec3> p = openPoints(curve);
  const std::size_t count = p.size();
  if (count < 3)
    throw InvalidArgument("closed curve needs at least 3 points, has " + std::to_string(count));
  for (std::size_t j = 0; j < count; ++j)
    if (!p[j].allFinite()) throw InvalidArgument("point " + std::to_string(j) + " is not finite");
  std::vector<double> v(count);
  const bool collapsed = spectral::spread(p) == 0.0;
  if (parameterization == VParameterization::Uniform || collapsed) {
    // A curve collapsed to a point has no length: its v values do not matter.
    for (std::size_t j = 0; j < count; ++j)
      v[j] = kTwoPi * static_cast<double>(j) / static_cast<double>(count);
    return v;
  }
  std::vector<double> s(count + 1, 0.0);
  for (std::size_t j = 0; j < count; ++j) s[j + 1] = s[j] + (p[(j + 1) % count] - p[j]).norm();
  for (std::size_t j = 0; j < count; ++j) {
    v[j] = kTwoPi * s[j] / s[count];
    if (j > 0 && !(v[j] > v[j - 1]))
      throw InvalidArgument("points " + std::to_string(j - 1) + " and " + std::to_string(j) +
                            " coincide: chord-length v needs distinct consecutive points");
  }
  return v;
}

FourierFit fitFourier(const SampledCurve& curve, std::uint32_t terms,
                      const FourierFitOptions& options) {
  FourierFit fit;
  fit.v = curveParameters(curve, options.parameterization);
  fit.points = curve.v.empty() ? openPoints(curve) : curve.points;
  const std::size_t count = fit.points.size();
  const std::size_t unknowns = 2 * static_cast<std::size_t>(terms) + 1;
  if (count < unknowns)
    throw InvalidArgument(std::to_string(terms) + " Fourier terms need at least " +
                          std::to_string(unknowns) + " points, the curve has " +
                          std::to_string(count));
  // Extended precision and long double storage: no Eigen heap types of double (basis.hpp).
  spectral::MatrixR a(count, unknowns);
  spectral::MatrixR rhs(count, 3);
  for (std::size_t j = 0; j < count; ++j) {
    a(j, 0) = 1.0;
    for (std::uint32_t n = 1; n <= terms; ++n) {
      a(j, 2 * n - 1) = std::cos(n * fit.v[j]);
      a(j, 2 * n) = std::sin(n * fit.v[j]);
    }
    rhs.row(j) = fit.points[j].transpose().cast<spectral::Real>();
  }
  const Eigen::ColPivHouseholderQR<spectral::MatrixR> qr(a);
  if (qr.rank() < static_cast<Eigen::Index>(unknowns))
    throw InvalidArgument("the v values do not determine " + std::to_string(terms) +
                          " Fourier terms (points too clustered in v)");
  const spectral::MatrixR c = qr.solve(rhs);
  fit.curve.a0 = c.row(0).transpose().cast<double>();
  fit.curve.a.resize(terms);
  fit.curve.b.resize(terms);
  for (std::uint32_t n = 1; n <= terms; ++n) {
    fit.curve.a[n - 1] = c.row(2 * n - 1).transpose().cast<double>();
    fit.curve.b[n - 1] = c.row(2 * n).transpose().cast<double>();
  }
  double sum = 0.0;
  for (std::size_t j = 0; j < count; ++j) {
    const double e = (fit.curve.evaluate(fit.v[j]) - fit.points[j]).norm();
    fit.maxError = std::max(fit.maxError, e);
    sum += e;
  }
  fit.meanError = sum / static_cast<double>(count);
  return fit;
}

namespace spectral {

PeriodicSpline::PeriodicSpline(std::vector<double> v, std::vector<Vec3> y)
    : v_(std::move(v)), y_(std::move(y)), m_(v_.size(), Vec3::Zero()) {
  const std::size_t n = v_.size();
  auto h = [&](std::size_t j) {  // interval j → j+1 (the last one wraps by 2π)
    return j + 1 < n ? v_[j + 1] - v_[j] : v_[0] + kTwoPi - v_[n - 1];
  };
  // Cyclic tridiagonal system for the second derivatives m_j:
  // h_{j-1} m_{j-1} + 2(h_{j-1} + h_j) m_j + h_j m_{j+1} = 6(Δ_j - Δ_{j-1}), indices mod n.
  // Sherman–Morrison on the Thomas algorithm (diagonally dominant: no pivoting needed).
  std::vector<double> lower(n), diag(n), upper(n);
  std::vector<Vec3> rhs(n);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t prev = (j + n - 1) % n, next = (j + 1) % n;
    lower[j] = h(prev);
    upper[j] = h(j);
    diag[j] = 2.0 * (h(prev) + h(j));
    rhs[j] = 6.0 * ((y_[next] - y_[j]) / h(j) - (y_[j] - y_[prev]) / h(prev));
  }
  auto thomas = [&](std::vector<double> dg, std::vector<Vec3> r) {
    for (std::size_t j = 1; j < n; ++j) {
      const double f = lower[j] / dg[j - 1];
      dg[j] -= f * upper[j - 1];
      r[j] -= f * r[j - 1];
    }
    std::vector<Vec3> x(n);
    x[n - 1] = r[n - 1] / dg[n - 1];
    for (std::size_t j = n - 1; j-- > 0;) x[j] = (r[j] - upper[j] * x[j + 1]) / dg[j];
    return x;
  };
  // A = T + w zᵀ with corners A(0,n-1) = lower[0], A(n-1,0) = upper[n-1]: w = (γ,0..,upper[n-1])ᵀ,
  // z = (1,0..,lower[0]/γ)ᵀ and T's first and last diagonals reduced accordingly.
  const double gamma = -diag[0];
  std::vector<double> dg = diag;
  dg[0] -= gamma;
  dg[n - 1] -= upper[n - 1] * lower[0] / gamma;
  const std::vector<Vec3> x = thomas(dg, rhs);
  std::vector<Vec3> wv(n, Vec3::Zero());
  wv[0] = Vec3::Constant(gamma);
  wv[n - 1] = Vec3::Constant(upper[n - 1]);
  const std::vector<Vec3> q = thomas(dg, wv);
  const double zq = q[0].x() + lower[0] / gamma * q[n - 1].x();
  const Vec3 zx = x[0] + lower[0] / gamma * x[n - 1];
  for (std::size_t j = 0; j < n; ++j) m_[j] = x[j] - q[j].x() * zx / (1.0 + zq);
}

Vec3 PeriodicSpline::evaluate(double v, std::uint32_t k) const {
  const std::size_t n = v_.size();
  double x = std::fmod(v - v_[0], kTwoPi);
  if (x < 0) x += kTwoPi;
  x += v_[0];
  std::size_t j = static_cast<std::size_t>(std::upper_bound(v_.begin(), v_.end(), x) - v_.begin());
  j = j == 0 ? 0 : j - 1;
  const std::size_t j1 = (j + 1) % n;
  const double x0 = v_[j], x1 = j + 1 < n ? v_[j + 1] : v_[0] + kTwoPi;
  const double h = x1 - x0, a = x1 - x, b = x - x0;
  const Vec3 &y0 = y_[j], &y1 = y_[j1], &m0 = m_[j], &m1 = m_[j1];
  return spectral::cubicSegment(y0, y1, m0, m1, h, a, b, k);
}

SpineOffset naturalSpline(std::vector<double> u, std::vector<Vec3> y) {
  SpineOffset s;
  const std::size_t n = u.size();
  s.second.assign(n, Vec3::Zero());
  if (n >= 3) {
    // Tridiagonal (Thomas) solve for the interior second derivatives; ends are 0.
    std::vector<double> diag(n), upper(n);
    std::vector<Vec3> rhs(n, Vec3::Zero());
    for (std::size_t j = 1; j + 1 < n; ++j) {
      const double h0 = u[j] - u[j - 1], h1 = u[j + 1] - u[j];
      diag[j] = 2.0 * (h0 + h1);
      upper[j] = h1;
      rhs[j] = 6.0 * ((y[j + 1] - y[j]) / h1 - (y[j] - y[j - 1]) / h0);
    }
    for (std::size_t j = 2; j + 1 < n; ++j) {
      const double lower = u[j] - u[j - 1];
      const double f = lower / diag[j - 1];
      diag[j] -= f * upper[j - 1];
      rhs[j] -= f * rhs[j - 1];
    }
    for (std::size_t j = n - 2; j >= 1; --j) {
      Vec3 r = rhs[j];
      if (j + 2 < n) r -= upper[j] * s.second[j + 1];
      s.second[j] = r / diag[j];
    }
  }
  s.knots = std::move(u);
  s.values = std::move(y);
  return s;
}

Vec3 evaluateNaturalSpline(const SpineOffset& s, double u, std::uint32_t k) {
  const std::size_t n = s.knots.size();
  if (n == 1) return k == 0 ? s.values[0] : Vec3::Zero();
  // Interval and the end tangents for linear extension.
  auto slope = [&](std::size_t j, bool atRight) {  // derivative at an end of interval j
    const double h = s.knots[j + 1] - s.knots[j];
    const Vec3 base = (s.values[j + 1] - s.values[j]) / h;
    return atRight ? Vec3(base + h * (2 * s.second[j + 1] + s.second[j]) / 6)
                   : Vec3(base - h * (2 * s.second[j] + s.second[j + 1]) / 6);
  };
  if (u <= s.knots.front() || u >= s.knots.back()) {
    const bool left = u <= s.knots.front();
    const std::size_t j = left ? 0 : n - 2;
    const double u0 = left ? s.knots.front() : s.knots.back();
    const Vec3 y0 = left ? s.values.front() : s.values.back();
    const Vec3 d = slope(j, !left);
    if (k == 0) return y0 + d * (u - u0);
    return k == 1 ? d : Vec3::Zero();
  }
  std::size_t j = static_cast<std::size_t>(std::upper_bound(s.knots.begin(), s.knots.end(), u) -
                                           s.knots.begin()) -
                  1;
  const double x0 = s.knots[j], x1 = s.knots[j + 1], h = x1 - x0, a = x1 - u, b = u - x0;
  const Vec3 &y0 = s.values[j], &y1 = s.values[j + 1], &m0 = s.second[j], &m1 = s.second[j + 1];
  return spectral::cubicSegment(y0, y1, m0, m1, h, a, b, k);
}

ConditionData resolveCurve(const CurveInput& curve, std::uint32_t modes,
                           VParameterization parameterization, bool remainder,
                           const std::string& what) {
  ConditionData c;
  try {
    if (const auto* f = std::get_if<FourierCurve>(&curve)) {
      if (f->a.size() != f->b.size())
        throw InvalidArgument("Fourier curve has " + std::to_string(f->a.size()) + " cosine and " +
                              std::to_string(f->b.size()) + " sine terms");
      c.fourier.a0 = f->a0;
      c.fourier.a.assign(modes, Vec3::Zero());
      c.fourier.b.assign(modes, Vec3::Zero());
      for (std::uint32_t n = 1; n <= std::min(modes, f->terms()); ++n) {
        c.fourier.a[n - 1] = f->a[n - 1];
        c.fourier.b[n - 1] = f->b[n - 1];
      }
      bool hasTail = false;
      auto high = std::make_shared<FourierCurve>(*f);
      high->a0.setZero();
      for (std::uint32_t n = 1; n <= f->terms(); ++n) {
        if (n <= modes) {
          high->a[n - 1].setZero();
          high->b[n - 1].setZero();
        } else if (f->a[n - 1].squaredNorm() + f->b[n - 1].squaredNorm() > 0.0) {
          hasTail = true;
        }
      }
      if (hasTail && remainder) c.tail.push_back(TailTerm{1.0, nullptr, std::move(high)});
      return c;
    }
    const auto& s = std::get<SampledCurve>(curve);
    FourierFit fit = fitFourier(s, modes, FourierFitOptions{parameterization});
    c.fourier = std::move(fit.curve);
    c.points = std::move(fit.points);
    c.v = std::move(fit.v);
    c.collapsed = spread(c.points) <= kDegenerateCurveTolerance * (c.points.front().norm() + 1.0);
    if (remainder && fit.maxError > 0.0) {
      std::vector<Vec3> residual(c.points.size());
      for (std::size_t j = 0; j < residual.size(); ++j)
        residual[j] = c.points[j] - c.fourier.evaluate(c.v[j]);
      c.tail.push_back(
          TailTerm{1.0, std::make_shared<PeriodicSpline>(c.v, std::move(residual)), nullptr});
    }
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(what + ": " + e.what());
  }
  return c;
}

}  // namespace spectral
}  // namespace pdesurf
