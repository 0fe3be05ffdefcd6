// Sections taken as they come (include/pdesurf/sections.hpp; docs/spectral.md).
#include "numerics/eigen_warnings.hpp"  // first: see the file

#include "pdesurf/sections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <Eigen/Eigenvalues>

#include "spectral/internal.hpp"

namespace pdesurf {

namespace {

using spectral::numberText;

/// Relative area (to the squared perimeter) below which a loop encloses nothing: a loop
/// folded onto itself, or points on a line. A circle has area / perimeter² = 1/(4π) ≈ 0.08.
constexpr double kFlatLoop = 1e-12;

std::string pointText(const Vec3& p) {
  return "(" + numberText(p.x()) + ", " + numberText(p.y()) + ", " + numberText(p.z()) + ")";
}

/// A closed polygon with its arc lengths: cum[j] is the length from point 0 to point j.
struct Loop {
  std::vector<Vec3> points;
  std::vector<double> cum;
  double length = 0.0;
  Vec3 normal = Vec3::Zero();    ///< Newell's vector: 2 × the vector area
  Vec3 centroid = Vec3::Zero();  ///< perimeter centroid

  void measure() {
    const std::size_t n = points.size();
    cum.assign(n, 0.0);
    normal.setZero();
    centroid.setZero();
    length = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3& a = points[j];
      const Vec3& b = points[(j + 1) % n];
      const double l = (b - a).norm();
      cum[j] = length;
      length += l;
      normal += a.cross(b);
      centroid += 0.5 * l * (a + b);
    }
    centroid /= length;
  }
  void reverse() {
    std::reverse(points.begin() + 1, points.end());  // keep point 0, run the other way
    measure();
  }
  /// The point at arc length s (any real: taken modulo the length).
  Vec3 at(double s) const {
    s = std::fmod(s, length);
    if (s < 0.0) s += length;
    const auto j =
        static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin() - 1);
    const Vec3& a = points[j];
    const Vec3& b = points[(j + 1) % points.size()];
    const double l = (j + 1 < cum.size() ? cum[j + 1] : length) - cum[j];
    return l > 0.0 ? Vec3(a + (s - cum[j]) / l * (b - a)) : a;
  }
  std::vector<Vec3> resample(double offset, std::uint32_t count) const {
    std::vector<Vec3> out(count);
    for (std::uint32_t j = 0; j < count; ++j) out[j] = at(offset + length * j / count);
    return out;
  }
};

Loop cleanLoop(const std::vector<Vec3>& raw, std::uint32_t index) {
  Loop loop;
  for (std::size_t j = 0; j < raw.size(); ++j) {
    if (!raw[j].allFinite())
      throw SectionError(index, "point " + std::to_string(j) + " is not finite");
    if (loop.points.empty() || raw[j] != loop.points.back()) loop.points.push_back(raw[j]);
  }
  while (loop.points.size() > 1 && loop.points.back() == loop.points.front())
    loop.points.pop_back();
  if (loop.points.size() < 3)
    throw SectionError(index, "has " + std::to_string(loop.points.size()) +
                                  " distinct points; a closed curve needs at least 3");
  loop.measure();
  return loop;
}

/// The normal of the loop's best-fit plane (least squares through its points): defined for
/// loops whose signed area cancels (a figure eight), unlike Newell's vector.
Vec3 bestFitNormal(const Loop& loop) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : loop.points) mean += p;
  mean /= static_cast<double>(loop.points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3& p : loop.points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  return eigen.eigenvectors().col(0);  // the smallest eigenvalue's vector
}

void checkArea(const Loop& loop, std::uint32_t index) {
  if (!(0.5 * loop.normal.norm() > kFlatLoop * loop.length * loop.length))
    throw SectionError(index,
                       "encloses no area (its points lie on a line or fold back onto "
                       "themselves)");
}

/// 2D orientation of c against the line a→b: > 0 left, < 0 right, 0 on it.
double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segmentsMeet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  const Eigen::Vector2d& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
         (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

/// Throws unless no two non-adjacent edges of the loop, projected onto its plane, meet.
/// A sweep over the edges sorted by their smallest x: each edge is tested only against the
/// edges whose x-range overlaps its own.
void checkSimple(const Loop& loop, std::uint32_t index) {
  const std::size_t n = loop.points.size();
  const Vec3 normal = bestFitNormal(loop);
  const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  std::vector<Eigen::Vector2d> q(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3 d = loop.points[j] - loop.centroid;
    q[j] = {d.dot(e1), d.dot(e2)};
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto lo = [&](std::size_t j) { return std::min(q[j].x(), q[(j + 1) % n].x()); };
  auto hi = [&](std::size_t j) { return std::max(q[j].x(), q[(j + 1) % n].x()); };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t x = 0; x < n; ++x) {
    const std::size_t j = order[x];
    for (std::size_t y = x + 1; y < n && lo(order[y]) <= hi(j); ++y) {
      const std::size_t k = order[y];
      const std::size_t gap = j > k ? j - k : k - j;
      if (gap == 1 || gap == n - 1) continue;  // neighbours share a point
      if (segmentsMeet(q[j], q[(j + 1) % n], q[k], q[(k + 1) % n]))
        throw SectionError(index, "is not a simple closed curve: its edges " +
                                      std::to_string(std::min(j, k)) + " and " +
                                      std::to_string(std::max(j, k)) + " meet near " +
                                      pointText(loop.points[std::min(j, k)]));
    }
  }
}

/// The arc length where the ray from the centroid along `reference` (projected into the
/// loop's plane) leaves the loop: its outermost crossing; the point farthest along the
/// reference when the ray crosses nothing (a centroid outside a strongly bent loop).
double startOnRay(const Loop& loop, const Vec3& reference) {
  const Vec3 normal = loop.normal.normalized();
  Vec3 e1 = reference - reference.dot(normal) * normal;
  if (!(e1.norm() > 1e-9 * reference.norm())) e1 = normal.unitOrthogonal();
  e1.normalize();
  const Vec3 e2 = normal.cross(e1);
  const std::size_t n = loop.points.size();
  double best = -1.0, bestS = 0.0, far = -std::numeric_limits<double>::infinity(), farS = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3 a = loop.points[j] - loop.centroid, b = loop.points[(j + 1) % n] - loop.centroid;
    const double ya = a.dot(e2), yb = b.dot(e2);
    if (a.dot(e1) > far) {
      far = a.dot(e1);
      farS = loop.cum[j];
    }
    if ((ya < 0.0) == (yb < 0.0) || ya == yb) continue;  // b lies on the same side as a
    const double t = ya / (ya - yb);
    const double x = (1 - t) * a.dot(e1) + t * b.dot(e1);
    if (x > best) {
      best = x;
      const double l = (j + 1 < n ? loop.cum[j + 1] : loop.length) - loop.cum[j];
      bestS = loop.cum[j] + t * l;
    }
  }
  return best > 0.0 ? bestS : farS;
}

