// Coons patches on the boundary curves of a pdesurf patch: the baselines of seed 000 §4.2
// (Fig. 8), used by comparisons, never by the PDE methods (docs/coons.md).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// A curve on [0, 1] and its derivative.
struct CoonsCurve {
  std::function<Vec3(double)> value, derivative;
};

/// The four boundaries, named as the seed names a patch's sides: α(u) = S(u, 0),
/// β(u) = S(u, 1), γ(v) = S(0, v), δ(v) = S(1, v). Their corners must agree
/// (α(0) = γ(0), α(1) = δ(0), β(0) = γ(1), β(1) = δ(1)).
struct CoonsBoundary {
  CoonsCurve alpha, beta, gamma, delta;
};

/// Cross-boundary derivatives: S_v along α and β, S_u along γ and δ.
struct CoonsTangents {
  CoonsCurve alpha, beta, gamma, delta;
};

/// A bilinear or bicubic Coons patch (the Boolean sum of two lofts minus their tensor
/// product). Both interpolate the four boundaries exactly. The bicubic one meets the
/// tangents where they agree with the boundaries at the corners (Tα(0) = γ'(0), ...), and
/// reproduces every bicubic polynomial surface from its own boundary data; its corner twists
/// are the mean of the two tangents' derivatives at each corner.
class CoonsPatch {
 public:
  static CoonsPatch bilinear(CoonsBoundary boundary);
  static CoonsPatch bicubic(CoonsBoundary boundary, CoonsTangents tangents);

  bool isBicubic() const { return bicubic_; }
  SurfacePoint evaluate(double u, double v) const;

 private:
  CoonsBoundary b_;
  CoonsTangents t_;
  bool bicubic_ = false;
  /// Corner data of the tensor-product term: rows [S(0,·), S(1,·), S_u(0,·), S_u(1,·)],
  /// columns [·(v=0), ·(v=1), ∂v·(v=0), ∂v·(v=1)].
  std::array<std::array<Vec3, 4>, 4> corner_{};
};

/// The boundary curves of a vertex-frame patch, with their analytic derivatives.
CoonsBoundary boundaryOf(const VertexFramePatch& patch);

/// The seed's tangent functions w1 α(u), w2 β(u), w3 γ(v), w4 δ(v) (component-wise
/// products of a weight vector and the boundary curve).
CoonsTangents seedTangents(const CoonsBoundary& boundary, const std::array<Vec3, 4>& w);

/// The patch's own cross-boundary derivatives (S_v on α and β, S_u on γ and δ); their
/// derivatives along the boundary by central differences (step kCoonsTangentStep).
CoonsTangents patchTangents(const VertexFramePatch& patch);

/// Step of the central differences in patchTangents: the truncation error h² |S'''| and the
/// rounding error ε/h balance near 1e-5 for surfaces of unit size.
constexpr double kCoonsTangentStep = 1e-5;

/// Each patch sampled on an options.resolution × options.resolution grid with normals from
/// the derivatives; patches are not welded to each other (a baseline, not a model).
Mesh tessellate(const std::vector<CoonsPatch>& patches, const TessellateOptions& options = {});

}  // namespace pdesurf
