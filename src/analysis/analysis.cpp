// Continuity, bounds and storage measurements.
#include <fmt/format.h>

#include "pdesurf/analysis.hpp"

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

Bounds surfaceBounds(const VertexFrameSurface& surface, std::uint32_t samples) {
  Bounds b;
  samples = std::max<std::uint32_t>(samples, 2);
  for (const VertexFramePatch& patch : surface.patches)
    for (std::uint32_t j = 0; j < samples; ++j)
      for (std::uint32_t i = 0; i < samples; ++i)
        b.add(patch.position(static_cast<double>(i) / (samples - 1),
                             static_cast<double>(j) / (samples - 1)));
  return b;
}

std::size_t storageBytes(const VertexFrameModel& model) {
  fmt::memory_buffer out;
  auto num = [&](double x) { fmt::format_to(std::back_inserter(out), "{:.6g} ", x); };
  auto idx = [&](std::uint32_t i) { fmt::format_to(std::back_inserter(out), "{} ", i); };
  auto vec = [&](const Vec3& v) {
    for (int c = 0; c < 3; ++c) num(v[c]);
  };
  // Each record's trailing space becomes its newline: the byte count is the same.
  for (const Vec3& v : model.vertices) vec(v);
  for (const Frame& f : model.frames) {
    for (std::uint32_t i : f.vertices) idx(i);
    vec(f.a1);
    vec(f.a2);
    for (const FrameForce& ff : f.forces) {
      vec(ff.f0);
      for (double r : {ff.region.u0, ff.region.u1, ff.region.v0, ff.region.v1}) num(r);
    }
  }
  for (const SharedForce& sf : model.forces) {
    vec(sf.f0);
    for (std::uint32_t k : sf.frames) idx(k);
  }
  return out.size();
}

}  // namespace pdesurf
