// Analytic curvature (analysis.hpp): the closed forms of a Monge patch z = f(u, v), with and
// without a sculpting force, and the per-vertex values of a tessellated model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

/// The formulas are evaluated in double from exact derivatives: agreement to rounding,
/// a few ulps of the values' size; 1e-10 relative leaves ample headroom.
constexpr double kCurvatureTol = 1e-10;
/// The studio's values are float32: 1e-6 relative covers that rounding.
constexpr double kFloatTol = 1e-6;

/// H (the studio's sign: −classical for the normal +z) and K of z = f(u, v) from f's
/// derivatives (the Monge patch: do Carmo §3.3, Ex. 5).
Curvature monge(double fu, double fv, double fuu, double fuv, double fvv) {
  const double w = 1.0 + fu * fu + fv * fv;
  const double h =
      ((1 + fv * fv) * fuu - 2 * fu * fv * fuv + (1 + fu * fu) * fvv) / (2 * std::pow(w, 1.5));
  return {-h, (fuu * fvv - fuv * fuv) / (w * w)};
}

/// The plane S = (u, v, 0): the start of every Monge patch below.
VertexFramePatch planePatch() {
  VertexFramePatch patch;
  patch.c.fill(Vec3::Zero());
  patch.c[1] = Vec3(1, 0, 0);
  patch.c[4] = Vec3(0, 1, 0);
  return patch;
}

TEST(Curvature, MongePatchMatchesTheClosedForm) {
  // S = (u, v, a u² + b v² + c uv + d u²v + e uv² + g u³): every polynomial term of a patch.
  const double a = 0.7, b = -0.4, c = 0.3, d = 0.2, e = -0.5, g = 0.6;
  VertexFramePatch patch = planePatch();
  patch.c[2] = Vec3(0, 0, a);
  patch.c[5] = Vec3(0, 0, b);
  patch.c[7] = Vec3(0, 0, c);
  patch.c[8] = Vec3(0, 0, d);
  patch.c[9] = Vec3(0, 0, e);
  patch.c[3] = Vec3(0, 0, g);
  for (double u : {0.0, 0.25, 0.6, 1.0})
    for (double v : {0.0, 0.4, 0.9}) {
      const Curvature want =
          monge(2 * a * u + c * v + 2 * d * u * v + e * v * v + 3 * g * u * u,
                2 * b * v + c * u + d * u * u + 2 * e * u * v, 2 * a + 2 * d * v + 6 * g * u,
                c + 2 * d * u + 2 * e * v, 2 * b + 2 * e * u);
      const Curvature got = patchCurvature(patch, u, v, Vec3(0, 0, 1));
      EXPECT_NEAR(got.mean, want.mean, kCurvatureTol * (1 + std::abs(want.mean))) << u << " " << v;
      EXPECT_NEAR(got.gaussian, want.gaussian, kCurvatureTol * (1 + std::abs(want.gaussian)));
      // The normal's side flips H, never K.
      const Curvature flipped = patchCurvature(patch, u, v, Vec3(0, 0, -1));
      EXPECT_NEAR(flipped.mean, -got.mean, kCurvatureTol * (1 + std::abs(want.mean)));
      EXPECT_NEAR(flipped.gaussian, got.gaussian, kCurvatureTol * (1 + std::abs(want.gaussian)));
    }
  // A bowl z = (u² + v²)/(2R) at its bottom, normal up (toward its centre of curvature):
  // H = −1/R in the studio's sign (a sphere seen from outside is +1/R), K = 1/R².
  const double r = 2.5;
  patch = planePatch();
  patch.c[2] = patch.c[5] = Vec3(0, 0, 1 / (2 * r));
  const Curvature bowl = patchCurvature(patch, 0, 0, Vec3(0, 0, 1));
  EXPECT_NEAR(bowl.mean, -1 / r, kCurvatureTol);
  EXPECT_NEAR(bowl.gaussian, 1 / (r * r), kCurvatureTol);
}

