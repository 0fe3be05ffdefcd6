// Tessellation: watertight, consistently oriented meshes whose points lie on the patches.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/mesh_checks.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

using testing::latticeModel;
using testing::LatticeOptions;

TEST(Tessellate, ClosedTorusIsWatertightOrientedAndHasEulerCharacteristicZero) {
  std::mt19937 rng(21);
  for (std::uint32_t res : {2u, 3u, 8u, 17u}) {
    LatticeOptions o;
    o.rows = 3;
    o.cols = 5;
    o.closedU = o.closedV = true;
    o.randomOrientation = true;
    const VertexFrameModel m = latticeModel(o, rng);
    const VertexFrameSurface s = solve(m);
    const Mesh mesh = tessellate(s, {res});
    const auto stats = testing::edgeStats(mesh);
    EXPECT_EQ(stats.boundaryEdges, 0u) << "res " << res;
    EXPECT_EQ(stats.nonManifoldEdges, 0u);
    EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u) << "res " << res;
    const long long chi = static_cast<long long>(mesh.vertexCount()) -
                          static_cast<long long>(stats.edges) +
                          static_cast<long long>(mesh.triangleCount());
    EXPECT_EQ(chi, 0);
    // Corners + inner edge points + inner patch points, each once.
    const std::size_t inner = res - 2;
    EXPECT_EQ(mesh.vertexCount(), 3u * 5 + (2u * 3 * 5) * inner + 15u * inner * inner);
  }
}

TEST(Tessellate, NormalsAreUnitAndFaceTheWayTheTrianglesDo) {
  std::mt19937 rng(22);
  LatticeOptions o;
  o.rows = 3;
  o.cols = 6;
  o.closedU = o.closedV = true;
  o.randomOrientation = true;  // mirrored frames must be flipped to one orientation
  const VertexFrameModel m = latticeModel(o, rng);
  const Mesh mesh = tessellate(solve(m), {9});
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const Eigen::Vector3f n(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
    EXPECT_NEAR(n.norm(), 1.0f, 1e-6f);
  }
  // On a smooth surface every corner normal lies within 60° of its triangle's normal.
  EXPECT_GT(testing::minCornerNormalAgreement(mesh), 0.5);
  // And on a torus the normals point away from the core circle (outward), or all inward.
  double outward = 0, inward = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const Eigen::Vector3d p(mesh.positions[3 * v], mesh.positions[3 * v + 1],
                            mesh.positions[3 * v + 2]);
    const Eigen::Vector3d core = 3.0 * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    const Eigen::Vector3d n(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
    ((p - core).dot(n) > 0 ? outward : inward) += 1;
  }
  EXPECT_TRUE(outward == 0 || inward == 0) << outward << " out, " << inward << " in";
}

TEST(Tessellate, PointsLieOnThePatchesAndSharedEdgesAreOneVertex) {
  std::mt19937 rng(23);
  LatticeOptions o;
  o.rows = 2;
  o.cols = 3;
  o.randomOrientation = true;
  o.noise = 0.2;
  VertexFrameModel m = latticeModel(o, rng);
  m.frames[1].forces.push_back({Vec3(0, 0, 4), Region{0.1, 0.8, 0.2, 0.9}});
  const VertexFrameSurface s = solve(m);
  const std::uint32_t n = 7;
  const Mesh mesh = tessellate(s, {n});
  // Every triangle corner of patch k is S_k at one of its grid points (float rounding).
  constexpr double kFloatTol = 1e-6;  // positions are stored as float: 2^-24 relative
  std::map<std::uint32_t, std::vector<Vec3>> grid;
  for (std::uint32_t k = 0; k < m.frames.size(); ++k)
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i)
        grid[k].push_back(s.patches[k].position(i / (n - 1.0), j / (n - 1.0)));
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.indices[3 * t + c];
      const Vec3 p(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
      double best = 1e300;
      for (const Vec3& q : grid[mesh.patchIds[t]]) best = std::min(best, (p - q).norm());
      EXPECT_LT(best, kFloatTol);
    }
  // An open 2×3 grid: its boundary is the outer ring, 2·(2+3)·(n-1) mesh edges.
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.boundaryEdges, 2u * (2 + 3) * (n - 1));
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
}

