// A mesh rebuilt as a cross-section model (include/pdesurf/section_rebuild.hpp).
#include "pdesurf/error.hpp"
#include "pdesurf/section_rebuild.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pdesurf {

namespace {

std::string planeText(Axis axis, const MeshSection& s) {
  return fmt::format("plane {} at {}={}", s.index, axisName(axis), s.coordinate);
}

/// Distinct points of a loop (the slicer drops repeats already; this counts what is left).
std::size_t distinctPoints(const std::vector<Vec3>& points) {
  std::size_t n = points.size();
  if (n > 1 && points.front() == points.back()) --n;
  return n;
}

// --- The part between the end planes ------------------------------------------------------

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

/// A point of a clipped triangle: a mesh vertex (plane < 0) or where mesh edge (a, b),
/// a < b, meets plane 0 (lo) or 1 (hi). Points inside a triangle (a cut of a cut that is not
/// on a mesh edge) get plane 2 + a fresh number in `a`.
struct ClipPoint {
  std::uint32_t a = 0, b = 0;
  int plane = -1;
  Vec3 position = Vec3::Zero();
  auto key() const { return std::array<std::uint64_t, 3>{a, b, std::uint64_t(plane + 1)}; }
};

/// The mesh edge both points lie on, if any: {a, b} with a < b, or false.
bool commonEdge(const ClipPoint& p, const ClipPoint& q, std::uint32_t& a, std::uint32_t& b) {
  if (p.plane >= 2 || q.plane >= 2) return false;
  // The distinct mesh vertices named by the two points: exactly two make an edge.
  std::uint32_t ids[2] = {0, 0};
  int n = 0;
  auto add = [&](std::uint32_t id) {
    if ((n > 0 && ids[0] == id) || (n > 1 && ids[1] == id)) return true;
    if (n == 2) return false;
    ids[n++] = id;
    return true;
  };
  for (const ClipPoint* x : {&p, &q})
    if (!add(x->a) || (x->plane >= 0 && !add(x->b))) return false;  // a vertex names one id
  if (n != 2) return false;
  if (ids[0] > ids[1]) std::swap(ids[0], ids[1]);
  a = ids[0];
  b = ids[1];
  return true;
}

}  // namespace

TessellateOptions chainMeasureOptions(std::size_t patches) {
  TessellateOptions o;
  o.resolution =
      static_cast<std::uint32_t>(std::max<std::size_t>(3, (256 + patches - 1) / patches + 1));
  o.aroundResolution = 256;
  return o;
}

Mesh sectionedPart(const Mesh& mesh, Axis axis, std::span<const MeshSection> sections) {
  if (sections.empty()) throw InvalidArgument("no sections to take a part of the mesh by");
  const int k = static_cast<int>(axis);
  const double lo = std::min(sections.front().coordinate, sections.back().coordinate);
  const double hi = std::max(sections.front().coordinate, sections.back().coordinate);
  const std::size_t triangles = mesh.triangleCount();
  auto vertex = [&](std::uint32_t v) {
    return Vec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
  };
  // Triangles that reach into the slab, joined by shared vertices.
  std::vector<std::uint32_t> inSlab;
  UnionFind components(mesh.vertexCount());
  for (std::uint32_t t = 0; t < triangles; ++t) {
    double mn = 1e300, mx = -1e300;
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.positions[3 * mesh.indices[3 * t + c] + k];
      mn = std::min(mn, x);
      mx = std::max(mx, x);
    }
    if (mx < lo || mn > hi) continue;
    inSlab.push_back(t);
    components.join(mesh.indices[3 * t], mesh.indices[3 * t + 1]);
    components.join(mesh.indices[3 * t], mesh.indices[3 * t + 2]);
  }
  // The components the kept loops lie on: each loop's first point lies on an edge of a
  // triangle its plane cuts; the triangle nearest to it names the component.
  std::vector<std::uint8_t> keep(mesh.vertexCount(), 0);
  for (const MeshSection& s : sections) {
    const Vec3 p = s.points.front();
    double best = 1e300;
    std::uint32_t bestVertex = 0;
    for (std::uint32_t t : inSlab) {
      std::array<Vec3, 3> c;
      double mn = 1e300, mx = -1e300;
      for (int j = 0; j < 3; ++j) {
        c[j] = vertex(mesh.indices[3 * t + j]);
        mn = std::min(mn, c[j][k]);
        mx = std::max(mx, c[j][k]);
      }
      if (s.coordinate < mn || s.coordinate > mx) continue;
      // Distance from p to the triangle's edges (p lies on one of them).
      for (int j = 0; j < 3; ++j) {
        const Vec3 e = c[(j + 1) % 3] - c[j];
        const double len2 = e.squaredNorm();
        const double u = len2 > 0.0 ? std::clamp((p - c[j]).dot(e) / len2, 0.0, 1.0) : 0.0;
        const double d = (p - c[j] - u * e).norm();
        if (d < best) {
          best = d;
          bestVertex = mesh.indices[3 * t];
        }
      }
    }
    if (best < 1e300) keep[components.find(bestVertex)] = 1;
  }
  // Clip the kept triangles to lo ≤ x_k ≤ hi, welding points on mesh edges.
  Mesh part;
  std::map<std::array<std::uint64_t, 3>, std::uint32_t> ids;
  std::uint32_t fresh = 0;
  auto idOf = [&](const ClipPoint& p) {
    const auto [it, added] = ids.try_emplace(p.key(), static_cast<std::uint32_t>(ids.size()));
    if (added)
      for (int c = 0; c < 3; ++c) part.positions.push_back(static_cast<float>(p.position[c]));
    return it->second;
  };
  auto cut = [&](const ClipPoint& p, const ClipPoint& q, int plane, double at) {
    ClipPoint r;
    std::uint32_t a = 0, b = 0;
    if (commonEdge(p, q, a, b)) {
      // On mesh edge (a, b): computed from the edge itself, as its other triangle does.
      const Vec3 pa = vertex(a), pb = vertex(b);
      r.a = a;
      r.b = b;
      r.plane = plane;
      r.position = pa + (at - pa[k]) / (pb[k] - pa[k]) * (pb - pa);
    } else {
      r.a = fresh++;
      r.plane = 2;
      r.position = p.position + (at - p.position[k]) / (q.position[k] - p.position[k]) *
                                    (q.position - p.position);
    }
    r.position[k] = at;
    return r;
  };
  for (std::uint32_t t : inSlab) {
    if (!keep[components.find(mesh.indices[3 * t])]) continue;
    std::vector<ClipPoint> poly;
    for (int j = 0; j < 3; ++j) {
      ClipPoint p;
      p.a = mesh.indices[3 * t + j];
      p.position = vertex(p.a);
      poly.push_back(p);
    }
    for (int plane = 0; plane < 2 && poly.size() >= 3; ++plane) {
      const double at = plane == 0 ? lo : hi;
      auto inside = [&](const ClipPoint& p) {
        return plane == 0 ? p.position[k] >= at : p.position[k] <= at;
      };
      std::vector<ClipPoint> next;
      for (std::size_t j = 0; j < poly.size(); ++j) {
        const ClipPoint& p = poly[j];
        const ClipPoint& q = poly[(j + 1) % poly.size()];
        if (inside(p)) next.push_back(p);
        if (inside(p) != inside(q)) next.push_back(cut(p, q, plane, at));
      }
      poly = std::move(next);
    }
    if (poly.size() < 3) continue;
    std::vector<std::uint32_t> corner;
    for (const ClipPoint& p : poly) corner.push_back(idOf(p));
    for (std::size_t j = 1; j + 1 < corner.size(); ++j)
      if (corner[0] != corner[j] && corner[j] != corner[j + 1] && corner[0] != corner[j + 1])
        part.indices.insert(part.indices.end(), {corner[0], corner[j], corner[j + 1]});
  }
  return part;
}

