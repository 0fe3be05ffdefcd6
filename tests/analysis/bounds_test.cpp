// Surface bounds: no sampled point lies outside, narrow force peaks are found.
#include <gtest/gtest.h>

#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

/// The refinement stops at parameter steps of 1e-12; the extreme it reports is a point of
/// the surface, so a dense sample may exceed it only by rounding (≈ 1e-15 relative).
constexpr double kBoundsTol = 1e-12;

void expectContainsDenseSamples(const VertexFrameSurface& s, const Bounds& b) {
  const int n = 201;
  const double tol = kBoundsTol * (1.0 + b.diagonal());
  for (const VertexFramePatch& patch : s.patches)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 p = patch.position(i / (n - 1.0), j / (n - 1.0));
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(p[c], b.min[c] - tol);
          EXPECT_LE(p[c], b.max[c] + tol);
        }
      }
}

TEST(Bounds, ContainEveryDenseSampleOfRandomModels) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 4; ++trial) {
    testing::LatticeOptions o;
    o.rows = 2;
    o.cols = 3;
    o.noise = 0.3;
    o.randomParameters = true;
    VertexFrameModel m = testing::latticeModel(o, rng);
    m.frames[2].forces.push_back({Vec3(1, -2, 5), Region{0.1, 0.3, 0.6, 0.7}});
    const VertexFrameSurface s = solve(m);
    expectContainsDenseSamples(s, surfaceBounds(s));
  }
}

TEST(Bounds, FindTheApexOfAForceNarrowerThanTheSampling) {
  VertexFrameModel m;
  m.vertices = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 0.5, 0},
                {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}, {0, 0.5, 0}};
  Frame f;
  f.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
  f.forces.push_back({Vec3(0, 0, -1e5), Region{0.33, 0.36, 0.33, 0.36}});
  m.frames = {f};
  const VertexFrameSurface s = solve(m);
  const Bounds b = surfaceBounds(s);
  // A flat patch: the force is the whole shape, its apex is at the region's centre.
  const double apex = s.patches[0].position(0.345, 0.345).z();
  EXPECT_NEAR(b.max.z(), apex, 1e-9 * apex);
  expectContainsDenseSamples(s, b);
}

}  // namespace
}  // namespace pdesurf
