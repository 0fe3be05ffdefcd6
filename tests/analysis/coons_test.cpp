// Coons baselines (src/analysis/coons.cpp): boundary interpolation, bilinear and bicubic
// precision, the seed's tangent functions, and `pdesurf coons`.
#include <gtest/gtest.h>

#include <random>

#include "pdesurf/coons.hpp"
#include "pdesurf/mesh_io.hpp"
#include "support/cli_run.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

/// Boundary interpolation is exact up to rounding in the Hermite sums (values of size ~1).
constexpr double kCoonsExact = 1e-12;
/// Reproduction with tangents whose along-boundary derivatives come from central
/// differences (step kCoonsTangentStep): the twist error is h² |S'''| ~ 1e-10, plus
/// rounding ε/h ~ 1e-11.
constexpr double kCoonsFiniteDifference = 1e-8;

/// A sculpted frame with a curved boundary: the patch of the seed's Fig. 8 setting.
/// The seed's w = 0 (Eigen vectors are not zero by default).
std::array<Vec3, 4> zeroWeights() {
  std::array<Vec3, 4> w;
  w.fill(Vec3::Zero());
  return w;
}

VertexFramePatch curvedPatch(bool withForce) {
  VertexFrameModel m;
  m.vertices = {{0, 0, 0},   {0.5, -0.1, 0.2}, {1, 0, 0},   {1.1, 0.5, 0.3},
                {1, 1, 0.1}, {0.5, 1.2, -0.1}, {0, 1, 0.2}, {-0.1, 0.5, 0}};
  Frame f;
  f.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
  f.a1 = Vec3(1, 2, 0.5);
  if (withForce) f.forces.push_back({Vec3(3, 1, 2), Region{0.25, 0.75, 0.25, 0.75}});
  m.frames = {f};
  return solve(m).patches[0];
}

TEST(Coons, BothKindsInterpolateTheFourBoundaries) {
  const VertexFramePatch patch = curvedPatch(true);
  const CoonsBoundary b = boundaryOf(patch);
  const std::array<Vec3, 4> w = {Vec3(100, 0, 0), Vec3(-100, 0, 0), Vec3(100, 0, 0),
                                 Vec3(-100, 0, 0)};
  for (const CoonsPatch& c :
       {CoonsPatch::bilinear(b), CoonsPatch::bicubic(b, seedTangents(b, w))}) {
    for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      EXPECT_LT((c.evaluate(t, 0).p - patch.position(t, 0)).norm(), kCoonsExact);
      EXPECT_LT((c.evaluate(t, 1).p - patch.position(t, 1)).norm(), kCoonsExact);
      EXPECT_LT((c.evaluate(0, t).p - patch.position(0, t)).norm(), kCoonsExact);
      EXPECT_LT((c.evaluate(1, t).p - patch.position(1, t)).norm(), kCoonsExact);
    }
  }
}

