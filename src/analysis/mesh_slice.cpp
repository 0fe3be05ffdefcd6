// Cross sections of triangle meshes: planes perpendicular to an axis, loops welded by edge.
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/error.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace pdesurf {
namespace {

int axisIndex(Axis axis) { return static_cast<int>(axis); }

/// The plane's in-plane coordinates (u, w) such that (u, w, axis) is right-handed: a loop
/// with positive shoelace area in (u, w) turns counter-clockwise seen from +axis.
std::pair<int, int> planeAxes(Axis axis) {
  const int k = axisIndex(axis);
  return {(k + 1) % 3, (k + 2) % 3};
}

/// A mesh edge as one number: its vertex indices, smaller first.
std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// A plane's cut before loops are traced: one node per crossed mesh edge (where the plane
/// meets it) and one directed segment per crossed triangle.
struct PlaneCut {
  std::vector<Vec3> nodes;
  std::vector<std::array<std::uint32_t, 2>> segments;  ///< node from, node to
};

/// The section of the plane p[axis] = c. `above[v]` says on which side vertex v counts.
PlaneCut cutMesh(const Mesh& mesh, int k, double c, const std::vector<std::uint8_t>& above) {
  PlaneCut cut;
  std::unordered_map<std::uint64_t, std::uint32_t> nodeOfEdge;
  auto position = [&](std::uint32_t v) {
    return Vec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
  };
  // The node of edge (a, b), computed once from the edge's lower end, so that both triangles
  // of an edge share it exactly. A vertex on the plane is its own intersection point.
  auto node = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, fresh] =
        nodeOfEdge.try_emplace(edgeKey(a, b), static_cast<std::uint32_t>(cut.nodes.size()));
    if (fresh) {
      if (above[a]) std::swap(a, b);
      const Vec3 pa = position(a), pb = position(b);
      Vec3 p;
      if (pa[k] == c) {
        p = pa;
      } else if (pb[k] == c) {
        p = pb;
      } else {
        const double t = (c - pa[k]) / (pb[k] - pa[k]);  // in (0, 1): pa[k] < c < pb[k]
        p = pa + t * (pb - pa);
        p[k] = c;
      }
      cut.nodes.push_back(p);
    }
    return it->second;
  };
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* v = &mesh.indices[3 * t];
    const int up = above[v[0]] + above[v[1]] + above[v[2]];
    if (up == 0 || up == 3) continue;
    // The corner alone on its side, and its neighbours in the triangle's order.
    const bool loneAbove = up == 1;
    int i = 0;
    while ((above[v[i]] != 0) != loneAbove) ++i;
    const std::uint32_t lone = v[i], next = v[(i + 1) % 3], prev = v[(i + 2) % 3];
    // Seen from +axis, an outward-facing triangle's segment runs counter-clockwise round
    // the solid: from edge (lone, next) to edge (prev, lone) when the lone corner is above.
    std::uint32_t from = node(lone, next), to = node(prev, lone);
    if (!above[lone]) std::swap(from, to);
    if (from != to) cut.segments.push_back({from, to});  // equal only for repeated corners
  }
  return cut;
}

struct Loops {
  std::vector<std::vector<std::uint32_t>> closed;  ///< node sequences, closed implicitly
  std::size_t openChains = 0;
};

/// Traces the segments into chains. At a node with more than two segments (a non-manifold
/// edge) the walk takes an unused segment leaving the node if there is one, else any.
Loops traceLoops(const PlaneCut& cut) {
  const std::size_t n = cut.nodes.size();
  // Incident segments of each node (compressed rows).
  std::vector<std::uint32_t> start(n + 1, 0), incident(2 * cut.segments.size());
  for (const auto& s : cut.segments) ++start[s[0] + 1], ++start[s[1] + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t s = 0; s < cut.segments.size(); ++s)
    for (std::uint32_t end : cut.segments[s]) incident[fill[end]++] = s;

  std::vector<std::uint8_t> used(cut.segments.size(), 0);
  // An unused segment at `node`, and the node at its other end; leaving segments first.
  auto step = [&](std::uint32_t node) -> std::pair<std::uint32_t, std::uint32_t> {
    std::uint32_t fallback = std::numeric_limits<std::uint32_t>::max();
    for (std::uint32_t r = start[node]; r < start[node + 1]; ++r) {
      const std::uint32_t s = incident[r];
      if (used[s]) continue;
      if (cut.segments[s][0] == node) return {s, cut.segments[s][1]};
      if (fallback == std::numeric_limits<std::uint32_t>::max()) fallback = s;
    }
    if (fallback == std::numeric_limits<std::uint32_t>::max()) return {fallback, node};
    return {fallback, cut.segments[fallback][0]};
  };

  Loops loops;
  for (std::uint32_t s0 = 0; s0 < cut.segments.size(); ++s0) {
    if (used[s0]) continue;
    used[s0] = 1;
    const std::uint32_t first = cut.segments[s0][0];
    std::vector<std::uint32_t> chain = {first, cut.segments[s0][1]};
    bool closed = false;
    while (true) {
      const auto [s, other] = step(chain.back());
      if (s == std::numeric_limits<std::uint32_t>::max()) break;
      used[s] = 1;
      if (other == first) {
        closed = true;
        break;
      }
      chain.push_back(other);
    }
    if (closed) {
      loops.closed.push_back(std::move(chain));
      continue;
    }
    // An open chain: consume the rest of it backwards from its first node.
    for (std::uint32_t node = first;;) {
      const auto [s, other] = step(node);
      if (s == std::numeric_limits<std::uint32_t>::max()) break;
      used[s] = 1;
      node = other;
    }
    ++loops.openChains;
  }
  return loops;
}

