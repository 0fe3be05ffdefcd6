// The shape fit's whole-frame forces and its a1, a2 direction (shape_step.hpp).
#include "fit/shape_step.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Sparse>

#include "fit/conjugate_gradients.hpp"
#include "numerics/force_shape.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf::fit {

namespace {

/// Added to the damped diagonal of the a1, a2 system: this fraction of its largest entry
/// everywhere, so that parameters that move no strip value (a frame's a1 and a2 scaled
/// together on strips of one frame, a strip value pinned to 0) stay, and the system is
/// positive definite.
constexpr double kParameterFloor = 1e-9;
/// Its conjugate gradients stop when the residual is this small relative to the gradient:
/// the step need not be more exact than its linearisation.
constexpr double kParameterCgTolerance = 1e-6;
/// No ln a1 or ln a2 changes by more than this in one step (a factor e).
constexpr double kMaxLogStep = 1.0;

}  // namespace

Vec3 wholeFrameForceAmplitude(const Frame& f) {
  if (f.forces.empty()) return Vec3::Zero();
  Vec3 k;
  for (int c = 0; c < 3; ++c)
    k[c] = detail::forceAmplitude(f.forces[0].f0[c], f.a1[c], f.a2[c], 1.0, 1.0);
  return k;
}

void setWholeFrameForceAmplitude(Frame& f, const Vec3& k) {
  f.forces.clear();
  if (k == Vec3::Zero()) return;
  Vec3 f0;
  for (int c = 0; c < 3; ++c) f0[c] = detail::forceOfAmplitude(k[c], f.a1[c], f.a2[c], 1.0, 1.0);
  f.forces.push_back({f0, Region{}});
}

std::optional<Eigen::VectorXd> parameterDirection(const LinearSurface& linear,
                                                  const VertexFrameModel& model,
                                                  const Evaluation& current,
                                                  double tangentialWeight, double damping) {
  const FrameTopology& topo = linear.topology();
  const auto nFrames = static_cast<std::uint32_t>(model.frames.size());
  const auto strips3 = 3 * static_cast<Eigen::Index>(topo.stripCount);
  const Eigen::Index params = 6 * static_cast<Eigen::Index>(nFrames);
  if (strips3 == 0) return std::nullopt;
  const VertexFrameSurface& surface = current.surface;
  const Eigen::SparseMatrix<double> g = linear.parameterJacobian(model.vertices);
  using Block = Eigen::Matrix<double, 6, 6>;
  std::vector<Block> blocks(nFrames, Block::Zero());
  Eigen::VectorXd gradientX = Eigen::VectorXd::Zero(strips3);
  const double mu = tangentialWeight;
  for (const Pair& p : current.pairs) {
    const double b0 = topo.parity[p.frame][0] * fit::cubicShape(p.u);
    const double b1 = topo.parity[p.frame][1] * fit::cubicShape(p.v);
    const Eigen::Matrix3d m =
        mu * Eigen::Matrix3d::Identity() + (1.0 - mu) * p.normal * p.normal.transpose();
    const Vec3 mr = m * (surface.patches[p.frame].position(p.u, p.v) - p.target);
    Block& block = blocks[p.frame];
    block.block<3, 3>(0, 0) += (p.weight * b0 * b0) * m;
    block.block<3, 3>(0, 3) += (p.weight * b0 * b1) * m;
    block.block<3, 3>(3, 0) += (p.weight * b1 * b0) * m;
    block.block<3, 3>(3, 3) += (p.weight * b1 * b1) * m;
    gradientX.segment<3>(3 * Eigen::Index{topo.strip[p.frame][0]}) += p.weight * b0 * mr;
    gradientX.segment<3>(3 * Eigen::Index{topo.strip[p.frame][1]}) += p.weight * b1 * mr;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(std::size_t{nFrames} * 36);
  for (std::uint32_t k = 0; k < nFrames; ++k)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        triplets.emplace_back(3 * Eigen::Index{topo.strip[k][i / 3]} + i % 3,
                              3 * Eigen::Index{topo.strip[k][j / 3]} + j % 3, blocks[k](i, j));
  Eigen::SparseMatrix<double> kx(strips3, strips3);
  kx.setFromTriplets(triplets.begin(), triplets.end());
  // diag(GᵀKG): a parameter moves at most its frame's two strips (two entries a column).
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(params);
  for (Eigen::Index col = 0; col < g.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator a(g, col); a; ++a)
      for (Eigen::SparseMatrix<double>::InnerIterator b(g, col); b; ++b)
        diagonal[col] += a.value() * kx.coeff(a.row(), b.row()) * b.value();
  const double largest = diagonal.maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;
  const Eigen::VectorXd damped = (1.0 + damping) * diagonal.array() + kParameterFloor * largest;
  const Eigen::VectorXd rhs = -(g.transpose() * gradientX);
  auto apply = [&](const Eigen::VectorXd& x) {
    const Eigen::VectorXd gx = g * x;
    return Eigen::VectorXd(g.transpose() * (kx * gx) + damping * diagonal.cwiseProduct(x) +
                           kParameterFloor * largest * x);
  };
  Eigen::VectorXd delta = conjugateGradients(
      apply, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(r.cwiseQuotient(damped)); },
      rhs, Eigen::VectorXd::Zero(params), kParameterCgTolerance, 0.0);
  // A trust region: no parameter changes by more than a factor e in one step.
  const double largestChange = delta.cwiseAbs().maxCoeff();
  if (!(largestChange > 0.0) || !std::isfinite(largestChange)) return std::nullopt;
  if (largestChange > kMaxLogStep) delta *= kMaxLogStep / largestChange;
  return delta;
}

VertexFrameModel withParameterStep(const VertexFrameModel& model, const Eigen::VectorXd& direction,
                                   double fraction) {
  VertexFrameModel candidate = model;
  for (std::size_t k = 0; k < candidate.frames.size(); ++k) {
    Frame& f = candidate.frames[k];
    const Vec3 amplitude = wholeFrameForceAmplitude(f);
    for (int w = 0; w < 2; ++w) {
      Vec3& a = w == 0 ? f.a1 : f.a2;
      for (int c = 0; c < 3; ++c)
        a[c] = std::clamp(
            a[c] * std::exp(fraction * direction[6 * static_cast<Eigen::Index>(k) + 3 * w + c]),
            kMinShapeParameter, kMaxShapeParameter);
    }
    setWholeFrameForceAmplitude(f, amplitude);
  }
  return candidate;
}

}  // namespace pdesurf::fit
