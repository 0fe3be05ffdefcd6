// Benchmarks of the mesh tools: slicing CGAL's elephant (libcgal-demo, through
// scripts/cgal_data), mesh-to-mesh distances with CGAL AABB trees, and the rebuilds.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <stdio.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"

namespace {

using namespace pdesurf;

/// A mesh of CGAL's sample data, extracted by scripts/cgal_data into build/cgal-data (this
/// repository's); throws with the script's message when libcgal-demo is missing.
Mesh cgalMesh(const std::string& name) {
  const std::filesystem::path root = PDESURF_SOURCE_DIR;
  const std::string command = "'" + (root / "scripts/cgal_data").string() + "' " + name;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  char buffer[4096] = {};
  const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, pipe);
  if (::pclose(pipe) != 0 || n == 0) throw std::runtime_error(command + " failed");
  std::string path(buffer, n);
  while (!path.empty() && path.back() == '\n') path.pop_back();
  return readMesh(path);
}

const Mesh& elephant() {
  static const Mesh mesh = cgalMesh("elephant.off");
  return mesh;
}

/// A latitude-longitude sphere of radius r with about 2 n² triangles.
Mesh sphere(int n, double r) {
  Mesh m;
  auto vertex = [&](double x, double y, double z) {
    m.positions.insert(m.positions.end(),
                       {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
  };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = M_PI * i / n - M_PI / 2, a = M_PI * j / n;
      vertex(r * std::cos(phi) * std::cos(a), r * std::cos(phi) * std::sin(a), r * std::sin(phi));
    }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * 2 * n + (j % (2 * n))); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j)
      m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j),
                                         at(i + 1, j + 1), at(i + 1, j)});
  return m;
}

