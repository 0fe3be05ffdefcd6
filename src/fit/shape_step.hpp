// The shape fit's parts (FitOptions::fitShape, docs/rebuild.md): one whole-frame force a frame,
// held by its amplitude, and the damped Gauss–Newton direction in ln a1 and ln a2.
#pragma once

#include <optional>

#include <Eigen/Dense>

#include "fit/linear_surface.hpp"
#include "fit/pairs.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::fit {

/// The amplitude k of a frame's whole-frame force: its particular solution is
/// k sin(πu) sin(πv) (detail::forceAmplitude with Lu = Lv = 1, as the solver computes it);
/// zero for a frame without force.
Vec3 wholeFrameForceAmplitude(const Frame& f);

/// Sets the frame's whole-frame force to amplitude k for its a1, a2 (none where k is 0).
void setWholeFrameForceAmplitude(Frame& f, const Vec3& k);

/// One damped Gauss–Newton direction in ln a1 and ln a2 of every frame (per component) on the
/// pairs of `current` (the evaluation of `model`), with the vertices and the forces'
/// amplitudes fixed: 6 a frame (a1's x, y, z, then a2's), scaled so that no ln a changes by
/// more than kMaxLogStep; nothing when no parameter moves a strip value.
///
/// a1 and a2 move the surface only through the strip values X (the forces keep their
/// amplitude), so S_i = S_i⁰ + A_i ΔX and ΔX ≈ G Δθ with G = linear.parameterJacobian.
/// The squared distances (tangential weight μ, as the least squares weighs them) are then
/// ½ Δθᵀ (Gᵀ K G) Δθ + (Gᵀ g)ᵀ Δθ + const with K = Σ w A_iᵀ M A_i and
/// g = Σ w A_iᵀ M (S_i⁰ - t_i), both over the strips (small and sparse); Gᵀ K G couples every
/// frame of two crossing strips, so it is never formed: Jacobi-preconditioned conjugate
/// gradients apply it as products with G, K and Gᵀ. `damping` is the Levenberg–Marquardt λ
/// of λ diag(GᵀKG).
std::optional<Eigen::VectorXd> parameterDirection(const LinearSurface& linear,
                                                  const VertexFrameModel& model,
                                                  const Evaluation& current,
                                                  double tangentialWeight, double damping);

/// `model` with every frame's a1 and a2 multiplied by exp(fraction × direction), within
/// [kMinShapeParameter, kMaxShapeParameter], each frame's force keeping its amplitude.
VertexFrameModel withParameterStep(const VertexFrameModel& model, const Eigen::VectorXd& direction,
                                   double fraction);

}  // namespace pdesurf::fit
