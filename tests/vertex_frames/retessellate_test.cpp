// Re-tessellation (Tessellator): the same mesh, bit for bit, as a fresh tessellate(), while
// only positions and normals are rewritten when the topology and resolution stay the same.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "pdesurf/error.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

using testing::latticeModel;
using testing::LatticeOptions;

/// Bit-for-bit equality of every buffer (memcmp, so that -0.0 ≠ 0.0 and NaNs compare too).
template <class T>
bool sameBits(const MeshBuffer<T>& a, const MeshBuffer<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectIdentical(const Mesh& got, const Mesh& want, const std::string& what) {
  EXPECT_TRUE(sameBits(got.positions, want.positions)) << what;
  EXPECT_TRUE(sameBits(got.normals, want.normals)) << what;
  EXPECT_TRUE(sameBits(got.indices, want.indices)) << what;
  EXPECT_TRUE(sameBits(got.patchIds, want.patchIds)) << what;
}

/// A torus of randomly oriented frames with forces (one over a whole patch, whose derivatives
/// reach the patch's border), a pole cap and a pillow: every kind of boundary the layout has.
std::vector<VertexFrameModel> models(std::mt19937& rng) {
  LatticeOptions o;
  o.rows = 3;
  o.cols = 4;
  o.closedU = o.closedV = true;
  o.randomOrientation = true;
  o.noise = 0.1;
  VertexFrameModel torus = latticeModel(o, rng);
  torus.frames[1].forces.push_back({Vec3(1, 0, 3), Region{}});
  torus.frames[5].forces.push_back({Vec3(0, 2, 4), Region{0.1, 0.6, 0.3, 0.9}});
  return {torus, testing::poleModel(5, true, rng), testing::pillowModel()};
}

/// The model after a drag: every vertex moved, a1 and a2 changed, forces changed.
VertexFrameModel edited(VertexFrameModel m, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-0.05, 0.05);
  for (Vec3& v : m.vertices) v += Vec3(unit(rng), unit(rng), unit(rng));
  m.frames[0].a1 = Vec3(2.0, 1.0, 0.5);
  m.frames[0].a2 = Vec3(0.5, 1.5, 1.0);
  for (Frame& f : m.frames)
    for (FrameForce& force : f.forces) force.f0 *= -1.5;
  m.frames.back().forces.push_back({Vec3(0, 0, 2), Region{0.0, 0.5, 0.25, 1.0}});
  return m;
}

TEST(Tessellator, IsBitIdenticalToAFreshTessellationAcrossEditsAndLayouts) {
  std::mt19937 rng(31);
  Tessellator tessellator;
  for (const VertexFrameModel& m : models(rng)) {
    const auto topology = std::make_shared<const FrameTopology>(buildTopology(m));
    const VertexFrameSurface first = solve(m, topology);
    const VertexFrameSurface second = solve(edited(m, rng), topology);  // same topology
    ASSERT_FALSE(sameBits(tessellate(first, {9}).positions, tessellate(second, {9}).positions));
    ASSERT_FALSE(sameBits(tessellate(first, {9}).normals, tessellate(second, {9}).normals));
    for (std::uint32_t res : {2u, 3u, 5u, 9u, 17u, 20u, 33u}) {
      const std::string at = "resolution " + std::to_string(res);
      expectIdentical(tessellator.tessellate(first, {res}), tessellate(first, {res}), at);
      const std::uint64_t layout = tessellator.layoutVersion();
      // Only positions and normals change; the result is still a fresh tessellation's.
      expectIdentical(tessellator.tessellate(second, {res}), tessellate(second, {res}),
                      at + ", after an edit");
      expectIdentical(tessellator.tessellate(first, {res}), tessellate(first, {res}),
                      at + ", edited back");
      EXPECT_EQ(tessellator.layoutVersion(), layout) << at;
    }
  }
}

TEST(Tessellator, LaysOutAfreshWhenTheTopologyOrResolutionChangesAndBack) {
  std::mt19937 rng(32);
  const std::vector<VertexFrameModel> ms = models(rng);
  const VertexFrameSurface torus = solve(ms[0]), pole = solve(ms[1]);
  Tessellator tessellator;
  std::uint64_t layout = tessellator.layoutVersion();
  auto check = [&](const VertexFrameSurface& s, std::uint32_t res, bool newLayout) {
    const std::string at = "resolution " + std::to_string(res);
    expectIdentical(tessellator.tessellate(s, {res}), tessellate(s, {res}), at);
    EXPECT_EQ(tessellator.layoutVersion() != layout, newLayout) << at;
    layout = tessellator.layoutVersion();
  };
  check(torus, 9, true);
  check(torus, 9, false);
  check(torus, 12, true);  // another resolution
  check(pole, 12, true);   // another topology, same resolution
  check(pole, 12, false);
  check(torus, 12, true);  // and back
  check(torus, 9, true);
  // A topology rebuilt for the same model is another object: laid out again, same mesh.
  const VertexFrameSurface rebuilt = solve(ms[0]);
  check(rebuilt, 9, true);
  EXPECT_EQ(tessellator.mesh().indices, tessellate(torus, {9}).indices);
}

TEST(Tessellator, RecoversAfterRefusingAMeshBeyond32BitIndices) {
  std::mt19937 rng(33);
  LatticeOptions o;
  o.rows = 15;
  o.cols = 20;  // 300 frames × 4095² inner points > 2³² vertices
  const VertexFrameSurface s = solve(latticeModel(o, rng));
  Tessellator tessellator;
  tessellator.tessellate(s, {5});
  EXPECT_THROW(tessellator.tessellate(s, {4097}), InvalidArgument);
  expectIdentical(tessellator.tessellate(s, {5}), tessellate(s, {5}), "after the refusal");
}

TEST(Tessellator, MovedFromTessellatorStillWorks) {
  std::mt19937 rng(34);
  const VertexFrameSurface s = solve(models(rng)[0]);
  Tessellator a;
  a.tessellate(s, {6});
  Tessellator b = std::move(a);
  expectIdentical(b.tessellate(s, {6}), tessellate(s, {6}), "moved to");
  expectIdentical(a.tessellate(s, {7}), tessellate(s, {7}), "moved from");  // NOLINT
}

}  // namespace
}  // namespace pdesurf
