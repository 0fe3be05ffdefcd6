// Continuity, bounds and storage measurements.
#include <algorithm>
#include <array>
#include <limits>
#include <variant>

#include <fmt/format.h>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf {

C0Report measureC0Gap(const VertexFrameSurface& surface, std::uint32_t samples) {
  C0Report report;
  const FrameTopology& topo = *surface.topology;
  samples = std::max<std::uint32_t>(samples, 2);
  for (std::uint32_t e = 0; e < topo.edges.size(); ++e) {
    const auto sides = topo.sides(e);
    const auto reversed = topo.reversed(e);
    if (sides.size() < 2) continue;
    ++report.sharedEdges;
    for (std::uint32_t i = 0; i < samples; ++i) {
      const double t = static_cast<double>(i) / (samples - 1);
      const auto [u0, v0] = sideParam(sides[0].side, t);
      const Vec3 p0 = surface.patches[sides[0].frame].position(u0, v0);
      for (std::size_t s = 1; s < sides.size(); ++s) {
        const auto [u, v] = sideParam(sides[s].side, reversed[s] ? 1.0 - t : t);
        const double gap = (surface.patches[sides[s].frame].position(u, v) - p0).norm();
        if (gap > report.maxGap) {
          report.maxGap = gap;
          report.worstEdge = e;
        }
      }
    }
  }
  return report;
}

