// The point of a patch nearest a given point, as parameters (session.hpp: nearestParameters).
#include <algorithm>
#include <cmath>

#include "pdesurf/session.hpp"

namespace pdesurf {

namespace {

/// Samples per side of the grid that finds the basin of the nearest point: finer than any
/// fold a second-order patch with forces makes between them.
constexpr int kNearestGrid = 17;
/// Gauss-Newton steps at most; each halves the error at least once in the basin.
constexpr int kNearestSteps = 40;
/// Steps shorter than this in (u, v) end the refinement: far below the 1e-6 a region's bound
/// is typed with.
constexpr double kNearestStep = 1e-13;

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

}  // namespace

std::array<double, 2> nearestParameters(const VertexFramePatch& patch, const Vec3& point) {
  double u = 0.0, v = 0.0, best = INFINITY;
  for (int j = 0; j < kNearestGrid; ++j)
    for (int i = 0; i < kNearestGrid; ++i) {
      const double su = double(i) / (kNearestGrid - 1), sv = double(j) / (kNearestGrid - 1);
      const double d = (patch.evaluate(su, sv).p - point).squaredNorm();
      if (d < best) best = d, u = su, v = sv;
    }
  for (int step = 0; step < kNearestSteps; ++step) {
    const SurfacePoint s = patch.evaluate(u, v);
    const Vec3 r = s.p - point;
    // The normal equations of min |S(u, v) - point|² linearised at (u, v).
    const double a = s.du.dot(s.du), b = s.du.dot(s.dv), c = s.dv.dot(s.dv);
    const double gu = s.du.dot(r), gv = s.dv.dot(r);
    const double det = a * c - b * b;
    if (!(std::abs(det) > 0.0)) break;  // a pole: the grid's sample stands
    double du = -(c * gu - b * gv) / det, dv = -(a * gv - b * gu) / det;
    // Shortened until the distance drops (and kept inside the patch).
    double nu = clamp01(u + du), nv = clamp01(v + dv);
    double d = (patch.evaluate(nu, nv).p - point).squaredNorm();
    for (int halve = 0; halve < 30 && d > r.squaredNorm(); ++halve) {
      du /= 2, dv /= 2;
      nu = clamp01(u + du), nv = clamp01(v + dv);
      d = (patch.evaluate(nu, nv).p - point).squaredNorm();
    }
    if (d > r.squaredNorm()) break;
    const double moved = std::hypot(nu - u, nv - v);
    u = nu, v = nv;
    if (moved < kNearestStep) break;
  }
  return {u, v};
}

}  // namespace pdesurf
