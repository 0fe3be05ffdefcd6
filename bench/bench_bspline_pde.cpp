// The B-spline PDE solve (seed 004, docs/bspline-pde.md) on n×n nets (last index n, so
// (n-2)² inner points, 3 components): the banded Kronecker solve X = M⁻¹ Y N⁻ᵀ against
// Eigen's SparseLU on the same (n-2)² mask equations, assembled and factored each time.
// Issue 5 targets: ≤ 10 ms at n = 200, SparseLU / Kronecker ≥ 20×.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "pdesurf/bspline_pde.hpp"

namespace {

using pdesurf::ControlNet;
using pdesurf::KnotType;
using pdesurf::Vec3;

/// A wavy boundary: given rows and columns on z = sin·cos, inner points zero.
ControlNet boundary(std::uint32_t n) {
  ControlNet net(n, n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.05, 0.05);
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j <= n; ++j) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      if (net.given(i, j)) net(i, j) = Vec3(u, v, std::sin(6 * u) * std::cos(5 * v) + d(rng));
    }
  return net;
}

/// The inner points by SparseLU on the assembled mask equations (one per span pair).
std::vector<Vec3> sparseSolve(const ControlNet& net, KnotType type) {
  const std::uint32_t n = net.nu;
  const std::vector<double> knots = pdesurf::cubicKnots(type, n);
  std::vector<std::array<double, 4>> t;
  for (std::uint32_t s = 3; s <= n; ++s) t.push_back(pdesurf::thirdDerivativeMask(knots, s));
  const int m = static_cast<int>(n) - 2;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(16 * m * m));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m * m, 3);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      for (int r = 0; r < 4; ++r)
        for (int q = 0; q < 4; ++q) {
          const auto i = static_cast<std::uint32_t>(a + r), j = static_cast<std::uint32_t>(b + q);
          const double w = t[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)] *
                           t[static_cast<std::size_t>(b)][static_cast<std::size_t>(q)];
          if (net.given(i, j))
            rhs.row(a * m + b) -= w * net(i, j).transpose();
          else
            entries.emplace_back(a * m + b, static_cast<int>(i - 2) * m + static_cast<int>(j - 2),
                                 w);
        }
  Eigen::SparseMatrix<double> matrix(m * m, m * m);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(matrix);
  if (lu.info() != Eigen::Success) {
    std::fprintf(stderr, "SparseLU failed at n = %u\n", n);
    std::abort();
  }
  const Eigen::MatrixXd x = lu.solve(rhs);
  std::vector<Vec3> out(static_cast<std::size_t>(m * m));
  for (int k = 0; k < m * m; ++k) out[static_cast<std::size_t>(k)] = x.row(k).transpose();
  return out;
}

KnotType knotType(const benchmark::State& state) {
  return state.range(1) ? KnotType::Clamped : KnotType::Uniform;
}

void BM_KroneckerSolve(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const KnotType type = knotType(state);
  const ControlNet net = boundary(n);
  for (auto _ : state) {
    pdesurf::BSplineSurface s = pdesurf::solve(net, {type, type});
    benchmark::DoNotOptimize(s.net().points.data());
  }
  state.counters["unknowns"] = static_cast<double>((n - 2) * (n - 2));
}

// An editor's re-solve: M, N, F, H factored once (BSplinePdeSolver), the net solved in place.
void BM_FactoredSolve(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const KnotType type = knotType(state);
  ControlNet net = boundary(n);
  const pdesurf::BSplinePdeSolver solver(n, n, {type, type});
  for (auto _ : state) {
    solver.solveInPlace(net);
    benchmark::DoNotOptimize(net.points.data());
  }
}

void BM_SparseLU(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const KnotType type = knotType(state);
  const ControlNet net = boundary(n);
  // The two solvers agree (checked once, outside the timing).
  {
    const pdesurf::BSplineSurface s = pdesurf::solve(net, {type, type});
    const std::vector<Vec3> x = sparseSolve(net, type);
    double worst = 0.0;
    const std::uint32_t m = n - 2;
    for (std::uint32_t a = 0; a < m; ++a)
      for (std::uint32_t b = 0; b < m; ++b)
        worst = std::max(worst, (x[a * m + b] - s.net()(a + 2, b + 2)).norm());
    state.counters["max_difference"] = worst;
  }
  for (auto _ : state) {
    std::vector<Vec3> x = sparseSolve(net, type);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["unknowns"] = static_cast<double>((n - 2) * (n - 2));
}

// Args: {n, clamped}.
BENCHMARK(BM_KroneckerSolve)
    ->ArgsProduct({{50, 100, 200}, {0, 1}})
    ->ArgNames({"n", "clamped"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FactoredSolve)
    ->ArgsProduct({{50, 100, 200}, {0, 1}})
    ->ArgNames({"n", "clamped"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SparseLU)
    ->ArgsProduct({{50, 100, 200}, {0, 1}})
    ->ArgNames({"n", "clamped"})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