namespace {

/// Maximises sign·S_c on the unit square from (u, v) by compass search with halving steps:
/// the refinement of a sampled extreme (S is smooth inside force regions and C0 across
/// their borders, so a derivative-free search is the robust choice).
double refineExtreme(const VertexFramePatch& patch, int c, double sign, double u, double v,
                     double step) {
  auto f = [&](double x, double y) { return sign * patch.position(x, y)[c]; };
  double best = f(u, v);
  constexpr double kStepFloor = 1e-12;  // parameter resolution of the search
  constexpr int kDirections[8][2] = {{1, 0}, {-1, 0}, {0, 1},  {0, -1},
                                     {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
  while (step > kStepFloor) {
    bool moved = false;
    for (const auto& d : kDirections) {
      const double x = std::clamp(u + d[0] * step, 0.0, 1.0);
      const double y = std::clamp(v + d[1] * step, 0.0, 1.0);
      const double value = f(x, y);
      if (value > best) {
        best = value;
        u = x;
        v = y;
        moved = true;
      }
    }
    if (!moved) step *= 0.5;
  }
  return sign * best;
}

}  // namespace

Bounds surfaceBounds(const VertexFrameSurface& surface, std::uint32_t samples) {
  samples = std::max<std::uint32_t>(samples, 2);
  // 1. Sample every patch on a grid, and every force region on a grid of its own (a
  //    narrow force can lie between the patch's samples); keep each patch's extremes.
  struct Extreme {
    double value, u, v;
    std::uint32_t patch;
  };
  std::array<std::vector<Extreme>, 6> extremes;  // (component, min|max)
  constexpr std::uint32_t kRegionSamples = 9;
  for (std::uint32_t k = 0; k < surface.patches.size(); ++k) {
    const VertexFramePatch& patch = surface.patches[k];
    std::array<Extreme, 6> best;
    for (int e = 0; e < 6; ++e)
      best[e] = {e % 2 ? -std::numeric_limits<double>::infinity()
                       : std::numeric_limits<double>::infinity(),
                 0, 0, k};
    auto visit = [&](double u, double v) {
      const Vec3 p = patch.position(u, v);
      for (int c = 0; c < 3; ++c) {
        if (p[c] < best[2 * c].value) best[2 * c] = {p[c], u, v, k};
        if (p[c] > best[2 * c + 1].value) best[2 * c + 1] = {p[c], u, v, k};
      }
    };
    for (std::uint32_t j = 0; j < samples; ++j)
      for (std::uint32_t i = 0; i < samples; ++i)
        visit(static_cast<double>(i) / (samples - 1), static_cast<double>(j) / (samples - 1));
    for (const ForceTerm& f : patch.forces)
      for (std::uint32_t j = 0; j < kRegionSamples; ++j)
        for (std::uint32_t i = 0; i < kRegionSamples; ++i)
          visit(f.region.u0 + (f.region.u1 - f.region.u0) * i / (kRegionSamples - 1),
                f.region.v0 + (f.region.v1 - f.region.v0) * j / (kRegionSamples - 1));
    for (int e = 0; e < 6; ++e) extremes[e].push_back(best[e]);
  }
  // 2. Refine the few most extreme patches of each of the six directions.
  constexpr std::size_t kRefined = 8;
  Bounds b;
  for (int e = 0; e < 6; ++e) {
    const int c = e / 2;
    const double sign = e % 2 ? 1.0 : -1.0;
    auto& list = extremes[e];
    const std::size_t keep = std::min(kRefined, list.size());
    std::partial_sort(
        list.begin(), list.begin() + static_cast<std::ptrdiff_t>(keep), list.end(),
        [&](const Extreme& x, const Extreme& y) { return sign * x.value > sign * y.value; });
    for (std::size_t i = 0; i < keep; ++i) {
      const Extreme& x = list[i];
      const double value =
          refineExtreme(surface.patches[x.patch], c, sign, x.u, x.v, 1.0 / (samples - 1));
      if (sign < 0)
        b.min[c] = std::min(b.min[c], value);
      else
        b.max[c] = std::max(b.max[c], value);
    }
  }
  return b;
}

std::size_t coincidentVertices(const VertexFrameModel& model) {
  std::vector<std::uint8_t> used(model.vertices.size(), 0);
  for (const Frame& f : model.frames)
    for (std::uint32_t v : f.vertices) used[v] = 1;
  std::vector<std::uint32_t> order;
  for (std::uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) order.push_back(v);
  auto key = [&](std::uint32_t v) {
    const Vec3& p = model.vertices[v];
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::size_t count = 0;
  for (std::size_t i = 1; i < order.size(); ++i)
    if (key(order[i]) == key(order[i - 1])) ++count;
  return count;
}

namespace {

/// Counts the bytes of numbers written to six significant digits as plain text, one space
/// between numbers and a newline after each record (the trailing space of each record
/// becomes its newline: the byte count is the same).
struct StorageText {
  fmt::memory_buffer out;
  void num(double x) { fmt::format_to(std::back_inserter(out), "{:.6g} ", x); }
  void idx(std::uint64_t i) { fmt::format_to(std::back_inserter(out), "{} ", i); }
  void vec(const Vec3& v) {
    for (int c = 0; c < 3; ++c) num(v[c]);
  }
};

}  // namespace

std::size_t storageBytes(const VertexFrameModel& model) {
  StorageText t;
  for (const Vec3& v : model.vertices) t.vec(v);
  for (const Frame& f : model.frames) {
    for (std::uint32_t i : f.vertices) t.idx(i);
    t.vec(f.a1);
    t.vec(f.a2);
    for (const FrameForce& ff : f.forces) {
      t.vec(ff.f0);
      for (double r : {ff.region.u0, ff.region.u1, ff.region.v0, ff.region.v1}) t.num(r);
    }
  }
  for (const SharedForce& sf : model.forces) {
    t.vec(sf.f0);
    for (std::uint32_t k : sf.frames) t.idx(k);
  }
  return t.out.size();
}

std::size_t storageBytes(const Mesh& mesh) {
  StorageText t;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    for (int c = 0; c < 3; ++c) t.num(mesh.positions[3 * v + c]);
  for (std::uint32_t i : mesh.indices) t.idx(i);
  return t.out.size();
}

std::size_t storageBytes(const CrossSectionModel& model) {
  StorageText t;
  t.num(model.options.a);  // the operator and the number of modes: one record
  t.idx(model.options.modes);
  for (double u : model.options.u) t.num(u);
  for (const CurveInput& c : model.curves) {
    if (const auto* f = std::get_if<FourierCurve>(&c)) {
      t.vec(f->a0);
      for (std::size_t n = 0; n < f->a.size(); ++n) {
        t.vec(f->a[n]);
        t.vec(f->b[n]);
      }
    } else {
      const auto& s = std::get<SampledCurve>(c);
      for (const Vec3& p : s.points) t.vec(p);
      for (double v : s.v) t.num(v);
    }
  }
  return t.out.size();
}

}  // namespace pdesurf