/// Shoelace area of a closed polyline in the plane's (u, w) coordinates, about its first
/// point (which keeps the products small).
double signedArea(const std::vector<Vec3>& points, std::pair<int, int> uw) {
  const auto [u, w] = uw;
  double twice = 0.0;
  const Vec3& o = points.front();
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    twice += (points[i][u] - o[u]) * (points[i + 1][w] - o[w]) -
             (points[i + 1][u] - o[u]) * (points[i][w] - o[w]);
  return 0.5 * twice;
}

/// Area centroid of a counter-clockwise closed polyline of (positive) `area` in the plane's
/// (u, w) coordinates; the axis coordinate is the polyline's own.
Vec3 areaCentroid(const std::vector<Vec3>& points, std::pair<int, int> uw, double area) {
  const auto [u, w] = uw;
  const Vec3& o = points.front();
  double cu = 0.0, cw = 0.0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const double au = points[i][u] - o[u], aw = points[i][w] - o[w];
    const double bu = points[i + 1][u] - o[u], bw = points[i + 1][w] - o[w];
    const double cross = au * bw - bu * aw;  // twice the signed area of (o, a, b)
    cu += cross * (au + bu);
    cw += cross * (aw + bw);
  }
  Vec3 c = o;
  c[u] += cu / (6.0 * area);
  c[w] += cw / (6.0 * area);
  return c;
}

/// Distance between two points projected onto the plane (the axis coordinate ignored).
double inPlaneDistance(const Vec3& a, const Vec3& b, std::pair<int, int> uw) {
  return std::hypot(a[uw.first] - b[uw.first], a[uw.second] - b[uw.second]);
}

std::string extentText(Axis axis, double lo, double hi) {
  return fmt::format("extent {} in [{}, {}]", axisName(axis), lo, hi);
}

}  // namespace

const char* axisName(Axis axis) {
  static constexpr const char* kNames[] = {"x", "y", "z"};  // in the order of Axis
  const auto index = static_cast<std::size_t>(axis);
  return index < std::size(kNames) ? kNames[index] : "?";
}

std::optional<Axis> parseAxis(const std::string& name) {
  if (name == "x" || name == "X") return Axis::X;
  if (name == "y" || name == "Y") return Axis::Y;
  if (name == "z" || name == "Z") return Axis::Z;
  return std::nullopt;
}

std::vector<double> slicePlanes(const SliceOptions& options, double lo, double hi) {
  const std::uint32_t count = options.count;
  if (count == 0) throw InvalidArgument("slicing needs at least one plane (count is 0)");
  std::vector<double> planes(count);
  if (!options.range) {
    for (std::uint32_t i = 0; i < count; ++i)
      planes[i] = lo + (i + 0.5) * (hi - lo) / static_cast<double>(count);
    return planes;
  }
  const auto [a, b] = *options.range;
  if (!std::isfinite(a) || !std::isfinite(b) || a > b || (a == b && count > 1))
    throw InvalidArgument(fmt::format(
        "slicing range [{}, {}]: needs finite a < b (a = b only for a single plane)", a, b));
  if (count == 1) return {0.5 * (a + b)};
  for (std::uint32_t i = 0; i < count; ++i)
    planes[i] = i + 1 == count ? b : a + (b - a) * (static_cast<double>(i) / (count - 1));
  return planes;
}

