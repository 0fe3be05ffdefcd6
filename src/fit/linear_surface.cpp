// The vertex-frame surface as a linear map of the vertex positions (docs/rebuild.md).
#include "fit/linear_surface.hpp"

#include <algorithm>
#include <cmath>

#include "numerics/force_shape.hpp"

namespace pdesurf::fit {
namespace {

/// basis[m][i]: the coefficient of monomial m (1, u, u², u³, v, v², v³, uv, u²v, uv²) that
/// vertex P(i+1) contributes with both cubic coefficients 0, read off the closed form itself
/// (patchCoefficients), so the two can never disagree.
using Basis = std::array<std::array<double, 8>, 10>;
const Basis& basis() {
  static const Basis table = [] {
    Basis b{};
    for (int i = 0; i < 8; ++i) {
      std::array<Vec3, 8> p;
      p.fill(Vec3::Zero());
      p[i] = Vec3::UnitX();
      const std::array<Vec3, 10> c = patchCoefficients(p, Vec3::Zero(), Vec3::Zero());
      for (int m = 0; m < 10; ++m) b[m][i] = c[m].x();
    }
    return b;
  }();
  return table;
}

/// The weights of P1..P8 in C9 (direction 0, the u-strip's cross term) and in C8
/// (direction 1), from the closed form as well (docs/derivations.md §1.2 lists them).
using CrossWeights = std::array<std::array<double, 8>, 2>;
const CrossWeights& crossWeights() {
  static const CrossWeights table = [] {
    CrossWeights w{};
    for (int d = 0; d < 2; ++d)
      for (int i = 0; i < 8; ++i) w[d][i] = basis()[d == 0 ? 9 : 8][i];
    return w;
  }();
  return table;
}

/// Per strip, for component c: the largest |a| of the frames along it (the solver's scaling,
/// which keeps the sums finite) and D = Σ (a / scale)² over its frames.
struct StripScales {
  std::vector<double> scale, den;
};

StripScales stripScales(const FrameTopology& topo, const std::vector<Frame>& frames, int c) {
  StripScales out{std::vector<double>(topo.stripCount, 0.0),
                  std::vector<double>(topo.stripCount, 0.0)};
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (int d = 0; d < 2; ++d) {
      const double a = std::abs(d == 0 ? frames[k].a1[c] : frames[k].a2[c]);
      out.scale[topo.strip[k][d]] = std::max(out.scale[topo.strip[k][d]], a);
    }
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (int d = 0; d < 2; ++d) {
      const std::uint32_t s = topo.strip[k][d];
      if (out.scale[s] == 0.0) continue;
      const double a = (d == 0 ? frames[k].a1[c] : frames[k].a2[c]) / out.scale[s];
      out.den[s] += a * a;
    }
  return out;
}

}  // namespace

LinearSurface::LinearSurface(const VertexFrameModel& model)
    : frames_(model.frames),
      topology_(std::make_shared<const FrameTopology>(buildTopology(model))) {
  // The forces' particular solutions depend on a1, a2, f0 and the regions, not on positions.
  const VertexFrameSurface solved = solve(model, topology_);
  forces_.reserve(solved.patches.size());
  for (const VertexFramePatch& patch : solved.patches) forces_.push_back(patch.forces);

  // The global solver (src/vertex_frames/solve.cpp): per strip and component,
  // X = -Σ s_p a_p b_p / Σ a_p² with b_p = other_p × cross_p / 3 and cross_p linear in the
  // patch's vertices. The same scaling by the strip's largest |a| keeps it finite.
  const FrameTopology& topo = *topology_;
  const std::uint32_t strips = topo.stripCount;
  const auto nFrames = static_cast<std::uint32_t>(frames_.size());
  for (int c = 0; c < 3; ++c) {
    const auto [scale, den] = stripScales(topo, frames_, c);
    std::vector<Eigen::Triplet<double>> triplets;
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (int d = 0; d < 2; ++d) {
        const std::uint32_t s = topo.strip[k][d];
        if (topo.stripPinned[s] || den[s] == 0.0) continue;  // the solver's 0
        const Frame& f = frames_[k];
        const double a = (d == 0 ? f.a1[c] : f.a2[c]) / scale[s];
        const double other = (d == 0 ? f.a2[c] : f.a1[c]) / scale[s];
        const double factor = -topo.parity[k][d] * a * other / 3.0 / den[s];
        for (int i = 0; i < 8; ++i)
          if (crossWeights()[d][i] != 0.0)
            triplets.emplace_back(s, f.vertices[i], factor * crossWeights()[d][i]);
      }
    stripRows_[c].resize(strips, static_cast<Eigen::Index>(model.vertices.size()));
    stripRows_[c].setFromTriplets(triplets.begin(), triplets.end());
  }
}

PointWeights LinearSurface::weights(std::uint32_t frame, double u, double v) const {
  return weightsOf(frame, u, v, -1);
}

PointWeights LinearSurface::derivativeWeights(std::uint32_t frame, double u, double v,
                                              int direction) const {
  return weightsOf(frame, u, v, direction);
}

PointWeights LinearSurface::weightsOf(std::uint32_t frame, double u, double v,
                                      int direction) const {
  const double u2 = u * u, v2 = v * v;
  // The monomials 1, u, u², u³, v, v², v³, uv, u²v, uv², or their derivatives along u or v.
  const std::array<double, 10> m =
      direction < 0    ? std::array{1.0, u, u2, u2 * u, v, v2, v2 * v, u * v, u2 * v, u * v2}
      : direction == 0 ? std::array{0.0, 1.0, 2 * u, 3 * u2, 0.0, 0.0, 0.0, v, 2 * u * v, v2}
                       : std::array{0.0, 0.0, 0.0, 0.0, 1.0, 2 * v, 3 * v2, u, u2, 2 * u * v};
  PointWeights w;
  const Basis& b = basis();
  for (int i = 0; i < 8; ++i) {
    double sum = 0.0;
    for (int k = 0; k < 10; ++k) sum += b[k][i] * m[k];
    w.vertex[i] = sum;
  }
  const auto along = [&](double t, int d) {
    return direction < 0 ? cubicShape(t) : direction == d ? cubicShapeDerivative(t) : 0.0;
  };
  w.strip[0] = topology_->parity[frame][0] * along(u, 0);
  w.strip[1] = topology_->parity[frame][1] * along(v, 1);
  for (const ForceTerm& f : forces_[frame]) {
    const detail::ForceShape su = detail::forceShape(u, f.region.u0, f.region.u1);
    const detail::ForceShape sv = detail::forceShape(v, f.region.v0, f.region.v1);
    const double s = direction < 0 ? su.s * sv.s : direction == 0 ? su.ds * sv.s : su.s * sv.ds;
    w.offset += s * f.k;
  }
  return w;
}

std::vector<Vec3> LinearSurface::stripValues(const std::vector<Vec3>& vertices) const {
  std::vector<Vec3> values(stripCount(), Vec3::Zero());
  for (int c = 0; c < 3; ++c) {
    const auto& rows = stripRows_[c];
    for (Eigen::Index s = 0; s < rows.outerSize(); ++s)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, s); it; ++it)
        values[s][c] += it.value() * vertices[it.col()][c];
  }
  return values;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> LinearSurface::parameterJacobian(
    const std::vector<Vec3>& vertices) const {
  const FrameTopology& topo = *topology_;
  const std::uint32_t strips = topo.stripCount;
  const auto nFrames = static_cast<std::uint32_t>(frames_.size());
  const std::vector<Vec3> x = stripValues(vertices);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < 3; ++c) {
    // The same scaling by the strip's largest |a| as the solver's: X is unchanged by it,
    // and so are its derivatives (N and D both scale by its square).
    const auto [scale, den] = stripScales(topo, frames_, c);
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (int d = 0; d < 2; ++d) {
        const std::uint32_t s = topo.strip[k][d];
        if (topo.stripPinned[s] || den[s] == 0.0) continue;  // X is 0 whatever a1, a2 are
        const Frame& f = frames_[k];
        const double a = (d == 0 ? f.a1[c] : f.a2[c]) / scale[s];
        const double other = (d == 0 ? f.a2[c] : f.a1[c]) / scale[s];
        double cross = 0.0;
        for (int i = 0; i < 8; ++i) cross += crossWeights()[d][i] * vertices[f.vertices[i]][c];
        const double term = topo.parity[k][d] * a * other * cross / 3.0;  // this term of N_s
        // Column of ln a (a1 for the u-strip, d = 0) and of ln other.
        const auto own = static_cast<Eigen::Index>(6 * k + 3 * d + c);
        const auto second = static_cast<Eigen::Index>(6 * k + 3 * (1 - d) + c);
        const auto row = static_cast<Eigen::Index>(3 * s + c);
        triplets.emplace_back(row, own, -(term + x[s][c] * 2.0 * a * a) / den[s]);
        triplets.emplace_back(row, second, -term / den[s]);
      }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian(3 * static_cast<Eigen::Index>(strips),
                                                        6 * static_cast<Eigen::Index>(nFrames));
  jacobian.setFromTriplets(triplets.begin(), triplets.end());
  return jacobian;
}

Vec3 LinearSurface::position(const std::vector<Vec3>& vertices, std::uint32_t frame, double u,
                             double v) const {
  const PointWeights w = weights(frame, u, v);
  const std::vector<Vec3> x = stripValues(vertices);
  Vec3 p = w.offset;
  for (int i = 0; i < 8; ++i) p += w.vertex[i] * vertices[frames_[frame].vertices[i]];
  for (int d = 0; d < 2; ++d) p += w.strip[d] * x[topology_->strip[frame][d]];
  return p;
}

}  // namespace pdesurf::fit