/// The elephant (5558 triangles) cut by 100 planes along z.
void BM_SliceElephant(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(state.range(1)));
  const Mesh& mesh = elephant();
  SliceOptions options;
  options.count = static_cast<std::uint32_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(sliceMesh(mesh, options));
  state.counters["planes"] = static_cast<double>(options.count);
}
// Args: planes, threads at most (oneTBB). Wall-clock time: the work runs on several threads.
BENCHMARK(BM_SliceElephant)
    ->Args({10, 1})
    ->Args({100, 1})
    ->Args({100, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// The elephant against a copy scaled by 1.01, both ways, default sampling (100000 face
/// samples per mesh).
void BM_DistanceElephant(benchmark::State& state) {
  DistanceOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  const Mesh& a = elephant();
  Mesh b = a;
  for (float& x : b.positions) x *= 1.01f;
  for (auto _ : state) benchmark::DoNotOptimize(meshDistance(a, b, options));
}
// Arg: threads. Wall-clock time, as below.
BENCHMARK(BM_DistanceElephant)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Two spheres of about 2 n² triangles each, both ways, default sampling. Args: n, threads.
void BM_DistanceSpheres(benchmark::State& state) {
  DistanceOptions options;
  options.threads = static_cast<unsigned>(state.range(1));
  const int n = static_cast<int>(state.range(0));
  const Mesh a = sphere(n, 1.0), b = sphere(n + 1, 1.05);
  for (auto _ : state) benchmark::DoNotOptimize(meshDistance(a, b, options));
  state.counters["triangles"] = static_cast<double>(a.triangleCount());
}
BENCHMARK(BM_DistanceSpheres)
    ->Args({64, 1})
    ->Args({64, 2})
    ->Args({256, 1})
    ->Args({256, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// The elephant's standing leg (docs/rebuild.md) rebuilt from K sections of 64 points with
/// 8 modes: slicing, preparing, fitting and solving the global chain, what `pdesurf rebuild`
/// does before it measures. Issue 12's target: under 50 ms at K = 49.
SectionRebuildOptions legOptions(std::uint32_t count) {
  SectionRebuildOptions o;
  o.slice.axis = Axis::Y;
  o.slice.count = count;
  o.slice.range = {-0.45, -0.32};
  o.slice.near = Vec3(0.117, -0.4, -0.045);
  o.prep.points = 64;
  o.modes = 8;
  return o;
}

void BM_RebuildElephantLeg(benchmark::State& state) {
  const Mesh& mesh = elephant();
  const SectionRebuildOptions o = legOptions(static_cast<std::uint32_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(rebuildFromSections(mesh, o));
  state.counters["sections"] = static_cast<double>(o.slice.count);
}
BENCHMARK(BM_RebuildElephantLeg)->Arg(25)->Arg(49)->Unit(benchmark::kMillisecond);

/// The baseline of the same run: slicing the same planes alone (the rebuild's first step).
void BM_SliceElephantLeg(benchmark::State& state) {
  const Mesh& mesh = elephant();
  const SectionRebuildOptions o = legOptions(static_cast<std::uint32_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sliceMesh(mesh, o.slice));
}
BENCHMARK(BM_SliceElephantLeg)->Arg(25)->Arg(49)->Unit(benchmark::kMillisecond);

/// Issue 13's target: a 1,000-frame layout fitted to a 30k-triangle mesh in under 10 s on
/// one core. The mesh: CGAL's mannequin-devil.off (25,888 triangles, one boundary loop: of
/// Debian's demo meshes with a disk's topology, the nearest to 30k); the layout: its 32 × 32
/// grid (1,024 frames, 4,225 vertices), made once outside the timing; the fit: default
/// options but automatic surface samples (5 × 5 a frame here), to convergence, one thread.
const Mesh& devil() {
  static const Mesh mesh = cgalMesh("mannequin-devil.off");
  return mesh;
}
const VertexFrameModel& devilGrid() {
  static const VertexFrameModel layout = gridLayout(devil(), {32, 32}, "mannequin-devil.off");
  return layout;
}

void BM_FitDevilGrid32(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const VertexFrameModel& layout = devilGrid();
  FitResult fit;
  FitOptions options;
  options.samplesPerSide = 0;
  for (auto _ : state) fit = fitVertexFrames(layout, devil(), options);
  state.counters["iterations"] = static_cast<double>(fit.iterations.size() - 1);
  state.counters["rms_percent"] = 100.0 * fit.iterations.back().measure.rms();
  state.counters["folded"] = fit.iterations.back().measure.foldedSamples;
}
BENCHMARK(BM_FitDevilGrid32)->Iterations(1)->Repetitions(3)->Unit(benchmark::kSecond);

/// The baseline of the same run: the distances of the layout's surface (tessellated at 5
/// points a side, 26,624 triangles) to the mesh, both ways, 25,600 face samples a mesh (the
/// fit's surface samples at 5 × 5 a frame), one thread: two AABB-tree builds and one pass of
/// closest-point queries each way, what one fit iteration cannot do without.
void BM_FitDevilBaseline(benchmark::State& state) {
  const VertexFrameModel& layout = devilGrid();
  const Mesh surface = tessellate(solve(layout), {5});
  DistanceOptions options;
  options.threads = 1;
  options.samples = 25600;
  for (auto _ : state) benchmark::DoNotOptimize(meshDistance(surface, devil(), options));
}
BENCHMARK(BM_FitDevilBaseline)->Repetitions(3)->Unit(benchmark::kMillisecond);

/// Issue 25's target: `rebuild --target-rms 0.2%` on a 30,000-triangle mesh within 60 s of
/// CPU time. The mesh: CGAL's bear.off (27,648 triangles, closed); the search
/// `searchTargetRms` with default options (growing from 12 frames, then bisecting), each
/// trial's layout made, fitted and measured; one thread, so CPU time is the time measured.
void BM_TargetRmsBear(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  static const Mesh bear = cgalMesh("bear.off");
  TargetSearchOptions options;
  options.targetRms = 0.002;
  TargetSearch search;
  for (auto _ : state) search = searchTargetRms(bear, options, "bear.off");
  state.counters["trials"] = search.trials;
  state.counters["frames"] = static_cast<double>(search.best.layout.model.frames.size());
  state.counters["worse_rms_percent"] = 100.0 * search.best.worseRms();
  state.counters["reached"] = search.reached ? 1 : 0;
}
BENCHMARK(BM_TargetRmsBear)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
