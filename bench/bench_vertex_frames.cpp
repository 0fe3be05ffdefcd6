// Benchmarks of the vertex-frame engine: solving large models and tessellating them.
// Results and the command that produced them: docs/performance.md. Tessellation runs on
// every core (oneTBB), so its rows are timed by the wall clock (UseRealTime), and so are
// their single-threaded baselines.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <random>

#include "pdesurf/vertex_frames.hpp"

namespace {

using namespace pdesurf;

/// A wavy sheet of side × side frames over a shared lattice, frames in random orientations,
/// a force on every tenth frame: what a large, real model exercises.
VertexFrameModel sheet(int side) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> rot(0, 3), coin(0, 1);
  const int n = 2 * side + 1;
  VertexFrameModel m;
  m.vertices.reserve(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.vertices.push_back({0.5 * i, 0.5 * j, 0.3 * std::sin(0.7 * i) * std::cos(0.5 * j)});
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * n + i); };
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side; ++c) {
      const int i = 2 * c, j = 2 * r;
      const std::array<std::uint32_t, 8> ring = {
          at(i, j),         at(i + 1, j),     at(i + 2, j), at(i + 2, j + 1),
          at(i + 2, j + 2), at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)};
      const int turn = rot(rng);
      const bool mirror = coin(rng) == 1;
      Frame f;
      for (int s = 0; s < 8; ++s) f.vertices[s] = ring[((mirror ? (8 - s) % 8 : s) + 2 * turn) % 8];
      if ((r * side + c) % 10 == 0) f.forces.push_back({Vec3(0, 0, 1), Region{0.2, 0.8, 0.2, 0.8}});
      m.frames.push_back(f);
    }
  return m;
}

int sideFor(std::int64_t frames) {
  return static_cast<int>(std::lround(std::sqrt(double(frames))));
}

/// The whole solve: topology (strips, edges, orientation) and every patch's coefficients.
void BM_Solve(benchmark::State& state) {
  const VertexFrameModel m = sheet(sideFor(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(solve(m));
  state.counters["frames"] = static_cast<double>(m.frames.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.frames.size()));
}
BENCHMARK(BM_Solve)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

/// Re-solve with a known topology: the studio's path while a vertex is dragged.
void BM_SolveKnownTopology(benchmark::State& state) {
  const VertexFrameModel m = sheet(sideFor(state.range(0)));
  const auto topo = std::make_shared<const FrameTopology>(buildTopology(m));
  for (auto _ : state) benchmark::DoNotOptimize(solve(m, topo));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.frames.size()));
}
BENCHMARK(BM_SolveKnownTopology)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

/// The tessellation rows' resolutions N (263k, 1.05 M and 4.2 M vertices), timed by the wall
/// clock (the tessellation runs on several threads).
void meshSizes(benchmark::internal::Benchmark* b) {
  b->Arg(17)->Arg(33)->Arg(65)->UseRealTime()->Unit(benchmark::kMillisecond);
}

/// The 1,024-frame sheet the tessellation rows use, solved.
const VertexFrameSurface& tessellationSheet() {
  static const VertexFrameSurface s = solve(sheet(32));
  return s;
}

/// Tessellation with normals; items = vertices. Fresh: a new Mesh per iteration, allocated,
/// written and freed, as `pdesurf build` pays it (its large blocks come from the cache of
/// freed blocks, include/pdesurf/mesh.hpp, as every tessellation but a process's first
/// does); cold: the same with that cache emptied before each iteration (outside the timing),
/// as a process's first tessellation pays it; otherwise into a mesh whose buffers are reused
/// (the arithmetic and the stores alone).
enum class Buffers { Fresh, Cold, Reused };
void runTessellate(benchmark::State& state, const VertexFrameSurface& s, std::uint32_t res,
                   Buffers buffers) {
  Mesh reused;
  std::size_t vertices = 0;
  const bool fresh = buffers != Buffers::Reused;
  for (auto _ : state) {
    if (buffers == Buffers::Cold) {
      state.PauseTiming();
      releaseMeshMemory();
      state.ResumeTiming();
    }
    if (fresh) {
      const Mesh mesh = tessellate(s, {res});
      benchmark::DoNotOptimize(mesh.positions.data());
      benchmark::ClobberMemory();
      vertices = mesh.vertexCount();
    } else {
      tessellate(s, {res}, reused);
      benchmark::DoNotOptimize(reused.positions.data());
      benchmark::ClobberMemory();
      vertices = reused.vertexCount();
    }
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(vertices));
}

