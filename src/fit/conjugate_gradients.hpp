// Preconditioned conjugate gradients for the fit's two symmetric systems (the vertices' least
// squares, fit.cpp, and the shape fit's a1, a2 step, shape_step.cpp), applied as products:
// neither matrix is formed.
#pragma once

#include <algorithm>

#include <Eigen/Dense>

namespace pdesurf::fit {

/// At most this many CG steps a solve (the preconditioners leave the strips' coupling
/// only: a few dozen steps in practice); then the last iterate is used.
inline constexpr int kMaxCgSteps = 400;

/// Preconditioned conjugate gradients on A x = b from x (apply: v ↦ A v, A symmetric;
/// precondition: r ↦ M⁻¹ r), until the residual is within `tolerance` of |b| or within
/// `reduction` of the starting residual, kMaxCgSteps at most; a direction of non-positive
/// curvature (A not positive there, or rounding) ends it.
template <class Apply, class Precondition>
Eigen::VectorXd conjugateGradients(const Apply& apply, const Precondition& precondition,
                                   const Eigen::VectorXd& b, Eigen::VectorXd x, double tolerance,
                                   double reduction) {
  Eigen::VectorXd r = b - apply(x);
  Eigen::VectorXd z = precondition(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  const double bound = std::max(tolerance * b.norm(), reduction * r.norm());
  for (int step = 0; step < kMaxCgSteps && r.norm() > bound; ++step) {
    const Eigen::VectorXd hp = apply(p);
    const double curvature = p.dot(hp);
    if (!(curvature > 0.0)) break;
    const double alpha = rz / curvature;
    x += alpha * p;
    r -= alpha * hp;
    z = precondition(r);
    const double next = r.dot(z);
    p = z + (next / rz) * p;
    rz = next;
  }
  return x;
}

}  // namespace pdesurf::fit
