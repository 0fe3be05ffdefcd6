// Moving, turning and scaling a whole model: an affine map x → A x + t applied to what the
// model file says (its data), so that saving writes the transformed model. Points (vertices,
// position curves, spine points) take the whole map, directions and rates of change
// (forces, derivative curves, Fourier modes above 0) only A.
//
// What re-solving the transformed data gives (tests/io/transform_test.cpp checks each):
// - spectral and cross-section models: every operator acts alike on x, y and z and has no
//   zeroth-order term, the Fourier fit and the remainder are linear in the points, and
//   chord lengths (v of points, u placement) scale uniformly under a similarity A = s R.
//   So for a similarity the solved transformed model is exactly the transformed surface.
//   For a general A it is the solve of the transformed data, which differs from the
//   transformed surface only where chord lengths decide v or u.
// - B-spline PDE models: likewise (transformModel below).
// - vertex frames: S ↦ A S + t solves a1 S_uu + a2 S_vv = A F when a1 and a2 are the same
//   in x, y and z (then the PDE acts alike on every component). With per-component a1/a2
//   the model is re-solved from the transformed vertices and forces: it still interpolates
//   the transformed vertices, but A mixes components that had different PDEs, so the
//   surface is not the transformed one in general (translations always are exact).
#pragma once

#include <Eigen/Core>

#include "pdesurf/model.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// |det A| at or below this fraction of ‖A‖³ (Frobenius) makes a map singular: such a map
/// flattens the model (and its inverse, the undo, would blow rounding up by 1e12).
constexpr double kSingularMapTolerance = 1e-12;

/// x → linear · x + translation. A value; compose with `*` (right-hand map first).
struct AffineMap {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Vec3 translation = Vec3::Zero();

  /// A point: A x + t.
  Vec3 point(const Vec3& x) const { return linear * x + translation; }
  /// A direction, a force or a derivative: A d.
  Vec3 vector(const Vec3& d) const { return linear * d; }
  /// This map after `first`: x → this(first(x)).
  AffineMap operator*(const AffineMap& first) const {
    return {linear * first.linear, linear * first.translation + translation};
  }

  /// x + t. Throws InvalidArgument when t is not finite.
  static AffineMap translationBy(const Vec3& t);
  /// A turn by `radians` about the line through `center` along `axis` (right-handed).
  /// Throws InvalidArgument for a zero or non-finite axis, a non-finite angle or
  /// center.
  static AffineMap rotationAbout(const Vec3& axis, double radians, const Vec3& center);
  /// center + s (x − center). Throws InvalidArgument unless s is finite and > 0.
  static AffineMap scalingAbout(double s, const Vec3& center);

  /// Throws InvalidArgument when an entry is not finite or A is singular
  /// (kSingularMapTolerance).
  void validate() const;
  /// Whether A = s R, s > 0, R a rotation, to `tolerance` relative to s² (A Aᵀ = s² I).
  bool isSimilarity(double tolerance = 1e-12) const;
};

/// Curves: points and a0 affine, the Fourier modes a_n, b_n linear; `linearOnly` (a
/// derivative condition's curve) applies A alone to everything.
CurveInput transformCurve(const CurveInput& curve, const AffineMap& map, bool linearOnly = false);

/// Vertices affine; frame and shared forces f0 → A f0 (a1, a2 and regions unchanged). With
/// per-component a1/a2 a turned force may fall on a component without solution: check
/// with checkTransform (session.hpp) before solving.
VertexFrameModel transformModel(const VertexFrameModel& model, const AffineMap& map);
/// Position conditions affine, derivative conditions (derivative ≥ 1) linear; spine edits
/// move the spine through absolute points, so their `moved` points are affine.
SpectralModel transformModel(const SpectralModel& model, const AffineMap& map);
/// Every curve affine.
CrossSectionModel transformModel(const CrossSectionModel& model, const AffineMap& map);
/// Control points (net, boundary curves and samples, second rows, blend curves) affine;
/// tangent functions (cross-boundary derivatives) linear. The mask equations act alike on
/// x, y and z and B-spline bases sum to 1, so the solved model is the transformed surface
/// (for a similarity where samples are placed by chord length).
BSplinePdeModel transformModel(const BSplinePdeModel& model, const AffineMap& map);
/// Any model: its method's transform (SurfaceMethod::transform, method.hpp).
AnyModel transformModel(const AnyModel& model, const AffineMap& map);

}  // namespace pdesurf
