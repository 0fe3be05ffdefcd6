// Analytic curvature of vertex-frame patches (analysis.hpp): the classical formulas of the
// first and second fundamental forms, K = (L N − M²)/(E G − F²) and
// H = (E N − 2 F M + G L)/(2 (E G − F²)), with the second derivatives of the closed form
// S = Σ c_i m_i(u, v) + Σ k sin(π(u−u0)/Lu) sin(π(v−v0)/Lv) (docs/derivations.md §1.2, §1.5).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "numerics/force_shape.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf {
namespace {

struct SecondDerivatives {
  Vec3 uu, uv, vv;
};

SecondDerivatives secondDerivatives(const VertexFramePatch& patch, double u, double v) {
  const auto& c = patch.c;  // m = 1, u, u², u³, v, v², v³, uv, u²v, uv²
  SecondDerivatives d{2.0 * c[2] + 6.0 * u * c[3] + 2.0 * v * c[8],
                      c[7] + 2.0 * u * c[8] + 2.0 * v * c[9],
                      2.0 * c[5] + 6.0 * v * c[6] + 2.0 * u * c[9]};
  constexpr double kPi = std::numbers::pi;
  for (const ForceTerm& f : patch.forces) {
    const detail::ForceShape su = detail::forceShape(u, f.region.u0, f.region.u1);
    const detail::ForceShape sv = detail::forceShape(v, f.region.v0, f.region.v1);
    // (sin πt)'' = −(π/L)² sin πt inside the region.
    const double wu = kPi / (f.region.u1 - f.region.u0), wv = kPi / (f.region.v1 - f.region.v0);
    d.uu += (-wu * wu * su.s * sv.s) * f.k;
    d.uv += (su.ds * sv.ds) * f.k;
    d.vv += (-wv * wv * su.s * sv.s) * f.k;
  }
  return d;
}

}  // namespace

Curvature patchCurvature(const VertexFramePatch& patch, double u, double v, const Vec3& n) {
  SurfacePoint p = patch.evaluate(u, v);
  double e = p.du.dot(p.du), f = p.du.dot(p.dv), g = p.dv.dot(p.dv);
  if (e * g - f * f <= kSingularMetric * (e + g) * (e + g)) {
    u += u < 0.5 ? kPoleCurvatureStep : -kPoleCurvatureStep;
    v += v < 0.5 ? kPoleCurvatureStep : -kPoleCurvatureStep;
    p = patch.evaluate(u, v);
    e = p.du.dot(p.du), f = p.du.dot(p.dv), g = p.dv.dot(p.dv);
  }
  const double metric = e * g - f * f;
  if (!(metric > 0.0)) return {};
  Vec3 normal = p.du.cross(p.dv).normalized();
  if (normal.dot(n) < 0.0) normal = -normal;
  const SecondDerivatives d = secondDerivatives(patch, u, v);
  const double l = d.uu.dot(normal), m = d.uv.dot(normal), nn = d.vv.dot(normal);
  // The studio's sign: a sphere's outward normal gives H = +1/R (there S_uu·n < 0).
  return {-(e * nn - 2.0 * f * m + g * l) / (2.0 * metric), (l * nn - m * m) / metric};
}

std::vector<float> meshCurvatures(const VertexFrameSurface& surface, const Mesh& mesh,
                                  std::uint32_t resolution) {
  const std::size_t vertices = mesh.vertexCount();
  const std::uint32_t n = resolution;
  std::vector<double> sum(2 * vertices, 0.0);
  std::vector<std::uint32_t> count(vertices, 0);
  // The triangles of each patch (patch ids in triangle order).
  std::vector<std::vector<std::uint32_t>> corners(surface.patches.size());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int j = 0; j < 3; ++j) corners[mesh.patchIds[t]].push_back(mesh.indices[3 * t + j]);
  std::vector<Vec3> grid(std::size_t{n} * n);
  std::vector<std::uint32_t> seen;
  for (std::size_t k = 0; k < surface.patches.size(); ++k) {
    const VertexFramePatch& patch = surface.patches[k];
    Bounds box;
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) {
        const Vec3 q = patch.position(double(i) / (n - 1), double(j) / (n - 1));
        grid[std::size_t{j} * n + i] = q;
        box.add(q);
      }
    // The grid's samples in cells about a sample spacing wide: a vertex's nearest sample
    // is in its cell or a neighbouring one.
    const double cell = std::max(box.diagonal() / n, std::numeric_limits<double>::min());
    const auto key = [&](long x, long y, long z) {
      return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) |
             (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
             static_cast<std::uint64_t>(z & 0x1fffff);
    };
    const auto cellOf = [&](const Vec3& q, int c) {
      return static_cast<long>(std::floor((q[c] - box.min[c]) / cell));
    };
    std::unordered_multimap<std::uint64_t, std::uint32_t> cells;
    for (std::uint32_t s = 0; s < grid.size(); ++s)
      cells.emplace(key(cellOf(grid[s], 0), cellOf(grid[s], 1), cellOf(grid[s], 2)), s);
    seen.clear();
    for (const std::uint32_t vertex : corners[k]) seen.push_back(vertex);
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (const std::uint32_t vertex : seen) {
      const Vec3 q(mesh.positions[3 * vertex], mesh.positions[3 * vertex + 1],
                   mesh.positions[3 * vertex + 2]);
      std::uint32_t best = 0;
      double bestDistance = std::numeric_limits<double>::infinity();
      const long cx = cellOf(q, 0), cy = cellOf(q, 1), cz = cellOf(q, 2);
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy)
          for (long dz = -1; dz <= 1; ++dz) {
            const auto [first, last] = cells.equal_range(key(cx + dx, cy + dy, cz + dz));
            for (auto it = first; it != last; ++it) {
              const double distance = (grid[it->second] - q).squaredNorm();
              if (distance < bestDistance) bestDistance = distance, best = it->second;
            }
          }
      if (!std::isfinite(bestDistance)) continue;  // not on this patch's grid: no value
      const Vec3 normal(mesh.normals[3 * vertex], mesh.normals[3 * vertex + 1],
                        mesh.normals[3 * vertex + 2]);
      const Curvature c =
          patchCurvature(patch, double(best % n) / (n - 1), double(best / n) / (n - 1), normal);
      sum[2 * vertex] += c.mean;
      sum[2 * vertex + 1] += c.gaussian;
      ++count[vertex];
    }
  }
  std::vector<float> out(2 * vertices, 0.0f);
  for (std::size_t i = 0; i < vertices; ++i)
    if (count[i] > 0)
      for (int c = 0; c < 2; ++c) out[2 * i + c] = static_cast<float>(sum[2 * i + c] / count[i]);
  return out;
}

}  // namespace pdesurf
