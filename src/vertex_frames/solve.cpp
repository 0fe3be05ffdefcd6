// Closed-form patches and strip solvers (seed 000 §3; docs/derivations.md §1.2–§1.4).
#include <cmath>
#include <queue>

#include <fmt/format.h>

#include "numerics/force_shape.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

namespace {

std::array<Vec3, 8> framePoints(const VertexFrameModel& model, std::uint32_t k) {
  std::array<Vec3, 8> p;
  for (int i = 0; i < 8; ++i) p[i] = model.vertices[model.frames[k].vertices[i]];
  return p;
}

/// C8 and C9 depend on the vertices alone: with A = C7+C8+C9, B = C7+C8+C9/2 and
/// D = C7+C8/2+C9 read off S(1,1), S(1,½) and S(½,1), C9 = 2(A-B) and C8 = 2(A-D).
struct CrossTerms {
  Vec3 c7, c8, c9;
};
CrossTerms crossTerms(const std::array<Vec3, 8>& p) {
  const Vec3 a = p[4] - p[2] - p[6] + p[0];
  const Vec3 b = 2.0 * (p[3] - p[2] - p[7] + p[0]);
  const Vec3 d = 2.0 * (p[5] - p[1] - p[6] + p[0]);
  const Vec3 c9 = 2.0 * (a - b);
  const Vec3 c8 = 2.0 * (a - d);
  return {a - c8 - c9, c8, c9};
}

/// -b/a per component, 0 where a is 0 (the coefficient is then free: 0 is the choice).
Vec3 minimiser(const Vec3& a, const Vec3& b) {
  Vec3 x;
  for (int c = 0; c < 3; ++c) x[c] = a[c] != 0.0 ? -b[c] / a[c] : 0.0;
  return x;
}

/// The PDE residual's part along (6u-3) is a1 C3 + a2 C9/3, along (6v-3) it is
/// a2 C6 + a1 C8/3 (docs/derivations.md §1.3); one patch alone zeroes it with
/// C3 = -(a2/a1) C9/3, C6 = -(a1/a2) C8/3 (ratio first: no overflow for large a1, a2).
/// Arguments: (a1, a2, C9) for C3, (a2, a1, C8) for C6.
Vec3 ownCubic(const Vec3& a, const Vec3& other, const Vec3& cross) {
  Vec3 x;
  for (int c = 0; c < 3; ++c) x[c] = a[c] != 0.0 ? -(other[c] / a[c]) * cross[c] / 3.0 : 0.0;
  return x;
}

}  // namespace

std::array<Vec3, 10> patchCoefficients(const std::array<Vec3, 8>& p, const Vec3& c3,
                                       const Vec3& c6) {
  const CrossTerms t = crossTerms(p);
  std::array<Vec3, 10> c;
  c[0] = p[0];
  c[1] = -3.0 * p[0] + 4.0 * p[1] - p[2] + 0.5 * c3;
  c[2] = 2.0 * p[0] - 4.0 * p[1] + 2.0 * p[2] - 1.5 * c3;
  c[3] = c3;
  c[4] = -3.0 * p[0] - p[6] + 4.0 * p[7] + 0.5 * c6;
  c[5] = 2.0 * p[0] + 2.0 * p[6] - 4.0 * p[7] - 1.5 * c6;
  c[6] = c6;
  c[7] = t.c7;
  c[8] = t.c8;
  c[9] = t.c9;
  return c;
}

std::array<Vec3, 2> singlePatchCubics(const std::array<Vec3, 8>& p, const Vec3& a1,
                                      const Vec3& a2) {
  const CrossTerms t = crossTerms(p);
  return {ownCubic(a1, a2, t.c9), ownCubic(a2, a1, t.c8)};
}

