// The basic geometry every layer shares (docs/architecture.md): points and vectors, a surface
// point with its first derivatives, and the resolution of a tessellation. The engines depend
// on this header (and mesh.hpp) only.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pdesurf/error.hpp"

namespace pdesurf {

using Vec3 = Eigen::Vector3d;

/// S, ∂S/∂u and ∂S/∂v at one parameter point.
struct SurfacePoint {
  Vec3 p, du, dv;
};

/// How finely a surface becomes a mesh: the options of every `tessellate` (a model of any
/// method, each engine's surfaces, Coons baselines), the CLI's --resolution and the studio's
/// meshes.
struct TessellateOptions {
  /// Samples per patch side (≥ 2): each patch becomes a resolution × resolution grid. A
  /// spectral or cross-section patch: `resolution` rows along u; a B-spline surface: at least
  /// resolution − 1 segments along the side with more knot spans, a whole number per span.
  std::uint32_t resolution = 17;
  /// Spectral and cross-section patches: distinct columns around the closed direction v
  /// (≥ 3). 0 (the default): 4 (resolution − 1), at least 8, since a turn is about 2π times
  /// longer than a patch is long. The other surfaces have no closed direction of their own:
  /// it leaves their meshes as they are.
  std::uint32_t aroundResolution = 0;
};

/// Throws InvalidArgument for a resolution below 2 or an aroundResolution of 1 or 2: every
/// tessellate checks its options so.
inline void checkTessellateOptions(const TessellateOptions& options) {
  if (options.resolution < 2)
    throw InvalidArgument("tessellate: resolution must be at least 2, got " +
                          std::to_string(options.resolution));
  if (options.aroundResolution == 1 || options.aroundResolution == 2)
    throw InvalidArgument("tessellate: aroundResolution must be 0 or at least 3, got " +
                          std::to_string(options.aroundResolution));
}

}  // namespace pdesurf