SectionRebuild rebuildFromSections(const Mesh& mesh, const SectionRebuildOptions& options) {
  if (options.prep.points < 2 * options.modes + 1)
    throw InvalidArgument(fmt::format(
        "{} points per section cannot determine {} Fourier modes: resample to at least {} points",
        options.prep.points, options.modes, 2 * options.modes + 1));
  SectionRebuild out;
  out.sections = sliceMesh(mesh, options.slice);
  const Axis axis = options.slice.axis;
  const bool chosen = options.slice.near.has_value() || options.slice.track;
  std::vector<std::vector<Vec3>> loops;
  for (const MeshSection& s : out.sections) {
    if (!chosen && s.loops > 1)
      throw InvalidArgument(
          fmt::format("{} cuts {} closed loops (separate parts of the mesh): choose the part with "
                      "--near X Y Z, and --track to follow it from plane to plane",
                      planeText(axis, s), s.loops));
    const std::size_t n = distinctPoints(s.points);
    if (!options.exact && n < 2 * std::size_t{options.modes} + 1)
      throw InvalidArgument(fmt::format(
          "{}: the loop has {} points, too few for {} Fourier modes (at least {}): use fewer "
          "modes or a finer mesh",
          planeText(axis, s), n, options.modes, 2 * options.modes + 1));
    loops.push_back(s.points);
  }
  SectionPrepOptions prep = options.prep;
  if (!prep.direction) prep.direction = Vec3::Unit(static_cast<int>(axis));
  std::vector<SampledCurve>& prepared = out.prepared;
  try {
    prepared = prepareSections(loops, prep);
  } catch (const SectionError& e) {
    throw InvalidArgument(planeText(axis, out.sections.at(e.section())) + ": the loop " +
                          e.reason());
  }
  CrossSectionModel& model = out.model;
  model.name = options.name;
  model.description = options.description;
  model.options.a = options.a;
  model.options.modes = options.modes;
  model.options.method = ChainMethod::Global;
  model.options.remainder = options.exact;
  model.options.spacing = ChainSpacing::Centroids;
  model.options.ends = options.ends;
  // Prepared points sit at v_j = 2πj/P: the uniform parameterisation, so exact curves are
  // stored as points alone.
  model.options.parameterization = VParameterization::Uniform;
  for (const SampledCurve& c : prepared)
    if (options.exact)
      model.curves.push_back(SampledCurve{c.points, {}, true});
    else
      model.curves.push_back(fitFourier(c, options.modes).curve);
  out.chain = solve(model.curves, model.options);
  return out;
}

}  // namespace pdesurf