/// Re-tessellation on an unchanged topology and resolution (a studio drag): a Tessellator
/// alternates between two solutions of a sheet on one topology, the second with every
/// vertex moved, so each call rewrites all positions and normals; items = vertices.
void runRetessellate(benchmark::State& state, int side, std::uint32_t res) {
  VertexFrameModel moved = sheet(side);
  const auto topology = std::make_shared<const FrameTopology>(buildTopology(moved));
  const VertexFrameSurface s0 = solve(moved, topology);
  for (Vec3& v : moved.vertices) v.z() += 0.05 * std::cos(3.0 * v.x());
  const VertexFrameSurface s1 = solve(moved, topology);
  Tessellator tessellator;
  tessellator.tessellate(s1, {res});  // lays the mesh out
  bool second = false;
  for (auto _ : state) {
    const Mesh& mesh = tessellator.tessellate(second ? s1 : s0, {res});
    second = !second;
    benchmark::DoNotOptimize(mesh.positions.data());
    benchmark::ClobberMemory();
  }
  const std::size_t nv = tessellator.mesh().vertexCount();
  state.counters["vertices"] = static_cast<double>(nv);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(nv));
}

/// The 1,024-frame sheet tessellated at N = Arg:
/// - BM_Tessellate: afresh into a new Mesh (allocation, page faults and freeing included);
/// - BM_TessellateCold: the same, each mesh on memory new to the process (the first
///   tessellation's cost);
/// - BM_TessellateReused: into a Mesh whose buffers are reused (already mapped: no
///   allocation, no faults).
const bool kTessellateRows = [] {
  for (const auto& [name, buffers] :
       {std::pair{"BM_Tessellate", Buffers::Fresh}, std::pair{"BM_TessellateCold", Buffers::Cold},
        std::pair{"BM_TessellateReused", Buffers::Reused}})
    benchmark::RegisterBenchmark(name, [buffers = buffers](benchmark::State& state) {
      runTessellate(state, tessellationSheet(), static_cast<std::uint32_t>(state.range(0)),
                    buffers);
    })->Apply(meshSizes);
  return true;
}();

/// The scaling rows' repetitions also report their fastest: on a shared VM other guests'
/// work only ever adds time, so the minimum is the least disturbed figure.
void scalingRows(benchmark::internal::Benchmark* b) {
  b->Args({33, 1})->Args({33, 2})->Args({65, 1})->Args({65, 2})->UseRealTime();
  b->Unit(benchmark::kMillisecond)->ComputeStatistics("min", [](const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
  });
}

/// Fresh tessellation at N = Arg 0 on at most Arg 1 threads (oneTBB): the scaling table.
void BM_TessellateThreads(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(state.range(1)));
  runTessellate(state, tessellationSheet(), static_cast<std::uint32_t>(state.range(0)),
                Buffers::Fresh);
}
BENCHMARK(BM_TessellateThreads)->Apply(scalingRows);

/// The 1,024-frame sheet re-tessellated at N = Arg.
void BM_Retessellate(benchmark::State& state) {
  runRetessellate(state, 32, static_cast<std::uint32_t>(state.range(0)));
}
BENCHMARK(BM_Retessellate)->Apply(meshSizes);

/// The computation alone, on one thread: a sheet small enough (9 frames at N = 33, 4 at N = 65:
/// under 1 MB of mesh) that its mesh stays in this core's L2 between calls, so that no time goes to
/// memory traffic. Args: frames per side, N. Items = vertices.
void BM_TessellateInCache(benchmark::State& state) {
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const VertexFrameSurface s = solve(sheet(static_cast<int>(state.range(0))));
  runTessellate(state, s, static_cast<std::uint32_t>(state.range(1)), Buffers::Reused);
}
BENCHMARK(BM_TessellateInCache)
    ->Args({3, 33})
    ->Args({2, 65})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

/// Re-tessellation of that small sheet.
void BM_RetessellateInCache(benchmark::State& state) {
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  runRetessellate(state, static_cast<int>(state.range(0)),
                  static_cast<std::uint32_t>(state.range(1)));
}
BENCHMARK(BM_RetessellateInCache)
    ->Args({3, 33})
    ->Args({2, 65})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

/// The baselines' writing: vertices [v0, v1) (position and normal, 6 floats each) and
/// triangles [t0, t1) (indices and patch ids), into the mesh's existing buffers. Compiled
/// for each SIMD level and run at the widest the CPU has, as the tessellation's kernels are.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void writeMeshRange(Mesh& mesh, std::size_t v0, std::size_t v1, std::size_t t0, std::size_t t1) {
  float* p = mesh.positions.data();
  float* n = mesh.normals.data();
  for (std::size_t v = v0; v < v1; ++v) {
    const auto x = static_cast<float>(v);
    p[3 * v] = x;
    p[3 * v + 1] = x + 1.0f;
    p[3 * v + 2] = x + 2.0f;
    n[3 * v] = 0.0f;
    n[3 * v + 1] = 0.0f;
    n[3 * v + 2] = 1.0f;
  }
  std::uint32_t* idx = mesh.indices.data();
  for (std::size_t t = 3 * t0; t < 3 * t1; ++t) idx[t] = static_cast<std::uint32_t>(t);
  std::uint32_t* pid = mesh.patchIds.data();
  for (std::size_t t = t0; t < t1; ++t) pid[t] = static_cast<std::uint32_t>(t >> 9);
}

