// The basic geometry every layer shares (docs/architecture.md): points and vectors, a surface
// point with its first derivatives, and the resolution of a tessellation. The engines depend
// on this header (and mesh.hpp) only.
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pdesurf {

using Vec3 = Eigen::Vector3d;

/// S, ∂S/∂u and ∂S/∂v at one parameter point.
struct SurfacePoint {
  Vec3 p, du, dv;
};

/// How finely a surface of any type becomes a mesh: one options struct for every model
/// type, the CLI's --resolution and the studio's meshes.
struct TessellateOptions {
  /// Samples per patch side (≥ 2): each patch becomes a resolution × resolution grid.
  std::uint32_t resolution = 17;
};

}  // namespace pdesurf
