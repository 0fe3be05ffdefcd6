// Per-point evaluation with unit normals of a vertex-frame patch against Open CASCADE's
// Geom_BSplineSurface::D1 on the same surface (its exact bicubic Bézier form, built by
// bezierPatch), in one program, at the same 4,096 random (u, v). Issue 5 target: pdesurf
// ≥ 40× OCCT's points per second. Items = points evaluated (each with position, both first
// derivatives and the unit normal).
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include <Geom_BSplineSurface.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include "pdesurf/model_io.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/occt_convert.hpp"
#include "pdesurf/spectral_io.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace {

using pdesurf::Vec3;

constexpr std::size_t kPoints = 4096;

/// A force-free patch of the mug example (a real model's coefficients, not a toy).
const pdesurf::VertexFramePatch& mugPatch() {
  static const pdesurf::VertexFrameSurface surface = pdesurf::solve(
      pdesurf::loadModel(PDESURF_SOURCE_DIR "/examples/mug.json").get<pdesurf::VertexFrameModel>());
  return surface.patches[5];
}

const std::vector<std::pair<double, double>>& points() {
  static const auto uvs = [] {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::pair<double, double>> out(kPoints);
    for (auto& [u, v] : out) u = unit(rng), v = unit(rng);
    return out;
  }();
  return uvs;
}

/// Sums `pointAndNormal(u, v)` (a point plus its unit normal) over the 4,096 points.
template <class PointAndNormal>
void sumOverPoints(benchmark::State& state, PointAndNormal pointAndNormal) {
  const auto& uvs = points();
  for (auto _ : state) {
    Vec3 sum = Vec3::Zero();
    for (const auto& [u, v] : uvs) sum += pointAndNormal(u, v);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * uvs.size()));
}

/// VertexFramePatch::evaluate (the general evaluation: polynomial plus forces, none here),
/// then the normal from the cross product.
void PdesurfEvaluate(benchmark::State& state) {
  const pdesurf::VertexFramePatch& patch = mugPatch();
  sumOverPoints(state, [&](double u, double v) -> Vec3 {
    const pdesurf::SurfacePoint s = patch.evaluate(u, v);
    return s.p + s.du.cross(s.dv).normalized();
  });
}

/// evaluatePolynomial: Horner on the ten monomials, normal included (force-free patches).
void PdesurfHorner(benchmark::State& state) {
  const pdesurf::VertexFramePatch& patch = mugPatch();
  sumOverPoints(state, [&](double u, double v) -> Vec3 {
    const pdesurf::PolynomialPatchPoint s = pdesurf::evaluatePolynomial(patch, u, v);
    return s.p + s.normal;
  });
}

/// evaluatePolynomial on the 4,096 points at once: still each point on its own (any u, v),
/// but laid out so that the loop runs in SIMD lanes.
void PdesurfHornerBatch(benchmark::State& state) {
  const pdesurf::VertexFramePatch& patch = mugPatch();
  std::vector<double> us, vs;
  for (const auto& [u, v] : points()) us.push_back(u), vs.push_back(v);
  pdesurf::PolynomialPatchPoints out;
  for (auto _ : state) {
    pdesurf::evaluatePolynomial(patch, us, vs, out);
    benchmark::DoNotOptimize(out.nz.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * us.size()));
}

/// Open CASCADE: D1 on the patch's Bézier form, then the normal as OCCT users compute it.
void OcctD1(benchmark::State& state) {
  const Handle(Geom_BSplineSurface) surface = pdesurf::toOcct(pdesurf::bezierPatch(mugPatch()));
  const auto& uvs = points();
  for (auto _ : state) {
    gp_Vec sum(0, 0, 0);
    for (const auto& [u, v] : uvs) {
      gp_Pnt p;
      gp_Vec du, dv;
      surface->D1(u, v, p, du, dv);
      gp_Vec n = du.Crossed(dv);
      const double len = n.Magnitude();
      if (len > 0.0) n.Divide(len);
      sum += gp_Vec(p.XYZ()) + n;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * uvs.size()));
}

/// The same points agree: a benchmark of wrong answers would be meaningless.
bool sameAnswers() {
  const Handle(Geom_BSplineSurface) surface = pdesurf::toOcct(pdesurf::bezierPatch(mugPatch()));
  for (const auto& [u, v] : points()) {
    gp_Pnt p;
    gp_Vec du, dv;
    surface->D1(u, v, p, du, dv);
    const pdesurf::PolynomialPatchPoint s = pdesurf::evaluatePolynomial(mugPatch(), u, v);
    if ((Vec3(p.X(), p.Y(), p.Z()) - s.p).norm() > 1e-12 ||
        (Vec3(du.X(), du.Y(), du.Z()) - s.du).norm() > 1e-11)
      return false;
  }
  return true;
}

}  // namespace

BENCHMARK(PdesurfEvaluate);
BENCHMARK(PdesurfHorner);
BENCHMARK(PdesurfHornerBatch);
BENCHMARK(OcctD1);

int main(int argc, char** argv) {
  if (!sameAnswers()) {
    std::fprintf(stderr, "bench_nurbs_eval: pdesurf and Open CASCADE disagree\n");
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
