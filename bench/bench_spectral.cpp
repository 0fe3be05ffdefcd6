// Seed 003 Table 1 cases (order 10 on 20×30, order 12 on 30×10, order 40 on 40×10, 6 Fourier
// modes): time of solve + evaluation on the grid. Curves are Fourier series (the seed fits
// 300 points per curve with 6 modes beforehand); the *_FromPoints variants include the fit of
// 300 points per curve and the remainder.
#include <cmath>
#include <numbers>
#include <optional>
#include <variant>
#include <vector>

#include <benchmark/benchmark.h>

#include "pdesurf/spectral.hpp"
#include "pdesurf/spectral_io.hpp"

namespace {

using pdesurf::CurveInput;
using pdesurf::FourierCurve;
using pdesurf::SampledCurve;
using pdesurf::SpectralCondition;
using pdesurf::Vec3;
constexpr double kPi = std::numbers::pi;
constexpr std::uint32_t kModes = 6;
constexpr int kPoints = 300;

/// Seed 003 eqs. 26–28 (sea shell), at section parameter s ∈ [0, π].
Vec3 shell(double s, double v) {
  const double al = 0.2, be = 1.0, ga = 0.1;
  return {al * (1 - s / (2 * kPi)) * std::cos(2 * s) * (1 + std::cos(v)) + ga * std::cos(2 * s),
          be * (1 - s / (2 * kPi)) * std::sin(2 * s) * (1 + std::cos(v)) + ga * std::sin(2 * s),
          ga * s / (2 * kPi) + al * (1 - v / (2 * kPi)) * std::sin(v)};
}

/// Seed 003 eqs. 29–31 (Klein bottle), s ∈ [0, 2π].
Vec3 klein(double s, double v) {
  const double al = 6, be = 16, ga = 4 * (1 - std::cos(s) / 2);
  if (s < kPi)
    return {al * std::cos(s) * (1 + std::sin(s)) + ga * std::cos(s) * std::cos(v),
            be * std::sin(s) + ga * std::sin(s) * std::cos(v), ga * std::sin(v)};
  return {al * std::cos(s) * (1 + std::sin(s)) + ga * std::cos(v + kPi), be * std::sin(s),
          ga * std::sin(v)};
}

/// A free-hand-like tube section (seed 003 Fig. 2 stands in: 10 curves).
Vec3 tube(double s, double v) {
  const double r = 1.0 + 0.3 * std::sin(3 * s);
  return {r * std::cos(v) + 0.1 * std::cos(2 * v) + 0.4 * std::sin(s), 0.8 * r * std::sin(v),
          3 * s + 0.1 * std::sin(v + s)};
}

template <class F>
std::vector<SampledCurve> sections(F f, int count, double s1) {
  std::vector<SampledCurve> out;
  for (int k = 0; k < count; ++k) {
    SampledCurve c;
    const double s = s1 * k / (count - 1);
    for (int j = 0; j < kPoints; ++j) {
      const double v = 2 * kPi * j / kPoints;
      c.points.push_back(f(s, v));
      c.v.push_back(v);
    }
    out.push_back(std::move(c));
  }
  return out;
}

void run(benchmark::State& state, const std::vector<SampledCurve>& curves, std::uint32_t n,
         int uCount, int vCount, bool fromPoints) {
  std::vector<SpectralCondition> conditions;
  for (const SampledCurve& c : curves) {
    if (fromPoints)
      conditions.push_back({0, std::nullopt, c});
    else
      conditions.push_back({0, std::nullopt, pdesurf::fitFourier(c, kModes).curve});
  }
  std::vector<double> us(uCount), vs(vCount);
  for (int i = 0; i < uCount; ++i) us[i] = static_cast<double>(i) / (uCount - 1);
  for (int j = 0; j < vCount; ++j) vs[j] = 2 * kPi * j / vCount;
  pdesurf::SpectralOptions options;
  options.modes = kModes;
  options.remainder = fromPoints;
  pdesurf::SpectralGrid grid;
  try {
    pdesurf::solve(pdesurf::SpectralOperator::ugail(n), conditions, options);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) {
    const pdesurf::SpectralPatch patch =
        pdesurf::solve(pdesurf::SpectralOperator::ugail(n), conditions, options);
    pdesurf::evaluateGrid(patch, us, vs, grid);
    benchmark::DoNotOptimize(grid.p.data());
  }
}

void Order10_20x30(benchmark::State& s) { run(s, sections(tube, 10, 1.0), 5, 20, 30, false); }
void Order12_30x10(benchmark::State& s) { run(s, sections(shell, 12, kPi), 6, 30, 10, false); }
void Order40_40x10(benchmark::State& s) { run(s, sections(klein, 40, 2 * kPi), 20, 40, 10, false); }
void Order10_20x30_FromPoints(benchmark::State& s) {
  run(s, sections(tube, 10, 1.0), 5, 20, 30, true);
}
void Order12_30x10_FromPoints(benchmark::State& s) {
  run(s, sections(shell, 12, kPi), 6, 30, 10, true);
}

/// Order 40 as examples/klein-bottle.json builds it (a = N = 20, sections at
/// Chebyshev–Lobatto u: docs/examples.md; mode 1 in quad). Order40_40x10 above is the seed's
/// own recipe (a = N = 20, uniform u, fitted curves: modes 1–6 in quad, docs/spectral.md).
void kleinExample(benchmark::State& state, std::optional<double> a) {
  auto model = pdesurf::loadModel(PDESURF_SOURCE_DIR "/examples/klein-bottle.json")
                   .get<pdesurf::SpectralModel>();
  if (a) model.op = pdesurf::SpectralOperator::ugail(model.op.power, a);
  std::vector<double> us(40), vs(10);
  for (int i = 0; i < 40; ++i) us[i] = i / 39.0;
  for (int j = 0; j < 10; ++j) vs[j] = 2 * kPi * j / 10;
  pdesurf::SpectralOptions options = model.options;
  options.modes = kModes;
  pdesurf::SpectralGrid grid;
  for (auto _ : state) {
    const pdesurf::SpectralPatch patch = pdesurf::solve(model.op, model.conditions, options);
    pdesurf::evaluateGrid(patch, us, vs, grid);
    benchmark::DoNotOptimize(grid.p.data());
  }
}

void Order40_40x10_KleinExample(benchmark::State& s) { kleinExample(s, std::nullopt); }
/// The same sections at a = 2N = 40: mode 1 stays in long double.
void Order40_40x10_KleinExampleAtTwiceN(benchmark::State& s) { kleinExample(s, 40.0); }

BENCHMARK(Order10_20x30)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order12_30x10)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order40_40x10)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order40_40x10_KleinExample)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order40_40x10_KleinExampleAtTwiceN)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order10_20x30_FromPoints)->Unit(benchmark::kMicrosecond);
BENCHMARK(Order12_30x10_FromPoints)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