std::vector<MeshSection> sliceMesh(const Mesh& mesh, const SliceOptions& options) {
  const int k = axisIndex(options.axis);
  const char* name = axisName(options.axis);
  if (options.near && !options.near->allFinite())
    throw InvalidArgument(fmt::format("slicing near ({}, {}, {}): the point is not finite",
                                      options.near->x(), options.near->y(), options.near->z()));
  if (mesh.triangleCount() == 0) throw MeshSliceError("cannot slice a mesh with no triangles");
  // The extent along the axis, over the vertices that triangles use.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::uint32_t v : mesh.indices) {
    assert(v < mesh.vertexCount());
    lo = std::min(lo, double{mesh.positions[3 * v + k]});
    hi = std::max(hi, double{mesh.positions[3 * v + k]});
  }
  if (!(lo < hi))
    throw MeshSliceError(fmt::format(
        "the mesh is flat along {} ({}): no plane perpendicular to {} cuts it in a loop", name,
        extentText(options.axis, lo, hi), name));
  const std::vector<double> planes = slicePlanes(options, lo, hi);
  const std::pair<int, int> uw = planeAxes(options.axis);

  // Each plane's closed loops, planes in parallel (a plane's cut depends on nothing else);
  // then, in plane order, the first failure is reported and one loop kept per plane (as
  // tracking needs the previous plane's choice): the same result for any thread count.
  struct PlaneLoops {
    std::vector<MeshSection> candidates;
    std::string error;  ///< why the plane has no loop, if it has none
  };
  auto cutPlane = [&](std::uint32_t i, std::vector<std::uint8_t>& above) {
    const double c = planes[i];
    PlaneLoops result;
    auto fail = [&](const std::string& what) {
      result.error = fmt::format("plane {} at {}={} {} ({})", i, name, c, what,
                                 extentText(options.axis, lo, hi));
      return result;
    };
    if (c < lo || c > hi) return fail("does not meet the mesh");
    // Symbolic perturbation: vertices on the plane count as above, except at the lowest
    // coordinate, where nothing would be below them.
    const bool onPlaneAbove = c != lo;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
      const double x = mesh.positions[3 * v + k];
      above[v] = x > c || (x == c && onPlaneAbove);
    }
    const PlaneCut cut = cutMesh(mesh, k, c, above);
    if (cut.segments.empty())
      return fail("cuts no triangle of the mesh (it passes between its parts)");
    const Loops loops = traceLoops(cut);

    // Every closed loop, counter-clockwise, with its area and centroid.
    std::vector<MeshSection>& candidates = result.candidates;
    std::size_t degenerate = 0;
    for (const auto& chain : loops.closed) {
      MeshSection loop;
      std::vector<Vec3>& points = loop.points;
      points.reserve(chain.size());
      for (std::uint32_t node : chain)
        if (points.empty() || cut.nodes[node] != points.back()) points.push_back(cut.nodes[node]);
      while (points.size() > 1 && points.back() == points.front()) points.pop_back();
      const double area = points.size() < 3 ? 0.0 : signedArea(points, uw);
      if (area == 0.0) {
        ++degenerate;
        continue;
      }
      if (area < 0.0) std::reverse(points.begin(), points.end());
      loop.area = std::abs(area);
      loop.centroid = areaCentroid(points, uw, loop.area);
      candidates.push_back(std::move(loop));
    }
    if (candidates.empty())
      return fail(
          fmt::format("has no closed loop: the section is {} open chain{} and {} degenerate loop{} "
                      "(the mesh is open or only touches the plane there)",
                      loops.openChains, loops.openChains == 1 ? "" : "s", degenerate,
                      degenerate == 1 ? "" : "s"));
    return result;
  };
  std::vector<PlaneLoops> cuts(planes.size());
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(planes.size())),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      std::vector<std::uint8_t> above(mesh.vertexCount());
                      for (std::uint32_t i = range.begin(); i != range.end(); ++i)
                        cuts[i] = cutPlane(i, above);
                    });

  std::vector<MeshSection> sections;
  sections.reserve(planes.size());
  for (std::uint32_t i = 0; i < planes.size(); ++i) {
    if (!cuts[i].error.empty()) throw MeshSliceError(cuts[i].error);
    std::vector<MeshSection>& candidates = cuts[i].candidates;
    const double c = planes[i];
    // The target the kept loop's centroid should be nearest to, if any.
    std::optional<Vec3> target;
    if (options.track && !sections.empty())
      target = sections.back().centroid;
    else if (options.near)
      target = *options.near;
    std::size_t pick = 0;
    for (std::size_t j = 1; j < candidates.size(); ++j) {
      if (target) {
        if (inPlaneDistance(candidates[j].centroid, *target, uw) <
            inPlaneDistance(candidates[pick].centroid, *target, uw))
          pick = j;
      } else if (candidates[j].area > candidates[pick].area) {
        pick = j;
      }
    }
    MeshSection best = std::move(candidates[pick]);
    best.loops = static_cast<std::uint32_t>(candidates.size());
    best.index = i;
    best.coordinate = c;
    for (std::size_t p = 0; p < best.points.size(); ++p)
      best.length += (best.points[(p + 1) % best.points.size()] - best.points[p]).norm();
    sections.push_back(std::move(best));
  }
  return sections;
}

}  // namespace pdesurf