TEST(Tessellate, PoleCapIsADiskWithOneVertexAtThePole) {
  std::mt19937 rng(24);
  for (int sectors : {3, 5, 8}) {
    const VertexFrameModel m = testing::poleModel(sectors, true, rng);
    const std::uint32_t n = 9;
    const Mesh mesh = tessellate(solve(m), {n});
    const auto stats = testing::edgeStats(mesh);
    EXPECT_EQ(stats.boundaryEdges, static_cast<std::size_t>(sectors) * (n - 1));
    EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
    EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
    const long long chi = static_cast<long long>(mesh.vertexCount()) -
                          static_cast<long long>(stats.edges) +
                          static_cast<long long>(mesh.triangleCount());
    EXPECT_EQ(chi, 1);  // a disk
    // The pole's normal is defined (from just inside the patches) and points up.
    EXPECT_GT(testing::minCornerNormalAgreement(mesh), 0.0);
  }
}

TEST(Tessellate, BranchKeepsTheSharedEdgeAsOneRowOfVertices) {
  std::mt19937 rng(25);
  const VertexFrameModel m = testing::branchModel(rng, true);
  const std::uint32_t n = 5;
  const Mesh mesh = tessellate(solve(m), {n});
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.nonManifoldEdges, n - 1);  // the fin's edge is used by three triangles
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
}

/// Two frames over the same eight vertices, one mirrored: a closed pillow. Both frames
/// share both sides at every corner; no triangle may appear twice.
TEST(Tessellate, PillowOfTwoFramesIsAClosedOrientedSphere) {
  const VertexFrameModel m = testing::pillowModel();
  for (std::uint32_t n : {3u, 4u, 7u, 16u}) {
    const Mesh mesh = tessellate(solve(m), {n});
    const auto stats = testing::edgeStats(mesh);
    EXPECT_EQ(stats.boundaryEdges, 0u) << n;
    EXPECT_EQ(stats.nonManifoldEdges, 0u) << n;
    EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u) << n;
    const long long chi = static_cast<long long>(mesh.vertexCount()) -
                          static_cast<long long>(stats.edges) +
                          static_cast<long long>(mesh.triangleCount());
    EXPECT_EQ(chi, 2) << n;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
      const Eigen::Vector3f nv(mesh.normals[3 * v], mesh.normals[3 * v + 1],
                               mesh.normals[3 * v + 2]);
      EXPECT_NEAR(nv.norm(), 1.0f, 1e-5f) << "vertex " << v << " at resolution " << n;
    }
  }
}

/// A side running a→m→a (a loop) is pinned flat, so its two halves coincide: they are one
/// row of vertices, and no triangle repeats a vertex.
TEST(Tessellate, LoopSideIsFoldedOntoItself) {
  VertexFrameModel m;
  m.vertices = {{0, 0, 0},     {1, 0, 0},        {1.2, 1, 0.3}, {0.6, 1.4, 0.2},
                {0, 1.5, 0.4}, {-0.6, 1.4, 0.2}, {-1.2, 1, 0.3}};
  Frame f;
  f.vertices = {0, 1, 0, 6, 5, 4, 3, 2};  // α = 0→1→0
  m.frames = {f};
  for (std::uint32_t n : {2u, 3u, 6u, 7u}) {
    const Mesh mesh = tessellate(solve(m), {n});
    EXPECT_EQ(testing::duplicatePositions(mesh), 0u) << n;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const std::uint32_t* tri = mesh.indices.data() + 3 * t;
      EXPECT_TRUE(tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]) << n;
    }
    // Every vertex is used by some triangle (no orphans from the folded half).
    std::vector<int> used(mesh.vertexCount(), 0);
    for (std::uint32_t i : mesh.indices) used[i] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << n;
  }
}

TEST(Tessellate, NormalsStayUnitForModelsOfAnyScale) {
  std::mt19937 rng(27);
  LatticeOptions o;
  o.rows = 3;
  o.cols = 4;
  o.closedU = true;
  o.randomOrientation = true;
  VertexFrameModel m = testing::latticeModel(o, rng);
  const Mesh reference = tessellate(solve(m), {6});
  for (double scale : {1e30, 1e-30, 1e150}) {
    VertexFrameModel scaled = m;
    for (Vec3& v : scaled.vertices) v *= scale;
    const Mesh mesh = tessellate(solve(scaled), {6});
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
      EXPECT_NEAR(mesh.normals[i], reference.normals[i], 1e-5f) << "scale " << scale;
  }
}

TEST(Tessellate, RefusesMeshesBeyond32BitIndicesBeforeAllocating) {
  std::mt19937 rng(26);
  LatticeOptions o;
  o.rows = 15;
  o.cols = 20;  // 300 frames × 4095² inner points > 2³² vertices
  const VertexFrameSurface s = solve(latticeModel(o, rng));
  EXPECT_THROW(tessellate(s, {4097}), InvalidArgument);
  EXPECT_NO_THROW(tessellate(s, {5}));
}

}  // namespace
}  // namespace pdesurf
