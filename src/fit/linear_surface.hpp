// A vertex-frame surface as a linear function of the model's vertex positions: with a1, a2
// and the forces fixed, S(k, u, v) = Σ φ_i(u,v) P_i + ψ(u) C3 + ψ(v) C6 + S_p(u, v), and the
// global solver's strip values C3, C6 are themselves linear in the vertices (docs/rebuild.md).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Sparse>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::fit {

/// ψ(t) = t³ - 3t²/2 + t/2: how a strip's cubic coefficient enters a patch along its
/// direction (the closed form's C1, C2 and C3 terms together); 0 at t = 0, ½ and 1.
inline double cubicShape(double t) { return t * (t - 0.5) * (t - 1.0); }
/// ψ'(t) = 3t² - 3t + ½.
inline double cubicShapeDerivative(double t) { return 3.0 * t * t - 3.0 * t + 0.5; }

/// One surface point as weights on unknowns: the frame's 8 vertices and its two strips.
struct PointWeights {
  std::array<double, 8> vertex{};  ///< φ_i(u, v) for the frame's P1..P8
  std::array<double, 2> strip{};   ///< parity × ψ(u), parity × ψ(v)
  Vec3 offset = Vec3::Zero();      ///< the forces' particular solution S_p(u, v)
};

class LinearSurface {
 public:
  /// Built for the model's frames, a1, a2 and forces; the vertex positions may change.
  explicit LinearSurface(const VertexFrameModel& model);

  const FrameTopology& topology() const { return *topology_; }
  std::shared_ptr<const FrameTopology> sharedTopology() const { return topology_; }
  std::uint32_t stripCount() const { return topology_->stripCount; }

  /// The weights of S(frame, u, v).
  PointWeights weights(std::uint32_t frame, double u, double v) const;
  /// The weights of the derivative ∂S/∂u (direction 0) or ∂S/∂v (direction 1) at (u, v):
  /// S_u and S_v are affine in the unknowns as S is.
  PointWeights derivativeWeights(std::uint32_t frame, double u, double v, int direction) const;

  /// The global solver's strip values as rows on the vertices: component c of strip s is
  /// Σ_j stripRows(c)(s, j) x_j[c] (a zero row for a pinned or undetermined strip).
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& stripRows(int component) const {
    return stripRows_[component];
  }

  /// S(frame, u, v) for the given vertices (the strip values computed from them).
  Vec3 position(const std::vector<Vec3>& vertices, std::uint32_t frame, double u, double v) const;
  /// The strip values of the given vertices, per strip, per component.
  std::vector<Vec3> stripValues(const std::vector<Vec3>& vertices) const;

  /// How the global solver's strip values move with the frames' a1 and a2, at the given
  /// vertices: row 3s + c, column 6k + 3w + c is ∂X_s[c] / ∂ ln a_w[c] of frame k (w = 0:
  /// a1, 1: a2). With X_s = -N_s / D_s, N_s = Σ s_p a_p o_p cross_p / 3 and D_s = Σ a_p²
  /// (src/vertex_frames/solve.cpp), each term of N_s is of degree one in ln a1 and in ln a2
  /// of its frame and a_p² of degree two in its own a, so ∂X_s = -(∂N_s + X_s ∂D_s) / D_s
  /// (docs/rebuild.md, "Fitting the shape"). Pinned and undetermined strips have zero rows.
  Eigen::SparseMatrix<double, Eigen::RowMajor> parameterJacobian(
      const std::vector<Vec3>& vertices) const;

  const Frame& frame(std::uint32_t k) const { return frames_[k]; }

 private:
  /// S's weights (direction -1) or those of its derivative along u (0) or v (1).
  PointWeights weightsOf(std::uint32_t frame, double u, double v, int direction) const;

  std::vector<Frame> frames_;
  std::vector<std::vector<ForceTerm>> forces_;
  std::shared_ptr<const FrameTopology> topology_;
  std::array<Eigen::SparseMatrix<double, Eigen::RowMajor>, 3> stripRows_;
};

}  // namespace pdesurf::fit