/// Centred points scaled to unit RMS radius.
std::vector<Vec3> normalisedShape(const std::vector<Vec3>& points) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) c += p;
  c /= static_cast<double>(points.size());
  double r = 0.0;
  for (const Vec3& p : points) r += (p - c).squaredNorm();
  r = std::sqrt(r / static_cast<double>(points.size()));
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back((p - c) / std::max(r, 1e-300));
  return out;
}

/// The start offset (arc length) of `loop` that twists it least against `previous` (the
/// prepared points of the section before): the best of `count` evenly spaced starts, refined
/// by a parabola through its neighbours' costs.
double leastTwistStart(const Loop& loop, const std::vector<Vec3>& previous, std::uint32_t count) {
  const std::vector<Vec3> p = normalisedShape(previous),
                          q = normalisedShape(loop.resample(0, count));
  std::vector<double> cost(count, 0.0);
  for (std::uint32_t k = 0; k < count; ++k)
    for (std::uint32_t j = 0; j < count; ++j) cost[k] += (q[(j + k) % count] - p[j]).squaredNorm();
  const auto best =
      static_cast<std::uint32_t>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  const double cm = cost[(best + count - 1) % count], c0 = cost[best],
               cp = cost[(best + 1) % count];
  const double curvature = cm - 2 * c0 + cp;
  const double shift = curvature > 0.0 ? std::clamp(0.5 * (cm - cp) / curvature, -0.5, 0.5) : 0.0;
  return (best + shift) * loop.length / count;
}

}  // namespace

std::vector<SampledCurve> prepareSections(std::span<const std::vector<Vec3>> raw,
                                          const SectionPrepOptions& options) {
  if (options.points < 8)
    throw InvalidArgument("sections are resampled to at least 8 points, asked for " +
                          std::to_string(options.points));
  if (options.direction && !(options.direction->allFinite() && options.direction->norm() > 0.0))
    throw InvalidArgument("the chain direction must be a finite, non-zero vector");
  if (options.reference && !(options.reference->allFinite() && options.reference->norm() > 0.0))
    throw InvalidArgument("the reference direction must be a finite, non-zero vector");
  std::vector<Loop> loops;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    loops.push_back(cleanLoop(raw[i], static_cast<std::uint32_t>(i)));
    checkSimple(loops.back(), static_cast<std::uint32_t>(i));
    checkArea(loops.back(), static_cast<std::uint32_t>(i));
  }
  const std::size_t count = loops.size();
  // The chain direction at each section; sections whose neighbours share their centroid
  // fall back to the first section's normal.
  std::vector<Vec3> direction(count);
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 d = options.direction.value_or(Vec3::Zero());
    if (!options.direction && count > 1)
      d = loops[std::min(i + 1, count - 1)].centroid - loops[i > 0 ? i - 1 : 0].centroid;
    if (!(d.norm() > 0.0)) d = loops[0].normal;
    direction[i] = d;
  }
  for (std::size_t i = 0; i < count; ++i)
    if (loops[i].normal.dot(direction[i]) < 0.0) loops[i].reverse();
  std::vector<SampledCurve> out(count);
  std::vector<double> v(options.points);
  for (std::uint32_t j = 0; j < options.points; ++j) v[j] = spectral::kTwoPi * j / options.points;
  for (std::size_t i = 0; i < count; ++i) {
    double start = 0.0;
    if (i == 0) {
      Vec3 reference = options.reference.value_or(Vec3::Zero());
      if (!options.reference) {
        const Vec3 d = direction[0].normalized();
        int axis = 0;
        for (int k = 1; k < 3; ++k)
          if (std::abs(d[k]) < std::abs(d[axis])) axis = k;
        reference = Vec3::Unit(axis);
      }
      start = startOnRay(loops[0], reference);
    } else {
      start = leastTwistStart(loops[i], out[i - 1].points, options.points);
    }
    out[i].points = loops[i].resample(start, options.points);
    out[i].v = v;
  }
  return out;
}

}  // namespace pdesurf
