// Affine maps of whole models (include/pdesurf/transform.hpp).
#include "pdesurf/transform.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "pdesurf/error.hpp"
#include "pdesurf/method.hpp"

namespace pdesurf {

AffineMap AffineMap::translationBy(const Vec3& t) {
  if (!t.allFinite())
    throw InvalidArgument(
        fmt::format("translation [{}, {}, {}] is not finite", t.x(), t.y(), t.z()));
  return {Eigen::Matrix3d::Identity(), t};
}

AffineMap AffineMap::rotationAbout(const Vec3& axis, double radians, const Vec3& center) {
  if (!axis.allFinite() || axis.norm() == 0.0 || !std::isfinite(axis.norm()))
    throw InvalidArgument(fmt::format("rotation axis [{}, {}, {}] is not a finite non-zero vector",
                                      axis.x(), axis.y(), axis.z()));
  if (!std::isfinite(radians))
    throw InvalidArgument(fmt::format("rotation angle {} is not finite", radians));
  if (!center.allFinite()) throw InvalidArgument("rotation center is not finite");
  const Eigen::Matrix3d r = Eigen::AngleAxisd(radians, axis.normalized()).toRotationMatrix();
  return {r, center - r * center};
}

AffineMap AffineMap::scalingAbout(double s, const Vec3& center) {
  if (!std::isfinite(s) || !(s > 0.0))
    throw InvalidArgument(fmt::format("scale {} is not a finite number above 0", s));
  if (!center.allFinite()) throw InvalidArgument("scaling center is not finite");
  return {s * Eigen::Matrix3d::Identity(), (1.0 - s) * center};
}

void AffineMap::validate() const {
  if (!linear.allFinite() || !translation.allFinite())
    throw InvalidArgument("the map has a number that is not finite");
  const double size = linear.norm();
  if (!std::isfinite(size * size * size) ||
      !(std::abs(linear.determinant()) > kSingularMapTolerance * size * size * size))
    throw InvalidArgument("the map is singular: it would flatten the model");
}

bool AffineMap::isSimilarity(double tolerance) const {
  const double s2 = linear.norm() * linear.norm() / 3.0;
  return s2 > 0.0 && linear.determinant() > 0.0 &&
         (linear * linear.transpose() - s2 * Eigen::Matrix3d::Identity()).norm() <= tolerance * s2;
}

CurveInput transformCurve(const CurveInput& curve, const AffineMap& map, bool linearOnly) {
  const auto point = [&](const Vec3& p) { return linearOnly ? map.vector(p) : map.point(p); };
  if (const auto* sampled = std::get_if<SampledCurve>(&curve)) {
    SampledCurve out = *sampled;  // v and closed stay: chord-length v is similarity-invariant
    for (Vec3& p : out.points) p = point(p);
    return out;
  }
  FourierCurve out = std::get<FourierCurve>(curve);
  out.a0 = point(out.a0);
  for (Vec3& a : out.a) a = map.vector(a);
  for (Vec3& b : out.b) b = map.vector(b);
  return out;
}

VertexFrameModel transformModel(const VertexFrameModel& model, const AffineMap& map) {
  VertexFrameModel out = model;
  for (Vec3& v : out.vertices) v = map.point(v);
  for (Frame& f : out.frames)
    for (FrameForce& force : f.forces) force.f0 = map.vector(force.f0);
  for (SharedForce& force : out.forces) force.f0 = map.vector(force.f0);
  return out;
}

SpectralModel transformModel(const SpectralModel& model, const AffineMap& map) {
  SpectralModel out = model;
  for (SpectralCondition& c : out.conditions)
    c.curve = transformCurve(c.curve, map, c.derivative > 0);
  for (SpineEdit& edit : out.spineEdits)
    for (Vec3& p : edit.moved) p = map.point(p);
  return out;
}

CrossSectionModel transformModel(const CrossSectionModel& model, const AffineMap& map) {
  CrossSectionModel out = model;
  for (CurveInput& c : out.curves) c = transformCurve(c, map);
  return out;
}

BSplinePdeModel transformModel(const BSplinePdeModel& model, const AffineMap& map) {
  BSplinePdeModel out = model;
  const auto points = [&](std::vector<Vec3>& list) {
    for (Vec3& p : list) p = map.point(p);  // NaN (unused inner net points) stays NaN
  };
  points(out.net.points);
  for (BoundaryCurve* c :
       {&out.boundary.uMin, &out.boundary.uMax, &out.boundary.vMin, &out.boundary.vMax})
    std::visit([&](auto& curve) { points(curve.points); }, *c);
  for (SecondRowInput* row : {&out.boundary.uMinSecond, &out.boundary.vMinSecond}) {
    if (auto* given = std::get_if<std::vector<Vec3>>(row)) {
      points(*given);
      continue;
    }
    // A tangent is a derivative: the linear part only.
    std::visit(
        [&](auto& curve) {
          for (Vec3& d : curve.points) d = map.linear * d;
        },
        std::get<TangentCurve>(*row).vectors);
  }
  for (BSplineCurve& c : out.curves) points(c.points);
  return out;
}

AnyModel transformModel(const AnyModel& model, const AffineMap& map) {
  return model.method().transform(model, map);
}

}  // namespace pdesurf