TEST(Curvature, ASculptingForceAddsItsSineToTheClosedForm) {
  // S = (u, v, k sin(π(u−u0)/Lu) sin(π(v−v0)/Lv)) inside the region, a plane outside.
  const double k = 0.35, u0 = 0.2, u1 = 0.8, v0 = 0.1, v1 = 0.7;
  VertexFramePatch patch = planePatch();
  patch.forces.push_back({Vec3(0, 0, k), Region{u0, u1, v0, v1}});
  const double wu = std::numbers::pi / (u1 - u0), wv = std::numbers::pi / (v1 - v0);
  for (double u : {0.3, 0.5, 0.75})
    for (double v : {0.2, 0.45, 0.6}) {
      const double su = std::sin(wu * (u - u0)), sv = std::sin(wv * (v - v0));
      const double cu = std::cos(wu * (u - u0)), cv = std::cos(wv * (v - v0));
      const Curvature want = monge(k * wu * cu * sv, k * wv * su * cv, -k * wu * wu * su * sv,
                                   k * wu * wv * cu * cv, -k * wv * wv * su * sv);
      const Curvature got = patchCurvature(patch, u, v, Vec3(0, 0, 1));
      EXPECT_NEAR(got.mean, want.mean, kCurvatureTol * (1 + std::abs(want.mean))) << u << " " << v;
      EXPECT_NEAR(got.gaussian, want.gaussian, kCurvatureTol * (1 + std::abs(want.gaussian)));
    }
  const Curvature outside = patchCurvature(patch, 0.1, 0.9, Vec3(0, 0, 1));
  EXPECT_EQ(outside.mean, 0.0);
  EXPECT_EQ(outside.gaussian, 0.0);
}

TEST(Curvature, EveryMeshVertexTakesItsPatchValue) {
  std::mt19937 rng(7);
  testing::LatticeOptions o;
  o.rows = 2;
  o.cols = 3;
  o.noise = 0.3;
  o.randomParameters = true;
  o.randomOrientation = true;  // normals against S_u × S_v on some patches
  VertexFrameModel model = testing::latticeModel(o, rng);
  model.frames[2].forces.push_back({Vec3(1, -2, 5), Region{0.1, 0.6, 0.3, 0.9}});
  const VertexFrameSurface surface = solve(model);
  const std::uint32_t n = 9;
  const Mesh mesh = tessellate(surface, {n});
  const std::vector<float> values = meshCurvatures(surface, mesh, n);
  ASSERT_EQ(values.size(), 2 * mesh.vertexCount());
  // A sample inside a patch is one mesh vertex of that patch alone: its value is the
  // patch's at that sample (for the mesh's normal there).
  std::size_t checked = 0;
  for (std::size_t k = 0; k < surface.patches.size(); ++k)
    for (std::uint32_t j = 1; j + 1 < n; ++j)
      for (std::uint32_t i = 1; i + 1 < n; ++i) {
        const double u = double(i) / (n - 1), v = double(j) / (n - 1);
        const Vec3 p = surface.patches[k].position(u, v);
        std::size_t nearest = 0;
        double best = INFINITY;
        for (std::size_t q = 0; q < mesh.vertexCount(); ++q) {
          const double dist =
              (Vec3(mesh.positions[3 * q], mesh.positions[3 * q + 1], mesh.positions[3 * q + 2]) -
               p)
                  .squaredNorm();
          if (dist < best) best = dist, nearest = q;
        }
        const Vec3 normal(mesh.normals[3 * nearest], mesh.normals[3 * nearest + 1],
                          mesh.normals[3 * nearest + 2]);
        const Curvature want = patchCurvature(surface.patches[k], u, v, normal);
        EXPECT_NEAR(values[2 * nearest], want.mean, kFloatTol * (1 + std::abs(want.mean)));
        EXPECT_NEAR(values[2 * nearest + 1], want.gaussian,
                    kFloatTol * (1 + std::abs(want.gaussian)));
        ++checked;
      }
  EXPECT_EQ(checked, surface.patches.size() * (n - 2) * (n - 2));
}

}  // namespace
}  // namespace pdesurf