/// All nv vertices, and all triangles when `triangles`.
void writeMeshData(Mesh& mesh, std::size_t nv, bool triangles) {
  writeMeshRange(mesh, 0, nv, 0, triangles ? mesh.patchIds.size() : 0);
}

/// A baseline: the writing alone, `write(mesh, vertices)`, into reused buffers sized as the
/// tessellation's mesh at N = Arg 0.
template <class Write>
void writeBaseline(benchmark::State& state, Write&& write) {
  Mesh mesh;
  tessellate(tessellationSheet(), {static_cast<std::uint32_t>(state.range(0))}, mesh);
  const std::size_t nv = mesh.vertexCount();
  for (auto _ : state) {
    write(mesh, nv);
    benchmark::DoNotOptimize(mesh.positions.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = static_cast<double>(nv);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(nv));
}

/// Baseline for a fresh tessellation: write the same number of vertices (position and
/// normal, 6 floats each), the same triangle indices and the same patch ids, computing nothing.
void BM_WriteVerticesBaseline(benchmark::State& state) {
  writeBaseline(state, [](Mesh& mesh, std::size_t nv) { writeMeshData(mesh, nv, true); });
}
BENCHMARK(BM_WriteVerticesBaseline)->Apply(meshSizes);

/// The same writing (vertices, indices, patch ids) split over at most Arg 1 threads (oneTBB,
/// contiguous chunks, as the tessellation's patches are): the most that more cores can gain
/// when the mesh is too big for the caches and the stores go to memory. Args: N, threads.
void BM_WriteVerticesBaselineThreads(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(state.range(1)));
  constexpr std::size_t kChunks = 64;  // many more than cores, few enough to be noise
  writeBaseline(state, [](Mesh& mesh, std::size_t nv) {
    const std::size_t nt = mesh.patchIds.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kChunks, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t c = r.begin(); c != r.end(); ++c)
                          writeMeshRange(mesh, nv * c / kChunks, nv * (c + 1) / kChunks,
                                         nt * c / kChunks, nt * (c + 1) / kChunks);
                      });
  });
}
BENCHMARK(BM_WriteVerticesBaselineThreads)->Apply(scalingRows);

/// The baseline in its own words, "writing the same number of vertices": positions
/// and normals only (6 floats per vertex), the comparison for re-tessellation.
void BM_WriteVertexDataBaseline(benchmark::State& state) {
  writeBaseline(state, [](Mesh& mesh, std::size_t nv) { writeMeshData(mesh, nv, false); });
}
BENCHMARK(BM_WriteVertexDataBaseline)->Apply(meshSizes);

#if defined(__SSE2__)
/// The write baseline's data with non-temporal (streaming) stores, which write whole cache
/// lines without reading them first: whether the tessellation's stores should stream. Same
/// values as writeMeshRange, four at a time (the mesh's large buffers are page-aligned).
void streamMeshData(Mesh& mesh, std::size_t nv) {
  float* p = mesh.positions.data();
  float* n = mesh.normals.data();
  const std::size_t floats = 3 * nv / 12 * 12;  // whole groups of four vertices
  for (std::size_t f = 0; f < floats; f += 12) {
    const auto v = static_cast<float>(f / 3);
    _mm_stream_ps(p + f, _mm_setr_ps(v, v + 1, v + 2, v + 1));
    _mm_stream_ps(p + f + 4, _mm_setr_ps(v + 2, v + 3, v + 2, v + 3));
    _mm_stream_ps(p + f + 8, _mm_setr_ps(v + 4, v + 3, v + 4, v + 5));
    _mm_stream_ps(n + f, _mm_setr_ps(0, 0, 1, 0));
    _mm_stream_ps(n + f + 4, _mm_setr_ps(0, 1, 0, 0));
    _mm_stream_ps(n + f + 8, _mm_setr_ps(1, 0, 0, 1));
  }
  auto* idx = reinterpret_cast<__m128i*>(mesh.indices.data());
  for (std::size_t t = 0; t < mesh.indices.size() / 4; ++t) {
    const auto i = static_cast<int>(4 * t);
    _mm_stream_si128(idx + t, _mm_setr_epi32(i, i + 1, i + 2, i + 3));
  }
  auto* pid = reinterpret_cast<__m128i*>(mesh.patchIds.data());
  for (std::size_t t = 0; t < mesh.patchIds.size() / 4; ++t)
    _mm_stream_si128(pid + t, _mm_set1_epi32(static_cast<int>((4 * t) >> 9)));
  _mm_sfence();
}

/// BM_WriteVerticesBaseline with streaming stores (the few values after the last whole
/// group of four are left out: under 16 bytes a buffer).
void BM_WriteVerticesStreaming(benchmark::State& state) { writeBaseline(state, streamMeshData); }
BENCHMARK(BM_WriteVerticesStreaming)->Apply(meshSizes);
#endif

}  // namespace

BENCHMARK_MAIN();