TEST(Coons, BilinearReproducesABilinearSurface) {
  // A hyperbolic paraboloid: its boundaries are lines and the bilinear Coons patch is it.
  const Vec3 p00(0, 0, 0), p10(2, 0, 1), p01(0, 1, -1), p11(2, 1, 3);
  auto line = [](Vec3 a, Vec3 b) {
    return CoonsCurve{[a, b](double t) -> Vec3 { return (1 - t) * a + t * b; },
                      [a, b](double) -> Vec3 { return b - a; }};
  };
  const CoonsPatch c =
      CoonsPatch::bilinear({line(p00, p10), line(p01, p11), line(p00, p01), line(p10, p11)});
  for (double u : {0.2, 0.6})
    for (double v : {0.3, 0.9}) {
      const Vec3 exact =
          (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11;
      const SurfacePoint s = c.evaluate(u, v);
      EXPECT_LT((s.p - exact).norm(), kCoonsExact);
      const Vec3 du = (1 - v) * (p10 - p00) + v * (p11 - p01);
      const Vec3 dv = (1 - u) * (p01 - p00) + u * (p11 - p10);
      EXPECT_LT((s.du - du).norm(), kCoonsExact);
      EXPECT_LT((s.dv - dv).norm(), kCoonsExact);
    }
}

TEST(Coons, BicubicWithThePatchsOwnTangentsReproducesAForceFreePatch) {
  // A force-free vertex-frame patch is a bicubic polynomial (monomials up to u³, v³): the
  // Boolean sum of cubic Hermite lofts has bicubic precision, so it comes back.
  const VertexFramePatch patch = curvedPatch(false);
  const CoonsPatch c = CoonsPatch::bicubic(boundaryOf(patch), patchTangents(patch));
  double worst = 0;
  for (double u = 0; u <= 1.0001; u += 0.125)
    for (double v = 0; v <= 1.0001; v += 0.125) {
      const SurfacePoint s = c.evaluate(u, v), e = patch.evaluate(u, v);
      worst = std::max({worst, (s.p - e.p).norm(), (s.du - e.du).norm(), (s.dv - e.dv).norm()});
    }
  EXPECT_LT(worst, kCoonsFiniteDifference);
  // With a force the patch is no longer bicubic: the same construction misses it inside.
  const VertexFramePatch forced = curvedPatch(true);
  const CoonsPatch cf = CoonsPatch::bicubic(boundaryOf(forced), patchTangents(forced));
  EXPECT_GT((cf.evaluate(0.5, 0.5).p - forced.position(0.5, 0.5)).norm(), 1e-3);
}

TEST(Coons, SeedTangentsMoveOnlyTheInterior) {
  const VertexFramePatch patch = curvedPatch(false);
  const CoonsBoundary b = boundaryOf(patch);
  const CoonsPatch flat = CoonsPatch::bicubic(b, seedTangents(b, zeroWeights()));
  const CoonsPatch pushed = CoonsPatch::bicubic(
      b, seedTangents(b, {Vec3(100, 0, 0), Vec3(-100, 0, 0), Vec3(100, 0, 0), Vec3(-100, 0, 0)}));
  // The interior moves (along x only: the weights have no y or z), the boundary does not.
  // How much depends on how far the tangents are from what the boundaries imply at the
  // corners: a cubic tangent that agrees there is absorbed by the tensor-product term.
  double most = 0;
  for (double u : {0.25, 0.5, 0.75})
    for (double v : {0.25, 0.5, 0.75}) {
      const Vec3 moved = pushed.evaluate(u, v).p - flat.evaluate(u, v).p;
      most = std::max(most, std::abs(moved.x()));
      EXPECT_LT(std::abs(moved.y()) + std::abs(moved.z()), kCoonsExact);
    }
  EXPECT_GT(most, 0.1);
  for (double t : {0.0, 0.4, 1.0})
    EXPECT_LT((pushed.evaluate(t, 0).p - flat.evaluate(t, 0).p).norm(), kCoonsExact);
}

TEST(Coons, TessellationAndCli) {
  const VertexFramePatch patch = curvedPatch(false);
  const CoonsBoundary b = boundaryOf(patch);
  const Mesh mesh = tessellate(
      {CoonsPatch::bilinear(b), CoonsPatch::bicubic(b, seedTangents(b, zeroWeights()))}, {5});
  EXPECT_EQ(mesh.vertexCount(), 2u * 25u);
  EXPECT_EQ(mesh.triangleCount(), 2u * 32u);
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const Vec3 n(mesh.normals[3 * i], mesh.normals[3 * i + 1], mesh.normals[3 * i + 2]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
  }
  EXPECT_THROW(tessellate({CoonsPatch::bilinear(b)}, {1}), InvalidArgument);

  testing::TempDir work, capture;
  const std::string model = std::string(PDESURF_SOURCE_DIR) + "/examples/sculpt.json";
  auto r = testing::runCli(work, capture,
                           "coons " + testing::shellQuote(model) +
                               " -o c.ply --resolution 9 --tangents 1,0,0,1,0,0,0,0,0,0,0,0");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(readMesh(work.file("c.ply")).vertexCount(), 81u);
  r = testing::runCli(work, capture, "coons " + testing::shellQuote(model) + " -o d.obj --frame 7");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--frame 7: out of range"), std::string::npos) << r.err;
  r = testing::runCli(
      work, capture, "coons " + testing::shellQuote(model) + " -o d.obj --bilinear --own-tangents");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(work.entries(), std::vector<std::string>{"c.ply"});
}

}  // namespace
}  // namespace pdesurf