namespace {

/// The particular solution of f0 on `region` of frame f (seed eq. 12; docs/derivations.md §1.5).
ForceTerm forceTerm(const Frame& f, const Vec3& f0, const Region& r) {
  const double lu = r.u1 - r.u0, lv = r.v1 - r.v0;
  ForceTerm t;
  t.region = r;
  for (int c = 0; c < 3; ++c) t.k[c] = detail::forceAmplitude(f0[c], f.a1[c], f.a2[c], lu, lv);
  return t;
}

/// Every frame's force terms: its own forces, then the shared ones in model order.
std::vector<std::vector<ForceTerm>> allForceTerms(const VertexFrameModel& model) {
  std::vector<std::vector<ForceTerm>> terms(model.frames.size());
  for (std::size_t k = 0; k < model.frames.size(); ++k)
    for (const FrameForce& ff : model.frames[k].forces)
      terms[k].push_back(forceTerm(model.frames[k], ff.f0, ff.region));
  for (const SharedForce& sf : model.forces)
    for (std::uint32_t k : sf.frames) terms[k].push_back(forceTerm(model.frames[k], sf.f0, {}));
  return terms;
}

}  // namespace

Vec3 VertexFramePatch::position(double u, double v) const {
  const double u2 = u * u, v2 = v * v;
  Vec3 p = c[0] + u * c[1] + u2 * c[2] + u2 * u * c[3] + v * c[4] + v2 * c[5] + v2 * v * c[6] +
           u * v * c[7] + u2 * v * c[8] + u * v2 * c[9];
  for (const ForceTerm& f : forces) {
    const detail::ForceShape su = detail::forceShape(u, f.region.u0, f.region.u1);
    const detail::ForceShape sv = detail::forceShape(v, f.region.v0, f.region.v1);
    p += (su.s * sv.s) * f.k;
  }
  return p;
}

SurfacePoint VertexFramePatch::evaluate(double u, double v) const {
  SurfacePoint r;
  r.p = position(u, v);
  const double u2 = u * u, v2 = v * v;
  r.du = c[1] + 2.0 * u * c[2] + 3.0 * u2 * c[3] + v * c[7] + 2.0 * u * v * c[8] + v2 * c[9];
  r.dv = c[4] + 2.0 * v * c[5] + 3.0 * v2 * c[6] + u * c[7] + u2 * c[8] + 2.0 * u * v * c[9];
  for (const ForceTerm& f : forces) {
    const detail::ForceShape su = detail::forceShape(u, f.region.u0, f.region.u1);
    const detail::ForceShape sv = detail::forceShape(v, f.region.v0, f.region.v1);
    r.du += (su.ds * sv.s) * f.k;
    r.dv += (su.s * sv.ds) * f.k;
  }
  return r;
}

VertexFrameSurface solve(const VertexFrameModel& model, const VertexFrameSolveOptions& options) {
  return solve(model, std::make_shared<const FrameTopology>(buildTopology(model)), options);
}

