// The same bytes whatever runs them: tessellation, batched evaluation and slicing give
// bit-identical output for any number of threads (oneTBB) and at every SIMD level the CPU
// has (src/runtime/simd.hpp); mesh buffers (include/pdesurf/mesh.hpp) keep large blocks on
// huge-page boundaries.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "runtime/mesh_buffer.hpp"
#include "runtime/simd.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

using detail::SimdLevel;

template <class V>
bool sameBits(const V& a, const V& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

::testing::AssertionResult identical(const Mesh& got, const Mesh& want) {
  if (!sameBits(got.positions, want.positions)) return ::testing::AssertionFailure() << "positions";
  if (!sameBits(got.normals, want.normals)) return ::testing::AssertionFailure() << "normals";
  if (!sameBits(got.indices, want.indices)) return ::testing::AssertionFailure() << "indices";
  if (!sameBits(got.patchIds, want.patchIds)) return ::testing::AssertionFailure() << "patch ids";
  return ::testing::AssertionSuccess();
}

/// Thread counts tried: one, this machine's, and more threads than cores.
const int kThreadCounts[] = {1, 2, 3, 8};

/// Runs f on `threads` threads at most (oneTBB's limit raised so that more threads than
/// cores really run).
template <class F>
void onThreads(int threads, F&& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  tbb::task_arena(threads).execute(f);
}

/// The SIMD levels this CPU can run, from v2 up.
std::vector<SimdLevel> levels() {
  std::vector<SimdLevel> out;
  for (SimdLevel l : {SimdLevel::kV2, SimdLevel::kV3, SimdLevel::kV4})
    if (static_cast<int>(l) <= static_cast<int>(detail::cpuSimdLevel())) out.push_back(l);
  return out;
}

/// Restores the SIMD level a test changed.
struct SimdLevelGuard {
  SimdLevel saved = detail::simdLevel();
  ~SimdLevelGuard() { detail::setSimdLevel(saved); }
};

/// Many patches (so that the work is split between threads) with forces, random
/// orientations and closed directions; a pole cap and a pillow (repeated ids, collapsed
/// sides).
std::vector<VertexFrameSurface> surfaces() {
  std::mt19937 rng(5);
  testing::LatticeOptions o;
  o.rows = 12;
  o.cols = 14;
  o.closedU = true;
  o.randomOrientation = true;
  o.noise = 0.1;
  VertexFrameModel sheet = testing::latticeModel(o, rng);
  for (std::size_t k = 0; k < sheet.frames.size(); k += 7)
    sheet.frames[k].forces.push_back({Vec3(0.5, -1, 2), Region{0.1, 0.7, 0.2, 0.9}});
  return {solve(sheet), solve(testing::poleModel(7, true, rng)), solve(testing::pillowModel())};
}

TEST(Parallel, TessellationIsTheSameBytesForAnyThreadCountAndSimdLevel) {
  SimdLevelGuard guard;
  for (const VertexFrameSurface& s : surfaces())
    for (std::uint32_t res : {3u, 9u, 33u}) {
      detail::setSimdLevel(SimdLevel::kV2);
      Mesh want;
      onThreads(1, [&] { want = tessellate(s, {res}); });
      ASSERT_GT(want.triangleCount(), 0u);
      for (SimdLevel level : levels()) {
        ASSERT_EQ(detail::setSimdLevel(level), level);
        for (int threads : kThreadCounts) {
          Mesh got;
          onThreads(threads, [&] { got = tessellate(s, {res}); });
          EXPECT_TRUE(identical(got, want))
              << "resolution " << res << ", SIMD level v" << static_cast<int>(level) << ", "
              << threads << " threads";
          // Re-tessellation writes the same values into the kept layout.
          Tessellator tessellator;
          onThreads(threads, [&] {
            tessellator.tessellate(s, {res});
            tessellator.tessellate(s, {res});
          });
          EXPECT_TRUE(identical(tessellator.mesh(), want)) << "re-tessellation, " << threads;
        }
      }
    }
}

TEST(Parallel, BatchedEvaluationIsTheSameBytesForAnyThreadCountAndSimdLevel) {
  SimdLevelGuard guard;
  const VertexFrameSurface s = surfaces()[0];
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> u(20011), v(u.size());  // not a multiple of any block or vector size
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = unit(rng), v[i] = unit(rng);
  const auto fields = [](const PolynomialPatchPoints& p) {
    return std::vector<const std::vector<double>*>{&p.x,  &p.y,  &p.z,  &p.ux, &p.uy, &p.uz,
                                                   &p.vx, &p.vy, &p.vz, &p.nx, &p.ny, &p.nz};
  };
  detail::setSimdLevel(SimdLevel::kV2);
  PolynomialPatchPoints want;
  onThreads(1, [&] { evaluatePolynomial(s.patches[3], u, v, want); });
  for (SimdLevel level : levels()) {
    detail::setSimdLevel(level);
    for (int threads : kThreadCounts) {
      PolynomialPatchPoints got;
      onThreads(threads, [&] { evaluatePolynomial(s.patches[3], u, v, got); });
      for (std::size_t f = 0; f < 12; ++f)
        EXPECT_TRUE(sameBits(*fields(got)[f], *fields(want)[f]))
            << "field " << f << ", SIMD level v" << static_cast<int>(level) << ", " << threads
            << " threads";
    }
  }
}

TEST(Parallel, SlicesAreTheSameForAnyThreadCount) {
  const Mesh mesh = tessellate(surfaces()[0], {17});
  SliceOptions options;
  options.axis = Axis::Z;                    // along the cylinder (z from about 0 to 3)
  options.range = std::make_pair(0.5, 2.5);  // clear of its ragged ends
  options.count = 40;
  options.track = true;
  std::vector<MeshSection> want;
  onThreads(1, [&] { want = sliceMesh(mesh, options); });
  ASSERT_EQ(want.size(), 40u);
  for (int threads : kThreadCounts) {
    std::vector<MeshSection> got;
    onThreads(threads, [&] { got = sliceMesh(mesh, options); });
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].points, want[i].points) << "plane " << i << ", " << threads << " threads";
      EXPECT_EQ(got[i].loops, want[i].loops);
      EXPECT_EQ(got[i].area, want[i].area);
    }
  }
}

