// The nearest point of a patch as parameters (session.hpp: nearestParameters), which the
// studio uses to place force regions on the surface.
#include <gtest/gtest.h>

#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf {
namespace {

/// Where the Gauss-Newton refinement ends: well below the parameters' use (regions typed to
/// 1e-6) and well above rounding.
constexpr double kParameterTolerance = 1e-8;

VertexFrameSurface sculpt() {
  return solve(loadVertexFrameModel(PDESURF_SOURCE_DIR "/examples/sculpt.json"));
}

TEST(NearestParameters, RecoversThePointsOfThePatchAndPointsAboveThem) {
  const VertexFrameSurface s = sculpt();
  for (std::size_t k = 0; k < s.patches.size(); ++k)
    for (const auto [u, v] : {std::array{0.3, 0.6}, std::array{0.0, 0.9}, std::array{0.77, 0.12}}) {
      const SurfacePoint at = s.patches[k].evaluate(u, v);
      const Vec3 normal = at.du.cross(at.dv).normalized();
      // On the surface, and a little above it (the nearest point is the foot of the normal).
      for (const double lift : {0.0, 1e-3}) {
        const auto [nu, nv] = nearestParameters(s.patches[k], at.p + lift * normal);
        EXPECT_NEAR(nu, u, kParameterTolerance) << "patch " << k << " lift " << lift;
        EXPECT_NEAR(nv, v, kParameterTolerance) << "patch " << k << " lift " << lift;
      }
    }
}

TEST(NearestParameters, APointBeyondASideLandsOnTheSide) {
  const VertexFrameSurface s = sculpt();
  const VertexFramePatch& p = s.patches[0];
  // Beyond the side u = 1, straight out along the surface's u direction there.
  const SurfacePoint edge = p.evaluate(1.0, 0.4);
  const auto [u, v] = nearestParameters(p, edge.p + 0.2 * edge.du.normalized());
  EXPECT_EQ(u, 1.0);
  EXPECT_GT(v, 0.0);
  EXPECT_LT(v, 1.0);
}

}  // namespace
}  // namespace pdesurf