VertexFrameSurface solve(const VertexFrameModel& model,
                         std::shared_ptr<const FrameTopology> topology,
                         const VertexFrameSolveOptions& options) {
  const auto nFrames = static_cast<std::uint32_t>(model.frames.size());
  VertexFrameSurface out;
  out.topology = std::move(topology);
  const FrameTopology& topo = *out.topology;

  std::vector<CrossTerms> cross(nFrames);
  for (std::uint32_t k = 0; k < nFrames; ++k) cross[k] = crossTerms(framePoints(model, k));

  std::vector<Vec3> values(topo.stripCount, Vec3::Zero());
  std::size_t freeStrips = 0;
  if (options.solver == Solver::Global) {
    // X = -Σ s a b / Σ a² over the strip's patches: the minimiser of its summed residual.
    // Both sums are formed with a and b divided by the strip's largest |a| (per
    // component), so that neither overflows nor underflows for any finite a1, a2.
    std::vector<Vec3> scale(topo.stripCount, Vec3::Zero());
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (int d = 0; d < 2; ++d) {
        const Vec3& a = d == 0 ? model.frames[k].a1 : model.frames[k].a2;
        scale[topo.strip[k][d]] = scale[topo.strip[k][d]].cwiseMax(a.cwiseAbs());
      }
    std::vector<Vec3> num(topo.stripCount, Vec3::Zero()), den(topo.stripCount, Vec3::Zero());
    for (std::uint32_t k = 0; k < nFrames; ++k) {
      for (int d = 0; d < 2; ++d) {
        const Frame& f = model.frames[k];
        const std::uint32_t s = topo.strip[k][d];
        const Vec3& a = d == 0 ? f.a1 : f.a2;
        const Vec3& other = d == 0 ? f.a2 : f.a1;
        const Vec3& cross3 = d == 0 ? cross[k].c9 : cross[k].c8;
        for (int c = 0; c < 3; ++c) {
          if (scale[s][c] == 0.0) continue;
          const double as = a[c] / scale[s][c];
          const double bs = other[c] / scale[s][c] * cross3[c] / 3.0;
          num[s][c] += topo.parity[k][d] * as * bs;
          den[s][c] += as * as;
        }
      }
    }
    for (std::uint32_t s = 0; s < topo.stripCount; ++s) {
      if (topo.stripPinned[s]) continue;
      values[s] = minimiser(den[s], num[s]);
      if ((den[s].array() == 0.0).any()) ++freeStrips;
    }
  } else {
    // The seed's patch generation rule: patches in breadth-first order from the seed; a
    // strip takes the single-patch least squares of the first patch that reaches it.
    std::vector<std::uint8_t> set(topo.stripCount, 0), seen(nFrames, 0);
    std::queue<std::uint32_t> queue;
    auto visit = [&](std::uint32_t k) {
      for (int d = 0; d < 2; ++d) {
        const std::uint32_t s = topo.strip[k][d];
        if (set[s]) continue;
        set[s] = 1;
        if (topo.stripPinned[s]) continue;
        const Frame& f = model.frames[k];
        const Vec3& a = d == 0 ? f.a1 : f.a2;
        values[s] = topo.parity[k][d] * (d == 0 ? ownCubic(f.a1, f.a2, cross[k].c9)
                                                : ownCubic(f.a2, f.a1, cross[k].c8));
        if ((a.array() == 0.0).any()) ++freeStrips;
      }
    };
    const std::uint32_t seed = options.seedFrame < nFrames ? options.seedFrame : 0;
    for (std::uint32_t start = 0; start <= nFrames; ++start) {
      const std::uint32_t root = start == 0 ? seed : start - 1;
      if (root >= nFrames || seen[root]) continue;
      seen[root] = 1;
      queue.push(root);
      while (!queue.empty()) {
        const std::uint32_t k = queue.front();
        queue.pop();
        visit(k);
        for (std::uint32_t e : topo.edgeOf[k])
          for (const FrameSide& fs : topo.sides(e))
            if (!seen[fs.frame]) {
              seen[fs.frame] = 1;
              queue.push(fs.frame);
            }
      }
    }
  }
  if (freeStrips > 0)
    out.notes.push_back(fmt::format(
        "{} strip(s) have a1 (or a2) = 0 in some component on every patch that decides them: "
        "the PDE does not fix their cubic coefficient there, so it is taken as 0",
        freeStrips));
  if (!topo.orientable)
    out.notes.push_back(
        "the surface is not orientable (a Möbius-like loop): normals flip somewhere");

  out.patches.resize(nFrames);
  auto forces = allForceTerms(model);
  for (std::uint32_t k = 0; k < nFrames; ++k) {
    const Vec3 c3 = topo.parity[k][0] * values[topo.strip[k][0]];
    const Vec3 c6 = topo.parity[k][1] * values[topo.strip[k][1]];
    out.patches[k].c = patchCoefficients(framePoints(model, k), c3, c6);
    out.patches[k].forces = std::move(forces[k]);
  }
  out.stripValues = std::move(values);
  return out;
}

}  // namespace pdesurf
