// A model file's tessellation through the model layer, as the CLI's build and the Python
// package's Surface.tessellate call it: the C++ side of bench/python_overhead.py's ratio
// (docs/performance.md, "The Python package").
#include <benchmark/benchmark.h>

#include <string>

#include "pdesurf/model_io.hpp"

namespace {

void BM_TessellateMug(benchmark::State& state) {
  const std::string path = std::string(PDESURF_SOURCE_DIR) + "/examples/mug.json";
  const pdesurf::SolvedModel solved = pdesurf::solve(pdesurf::loadModel(path), path);
  const pdesurf::TessellateOptions options{static_cast<std::uint32_t>(state.range(0))};
  for (auto _ : state) benchmark::DoNotOptimize(pdesurf::tessellate(solved, options));
}
BENCHMARK(BM_TessellateMug)->Arg(17)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