TEST(MeshBuffer, LargeBlocksStartOnHugePagesAndKeepTheirValuesWhenTheyGrow) {
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  MeshBuffer<float> big;
  big.resize(detail::kMappedBlockBytes / sizeof(float) + 3);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kHugePage, 0u);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<float>(i % 1000);
  big.resize(3 * big.size());  // moves into a new block
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kHugePage, 0u);
  for (std::size_t i = 0; i < big.size() / 3; ++i)
    ASSERT_EQ(big[i], static_cast<float>(i % 1000)) << "element " << i;
  MeshBuffer<std::uint32_t> small(10, 7u);  // an explicit value is still written
  EXPECT_EQ(small, MeshBuffer<std::uint32_t>(10, 7u));
}

#if defined(__linux__)
TEST(MeshBuffer, AFreedLargeBlockIsReusedForTheNextOfAboutItsSizeAndReleasedOnRequest) {
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  releaseMeshMemory();  // other tests of this process may have left blocks
  ASSERT_EQ(detail::cachedMeshBlockBytes(), 0u);
  const std::size_t floats = 3 * kHugePage / sizeof(float) + 5;  // 3 huge pages and a bit
  const float* first = nullptr;
  {
    MeshBuffer<float> a;
    a.resize(floats);
    first = a.data();
  }
  EXPECT_EQ(detail::cachedMeshBlockBytes(), 4 * kHugePage);  // rounded up to whole pages
  {
    MeshBuffer<float> tooSmall;  // under half the cached block: a block of its own
    tooSmall.resize(kHugePage / sizeof(float));
    EXPECT_NE(tooSmall.data(), first);
    MeshBuffer<float> b;  // 3 huge pages: the cached block, its fourth page unmapped
    b.resize(floats - 1000);
    EXPECT_EQ(b.data(), first);
    EXPECT_EQ(detail::cachedMeshBlockBytes(), 0u);
  }
  EXPECT_EQ(detail::cachedMeshBlockBytes(), 4 * kHugePage);  // 3 + 1
  EXPECT_EQ(releaseMeshMemory(), 4 * kHugePage);
  EXPECT_EQ(detail::cachedMeshBlockBytes(), 0u);
}

TEST(MeshBuffer, TheCacheNeverHoldsMoreThanItsCap) {
  releaseMeshMemory();
  // Blocks of 0.4 of the cap, never written (mapped, not faulted in: no memory is used).
  const std::size_t floats = detail::kBlockCacheBytes / 10 * 4 / sizeof(float);
  for (int k = 0; k < 4; ++k) {
    MeshBuffer<float> block;
    MeshBuffer<float> other;  // two alive at once, so the second cannot reuse the first
    block.reserve(floats);
    other.reserve(floats);
  }
  EXPECT_LE(detail::cachedMeshBlockBytes(), detail::kBlockCacheBytes);
  EXPECT_GT(detail::cachedMeshBlockBytes(), detail::kBlockCacheBytes / 2);  // kept what fits
  releaseMeshMemory();
}
#endif

}  // namespace
}  // namespace pdesurf
