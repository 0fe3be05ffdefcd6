// Structure edits of vertex-frame models and new models (include/pdesurf/session.hpp): each
// builds the next model as a value and checks it as a file would be checked, so a refused
// edit changes nothing.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "io/json_reader.hpp"
#include "io/middle_mismatch.hpp"
#include "numerics/frame_lattice.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf {
namespace {

using detail::sideName;

[[noreturn]] void refuse(const std::string& path, const std::string& problem) {
  throw ModelError("edit", path, problem);
}

/// The side opposite `side` (Alpha ↔ Beta, Delta ↔ Gamma): slot i of one faces slot i of the
/// other across the frame.
Side opposite(Side side) {
  switch (side) {
    case Side::Alpha:
      return Side::Beta;
    case Side::Beta:
      return Side::Alpha;
    case Side::Delta:
      return Side::Gamma;
    default:
      return Side::Delta;
  }
}

/// A side's three vertices in the order a counter-clockwise walk round its frame meets them
/// (Alpha and Delta run that way, Beta and Gamma against it).
std::array<std::uint32_t, 3> ccwVertices(const Frame& f, Side side) {
  const auto s = sideSlots(side);
  std::array<std::uint32_t, 3> v = {f.vertices[s[0]], f.vertices[s[1]], f.vertices[s[2]]};
  if (side == Side::Beta || side == Side::Gamma) std::swap(v[0], v[2]);
  return v;
}

/// The edge of a side, refused unless it is a boundary edge (one frame) that is not a point.
std::uint32_t boundaryEdge(const VertexFrameModel& model, const FrameTopology& topology,
                           FrameSide side, const std::string& path) {
  if (side.frame >= model.frames.size())
    refuse(path, fmt::format("frame {} is out of range (the model has {} frames)", side.frame,
                             model.frames.size()));
  const std::uint32_t e = topology.edgeOf[side.frame][static_cast<int>(side.side)];
  const auto sides = topology.sides(e);
  if (sides.size() != 1) {
    const FrameSide other =
        sides[0].frame == side.frame && sides[0].side == side.side ? sides[1] : sides[0];
    refuse(path, fmt::format("side {} of frame {} is not on the boundary: frame {} shares it",
                             sideName(side.side), side.frame, other.frame));
  }
  if (topology.edges[e].collapsed())
    refuse(path, fmt::format("side {} of frame {} is a single point (a pole)", sideName(side.side),
                             side.frame));
  return e;
}

void checkFrameIndices(const VertexFrameModel& model, const std::vector<std::uint32_t>& frames,
                       const std::string& path) {
  if (frames.empty()) refuse(path, "no frames given");
  std::vector<std::uint8_t> seen(model.frames.size(), 0);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::uint32_t k = frames[i];
    const std::string at = fmt::format("{}[{}]", path, i);
    if (k >= model.frames.size())
      refuse(at, fmt::format("frame {} is out of range (the model has {} frames)", k,
                             model.frames.size()));
    if (seen[k]++) refuse(at, fmt::format("frame {} is listed twice", k));
  }
}

void checkVertexIndex(const VertexFrameModel& model, std::uint32_t v, const std::string& path) {
  if (v >= model.vertices.size())
    refuse(path, fmt::format("vertex {} is out of range (the model has {} vertices)", v,
                             model.vertices.size()));
}

/// Removes the vertices marked in `drop` (frames must no longer use them), renumbering.
void dropVertices(VertexFrameModel& model, const std::vector<std::uint8_t>& drop) {
  std::vector<std::uint32_t> newIndex(model.vertices.size());
  std::vector<Vec3> kept;
  for (std::size_t i = 0; i < model.vertices.size(); ++i) {
    newIndex[i] = static_cast<std::uint32_t>(kept.size());
    if (!drop[i]) kept.push_back(model.vertices[i]);
  }
  model.vertices = std::move(kept);
  for (Frame& f : model.frames)
    for (std::uint32_t& v : f.vertices) v = newIndex[v];
}

/// Vertices the frames use.
std::vector<std::uint8_t> usedVertices(const VertexFrameModel& model) {
  std::vector<std::uint8_t> used(model.vertices.size(), 0);
  for (const Frame& f : model.frames)
    for (std::uint32_t v : f.vertices) used[v] = 1;
  return used;
}

/// What a file would be refused for, plus what the modeller keeps out: a frame using a vertex
/// twice other than on a side collapsed to a point, and an edge of more than two frames.
void checkResult(const VertexFrameModel& next) {
  for (std::size_t k = 0; k < next.frames.size(); ++k) {
    const auto& v = next.frames[k].vertices;
    for (int i = 0; i < 8; ++i)
      for (int j = i + 1; j < 8; ++j) {
        if (v[i] != v[j]) continue;
        bool onPole = false;
        for (Side s : {Side::Alpha, Side::Delta, Side::Beta, Side::Gamma}) {
          const auto sl = sideSlots(s);
          const bool holds =
              (sl[0] == i || sl[1] == i || sl[2] == i) && (sl[0] == j || sl[1] == j || sl[2] == j);
          onPole |= holds && v[sl[0]] == v[sl[1]] && v[sl[1]] == v[sl[2]];
        }
        if (!onPole)
          refuse(fmt::format("$.frames[{}].vertices", k),
                 fmt::format("frame {} would use vertex {} twice (P{} and P{})", k, v[i], i + 1,
                             j + 1));
      }
  }
  const FrameTopology topology = buildTopology(next);
  // Said in a designer's words (the file check below would name the file's fields).
  if (topology.error.kind == TopologyError::Kind::MiddleVertexDiffers) {
    const FrameSide a = topology.error.first, b = topology.error.second;
    const detail::MiddleMismatch m = detail::middleMismatch(next, topology.error);
    refuse("", fmt::format("frames {} and {} would meet at the two ends of a side (vertices {} "
                           "and {}) but not at its middle (vertex {} of frame {}, vertex {} of "
                           "frame {}): weld the middles too, or weld the two whole edges "
                           "(select the corners of both)",
                           a.frame, b.frame, m.corner0, m.corner1, m.middleFirst, a.frame,
                           m.middleSecond, b.frame));
  }
  // Everything a file is checked for (indices, forces solvable).
  (void)parseVertexFrameModel(serializeVertexFrameModel(next), "edit");
  for (const ModelEdge& e : topology.edges)
    if (e.sideCount > 2 && !e.collapsed()) {
      const FrameSide first = topology.edgeSides[e.firstSide];
      refuse(fmt::format("$.frames[{}].vertices", first.frame),
             fmt::format("the edge through vertices {}, {}, {} would join {} frames (at most 2)",
                         e.vertices[0], e.vertices[1], e.vertices[2], e.sideCount));
    }
}

// ---------------------------------------------------------------------------------------

VertexFrameModel extrude(const VertexFrameModel& model, const FrameTopology& topology,
                         const ExtrudeEdges& e) {
  if (e.edges.empty()) refuse("$.edges", "no edges given");
  if (!(std::isfinite(e.distance) && e.distance >= 0.0))
    refuse("$.distance", fmt::format("distance {} is not a finite number ≥ 0", e.distance));
  std::vector<std::uint8_t> seen(topology.edges.size(), 0);
  // Offsets of the edges' vertices away from their frames, summed where edges meet.
  std::map<std::uint32_t, std::pair<Vec3, int>> offset;
  for (std::size_t i = 0; i < e.edges.size(); ++i) {
    const std::string path = fmt::format("$.edges[{}]", i);
    const FrameSide side = e.edges[i];
    const std::uint32_t edge = boundaryEdge(model, topology, side, path);
    if (seen[edge]++) refuse(path, "this edge is listed twice");
    const Frame& f = model.frames[side.frame];
    const auto here = sideSlots(side.side), there = sideSlots(opposite(side.side));
    for (int s = 0; s < 3; ++s) {
      Vec3 d = model.vertices[f.vertices[here[s]]] - model.vertices[f.vertices[there[s]]];
      if (e.distance > 0.0) {
        if (d.norm() == 0.0)
          refuse(path, fmt::format("frame {} has no width across side {}", side.frame,
                                   sideName(side.side)));
        d = d.normalized() * e.distance;
      }
      auto& [sum, count] = offset.try_emplace(f.vertices[here[s]], Vec3::Zero(), 0).first->second;
      sum += d, ++count;
    }
  }
  VertexFrameModel next = model;
  std::map<std::uint32_t, std::uint32_t> far, wall;  // per edge vertex: its copy, wall middle
  const auto add = [&](const Vec3& p) {
    next.vertices.push_back(p);
    return static_cast<std::uint32_t>(next.vertices.size() - 1);
  };
  std::vector<std::uint8_t> corner(model.vertices.size(), 0);  // only corners have walls
  for (const FrameSide& side : e.edges)
    for (int s : {0, 2}) corner[model.frames[side.frame].vertices[sideSlots(side.side)[s]]] = 1;
  for (const auto& [v, o] : offset) {
    const Vec3 d = o.first / o.second;
    far[v] = add(model.vertices[v] + d);
    if (corner[v]) wall[v] = add(model.vertices[v] + 0.5 * d);
  }
  for (const FrameSide& side : e.edges) {
    // The new frame is its frame moved across the edge: the edge becomes its opposite side,
    // so it faces the same way and its u and v run on as its frame's do.
    const Frame& from = model.frames[side.frame];
    const auto here = sideSlots(side.side), there = sideSlots(opposite(side.side));
    Frame f;
    f.a1 = from.a1;
    f.a2 = from.a2;
    for (int i = 0; i < 3; ++i) {
      f.vertices[there[i]] = from.vertices[here[i]];
      f.vertices[here[i]] = far[from.vertices[here[i]]];
    }
    // The two walls' middles, each between a corner of the edge and its copy.
    for (int slot = 1; slot < 8; slot += 2) {
      for (int i : {0, 2})
        if (here[i] == (slot + 1) % 8 || here[i] == (slot + 7) % 8) {
          const bool wallSlot = there[i] == (slot + 1) % 8 || there[i] == (slot + 7) % 8;
          if (wallSlot) f.vertices[slot] = wall[from.vertices[here[i]]];
        }
    }
    next.frames.push_back(std::move(f));
  }
  return next;
}

/// The edges of the topology by their two end vertices (either order): the middle vertex.
std::optional<std::uint32_t> middleOf(const FrameTopology& topology, std::uint32_t a,
                                      std::uint32_t b) {
  for (const ModelEdge& e : topology.edges)
    if ((e.vertices[0] == a && e.vertices[2] == b) || (e.vertices[0] == b && e.vertices[2] == a))
      return e.vertices[1];
  return std::nullopt;
}

VertexFrameModel addFrame(const VertexFrameModel& model, const FrameTopology& topology,
                          const AddFrame& e) {
  auto c = e.corners;
  for (int i = 0; i < 4; ++i) {
    checkVertexIndex(model, c[i], fmt::format("$.corners[{}]", i));
    for (int j = 0; j < i; ++j)
      if (c[i] == c[j])
        refuse(fmt::format("$.corners[{}]", i), fmt::format("vertex {} is given twice", c[i]));
  }
  // Reverse the corners when a shared edge runs the same way in its frame's walk: then the
  // new frame would face against its neighbour.
  const auto facesAgainst = [&] {
    for (int i = 0; i < 4; ++i)
      for (const Frame& other : model.frames)
        for (Side s : {Side::Alpha, Side::Delta, Side::Beta, Side::Gamma}) {
          const auto w = ccwVertices(other, s);
          if (w[0] == c[i] && w[2] == c[(i + 1) % 4]) return true;
        }
    return false;
  };
  if (facesAgainst()) std::reverse(c.begin() + 1, c.end());
  VertexFrameModel next = model;
  Frame f;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t a = c[i], b = c[(i + 1) % 4];
    std::uint32_t mid;
    if (const auto m = middleOf(topology, a, b)) {
      mid = *m;
    } else {
      next.vertices.push_back(0.5 * (model.vertices[a] + model.vertices[b]));
      mid = static_cast<std::uint32_t>(next.vertices.size() - 1);
    }
    f.vertices[2 * i] = a;
    f.vertices[2 * i + 1] = mid;
  }
  next.frames.push_back(std::move(f));
  return next;
}

VertexFrameModel deleteFrames(const VertexFrameModel& model, const DeleteFrames& e) {
  checkFrameIndices(model, e.frames, "$.frames");
  if (e.frames.size() == model.frames.size())
    refuse("$.frames", "a model keeps at least one frame");
  // newIndex[k]: frame k's index after, or kGone.
  constexpr std::uint32_t kGone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newIndex(model.frames.size(), 0);
  for (std::uint32_t k : e.frames) newIndex[k] = kGone;
  VertexFrameModel next;
  next.name = model.name;
  next.vertices = model.vertices;
  for (std::uint32_t k = 0; k < model.frames.size(); ++k) {
    if (newIndex[k] == kGone) continue;
    newIndex[k] = static_cast<std::uint32_t>(next.frames.size());
    next.frames.push_back(model.frames[k]);
  }
  for (const SharedForce& force : model.forces) {
    SharedForce kept;
    kept.f0 = force.f0;
    for (std::uint32_t k : force.frames)
      if (newIndex[k] != kGone) kept.frames.push_back(newIndex[k]);
    if (!kept.frames.empty()) next.forces.push_back(std::move(kept));
  }
  // The vertices only the deleted frames used go; vertices no frame used stay (a file's own).
  std::vector<std::uint8_t> drop = usedVertices(model);
  const std::vector<std::uint8_t> used = usedVertices(next);
  for (std::size_t i = 0; i < drop.size(); ++i) drop[i] = drop[i] && !used[i];
  dropVertices(next, drop);
  return next;
}

/// Merges vertices: into[v] is what v becomes (v itself when kept). The kept vertices move to
/// the mean of the vertices merged into them; the merged ones go.
VertexFrameModel mergeVertices(const VertexFrameModel& model, std::vector<std::uint32_t> into) {
  for (std::uint32_t& v : into)
    while (into[v] != v) v = into[v];
  VertexFrameModel next = model;
  std::vector<Vec3> sum(model.vertices.size(), Vec3::Zero());
  std::vector<int> count(model.vertices.size(), 0);
  for (std::size_t v = 0; v < into.size(); ++v) sum[into[v]] += model.vertices[v], ++count[into[v]];
  std::vector<std::uint8_t> drop(model.vertices.size(), 0);
  for (std::size_t v = 0; v < into.size(); ++v) {
    if (into[v] != v) drop[v] = 1;
    if (count[v] > 1) next.vertices[v] = sum[v] / count[v];
  }
  for (Frame& f : next.frames)
    for (std::uint32_t& v : f.vertices) v = into[v];
  dropVertices(next, drop);
  return next;
}

std::vector<std::uint32_t> identity(std::size_t n) {
  std::vector<std::uint32_t> into(n);
  for (std::size_t v = 0; v < n; ++v) into[v] = static_cast<std::uint32_t>(v);
  return into;
}

VertexFrameModel weldVertices(const VertexFrameModel& model, const WeldVertices& e) {
  checkVertexIndex(model, e.keep, "$.vertices[0]");
  checkVertexIndex(model, e.remove, "$.vertices[1]");
  if (e.keep == e.remove) refuse("$.vertices", "welds a vertex to itself");
  for (std::size_t k = 0; k < model.frames.size(); ++k) {
    const auto& v = model.frames[k].vertices;
    if (std::count(v.begin(), v.end(), e.keep) && std::count(v.begin(), v.end(), e.remove))
      refuse("$.vertices", fmt::format("vertices {} and {} are both on frame {}: welding them "
                                       "would fold it",
                                       e.keep, e.remove, k));
  }
  std::vector<std::uint32_t> into = identity(model.vertices.size());
  into[e.remove] = e.keep;
  return mergeVertices(model, std::move(into));
}

VertexFrameModel weldEdges(const VertexFrameModel& model, const FrameTopology& topology,
                           const WeldEdges& e) {
  const std::uint32_t first = boundaryEdge(model, topology, e.first, "$.edges[0]");
  const std::uint32_t second = boundaryEdge(model, topology, e.second, "$.edges[1]");
  if (first == second) refuse("$.edges", "welds an edge to itself");
  // Walked round their frames, the two edges must run against each other once welded.
  const auto a = ccwVertices(model.frames[e.first.frame], e.first.side);
  const auto b = ccwVertices(model.frames[e.second.frame], e.second.side);
  std::vector<std::uint32_t> into = identity(model.vertices.size());
  for (int i = 0; i < 3; ++i) {
    std::uint32_t keep = a[i], gone = b[2 - i];
    while (into[keep] != keep) keep = into[keep];
    while (into[gone] != gone) gone = into[gone];
    if (keep != gone) into[std::max(keep, gone)] = std::min(keep, gone);
  }
  return mergeVertices(model, std::move(into));
}

/// Frame `f` with its u reversed (P1..P8 mirrored, its force regions with them).
void flipU(Frame& f) {
  const auto v = f.vertices;
  f.vertices = {v[2], v[1], v[0], v[7], v[6], v[5], v[4], v[3]};  // u → 1 - u
  for (FrameForce& force : f.forces)
    force.region = {1.0 - force.region.u1, 1.0 - force.region.u0, force.region.v0, force.region.v1};
}

VertexFrameModel flipFrames(const VertexFrameModel& model, const FlipFrames& e) {
  checkFrameIndices(model, e.frames, "$.frames");
  VertexFrameModel next = model;
  for (std::uint32_t k : e.frames) flipU(next.frames[k]);
  return next;
}

VertexFrameModel mirrorFrames(const VertexFrameModel& model, const MirrorFrames& e) {
  checkFrameIndices(model, e.frames, "$.frames");
  if (e.axis < 0 || e.axis > 2) refuse("$.axis", fmt::format("axis {} is not x, y or z", e.axis));
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : model.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double onPlane = MirrorFrames::kMirrorPlaneTolerance * (hi - lo).norm();
  const auto mirrored = [&](Vec3 p) {  // a point across the plane
    p[e.axis] = 2.0 * e.at - p[e.axis];
    return p;
  };
  const auto turned = [&](Vec3 f) {  // a vector (a force) across it
    f[e.axis] = -f[e.axis];
    return f;
  };
  VertexFrameModel next = model;
  std::map<std::uint32_t, std::uint32_t> copy;  // vertex → its mirror image
  const auto image = [&](std::uint32_t v) {
    if (std::abs(model.vertices[v][e.axis] - e.at) <= onPlane) return v;  // on the seam: shared
    auto [it, fresh] = copy.try_emplace(v, 0);
    if (fresh) {
      next.vertices.push_back(mirrored(model.vertices[v]));
      it->second = static_cast<std::uint32_t>(next.vertices.size() - 1);
    }
    return it->second;
  };
  std::map<std::uint32_t, std::uint32_t> copyOf;  // frame → its copy
  for (std::uint32_t k : e.frames) {
    Frame f = model.frames[k];
    for (std::uint32_t& v : f.vertices) v = image(v);
    for (FrameForce& force : f.forces) force.f0 = turned(force.f0);
    flipU(f);  // a mirror image faces the other way: reversing u turns it back
    copyOf[k] = static_cast<std::uint32_t>(next.frames.size());
    next.frames.push_back(std::move(f));
  }
  // A shared force over mirrored frames: its mirror image over their copies.
  for (const SharedForce& force : model.forces) {
    SharedForce twin;
    twin.f0 = turned(force.f0);
    for (std::uint32_t k : force.frames)
      if (const auto it = copyOf.find(k); it != copyOf.end()) twin.frames.push_back(it->second);
    if (!twin.frames.empty()) next.forces.push_back(std::move(twin));
  }
  return next;
}

// ---------------------------------------------------------------------------------------
// Split: a loop cut through the frames across the edges it crosses.

VertexFrameModel split(const VertexFrameModel& model, const FrameTopology& topology,
                       const VertexFrameSurface& surface, const SplitFrame& e) {
  checkFrameIndices(model, e.frames, "$.frames");
  if (!e.acrossU && !e.acrossV) refuse("$.parts", "a split cuts across u, v or both");
  // cut[k][d]: frame k is cut at the middle of direction d (0: u, 1: v). A u cut crosses the
  // sides Alpha and Beta, which it halves; a neighbour on a halved edge is cut across it too.
  const std::size_t n = model.frames.size();
  std::vector<std::array<std::uint8_t, 2>> cut(n, {0, 0});
  std::vector<std::pair<std::uint32_t, int>> todo;
  const auto mark = [&](std::uint32_t k, int d) {
    if (!cut[k][d]) cut[k][d] = 1, todo.push_back({k, d});
  };
  for (std::uint32_t k : e.frames) {
    if (e.acrossU) mark(k, 0);
    if (e.acrossV) mark(k, 1);
  }
  while (!todo.empty()) {
    const auto [k, d] = todo.back();
    todo.pop_back();
    const Side crossed[2][2] = {{Side::Alpha, Side::Beta}, {Side::Gamma, Side::Delta}};
    for (Side s : crossed[d]) {
      const std::uint32_t edge = topology.edgeOf[k][static_cast<int>(s)];
      if (topology.edges[edge].collapsed()) continue;
      for (const FrameSide& other : topology.sides(edge))
        mark(other.frame, sideDirection(other.side));
    }
  }
  // Frame forces must lie inside one part of their frame (then they are the same force).
  for (std::uint32_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < model.frames[k].forces.size(); ++i) {
      const Region& r = model.frames[k].forces[i].region;
      if ((cut[k][0] && r.u0 < 0.5 && r.u1 > 0.5) || (cut[k][1] && r.v0 < 0.5 && r.v1 > 0.5))
        refuse(fmt::format("$.frames[{}].forces[{}]", k, i),
               fmt::format("the cut through frame {} would run through this force's region: "
                           "move or shrink it first",
                           k));
    }

  VertexFrameModel next = model;
  const auto add = [&](const Vec3& p) {
    next.vertices.push_back(p);
    return static_cast<std::uint32_t>(next.vertices.size() - 1);
  };
  // The quarter points of halved edges, shared by the frames on them: (edge, which quarter
  // in the edge's own direction) → vertex.
  std::map<std::pair<std::uint32_t, int>, std::uint32_t> quarter;
  std::vector<std::vector<std::uint32_t>> parts(n);  // the frames each frame became
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t nu = cut[k][0] ? 2 : 1, nv = cut[k][1] ? 2 : 1;
    if (nu == 1 && nv == 1) {
      parts[k] = {k};
      continue;
    }
    const Frame& f = model.frames[k];
    const VertexFramePatch& patch = surface.patches[k];
    // The (2nu + 1) × (2nv + 1) lattice of the parts, at u = i / 2nu, v = j / 2nv.
    const std::uint32_t cols = 2 * nu + 1, rows = 2 * nv + 1;
    std::vector<std::uint32_t> lattice(cols * rows, 0);
    for (std::uint32_t j = 0; j < rows; ++j)
      for (std::uint32_t i = 0; i < cols; ++i) {
        const double u = static_cast<double>(i) / (cols - 1),
                     v = static_cast<double>(j) / (rows - 1);
        std::uint32_t& out = lattice[j * cols + i];
        // A vertex of the frame itself: its corners and side middles.
        const auto slotAt = [&]() -> int {
          static constexpr std::array<std::array<double, 2>, 8> at = {
              {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5}, {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}}};
          for (int s = 0; s < 8; ++s)
            if (at[s][0] == u && at[s][1] == v) return s;
          return -1;
        };
        if (const int s = slotAt(); s >= 0) {
          out = f.vertices[s];
          continue;
        }
        // A part's centre (odd i and j): no frame uses it (latticeFrame leaves it out).
        if (i % 2 == 1 && j % 2 == 1) continue;
        const bool onSide = i == 0 || i == cols - 1 || j == 0 || j == rows - 1;
        if (!onSide) {
          out = add(patch.position(u, v));
          continue;
        }
        // A quarter point of a side: shared through the side's edge.
        const Side side = j == 0          ? Side::Alpha
                          : i == cols - 1 ? Side::Delta
                          : j == rows - 1 ? Side::Beta
                                          : Side::Gamma;
        const double t = sideDirection(side) == 0 ? u : v;
        const std::uint32_t edge = topology.edgeOf[k][static_cast<int>(side)];
        if (topology.edges[edge].collapsed()) {
          out = f.vertices[sideSlots(side)[1]];
          continue;
        }
        const bool reversed = topology.sideReversed[k][static_cast<int>(side)] != 0;
        const int which = (reversed ? 1.0 - t : t) < 0.5 ? 0 : 1;
        auto [it, fresh] = quarter.try_emplace({edge, which}, 0);
        if (fresh) it->second = add(patch.position(u, v));
        out = it->second;
      }
    const auto at = [&](std::uint32_t i, std::uint32_t j) { return lattice[j * cols + i]; };
    for (std::uint32_t b = 0; b < nv; ++b)
      for (std::uint32_t a = 0; a < nu; ++a) {
        Frame part = latticeFrame(at, 2 * a, 2 * b);
        // The same PDE on a part nu × nv times smaller: a1 S_uu scales by nu², a2 S_vv by nv².
        part.a1 = f.a1 * static_cast<double>(nu * nu);
        part.a2 = f.a2 * static_cast<double>(nv * nv);
        for (const FrameForce& force : f.forces) {
          const Region& r = force.region;
          const double u0 = a / static_cast<double>(nu), v0 = b / static_cast<double>(nv);
          if (r.u0 < u0 || r.u1 > u0 + 1.0 / nu || r.v0 < v0 || r.v1 > v0 + 1.0 / nv) continue;
          part.forces.push_back(
              {force.f0, {(r.u0 - u0) * nu, (r.u1 - u0) * nu, (r.v0 - v0) * nv, (r.v1 - v0) * nv}});
        }
        if (a == 0 && b == 0) {
          next.frames[k] = std::move(part);
          parts[k].push_back(k);
        } else {
          next.frames.push_back(std::move(part));
          parts[k].push_back(static_cast<std::uint32_t>(next.frames.size() - 1));
        }
      }
  }
  for (SharedForce& force : next.forces) {
    std::vector<std::uint32_t> frames;
    for (std::uint32_t k : force.frames)
      frames.insert(frames.end(), parts[k].begin(), parts[k].end());
    force.frames = std::move(frames);
  }
  return next;
}

}  // namespace

bool changesStructure(const Edit& edit) {
  return std::holds_alternative<ExtrudeEdges>(edit) || std::holds_alternative<AddFrame>(edit) ||
         std::holds_alternative<DeleteFrames>(edit) || std::holds_alternative<SplitFrame>(edit) ||
         std::holds_alternative<WeldVertices>(edit) || std::holds_alternative<WeldEdges>(edit) ||
         std::holds_alternative<FlipFrames>(edit) || std::holds_alternative<MirrorFrames>(edit);
}

VertexFrameModel restructure(const VertexFrameModel& model, const FrameTopology& topology,
                             const VertexFrameSurface& surface, const Edit& edit) {
  VertexFrameModel next = std::visit(
      [&](const auto& e) -> VertexFrameModel {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, ExtrudeEdges>) return extrude(model, topology, e);
        if constexpr (std::is_same_v<T, AddFrame>) return addFrame(model, topology, e);
        if constexpr (std::is_same_v<T, DeleteFrames>) return deleteFrames(model, e);
        if constexpr (std::is_same_v<T, SplitFrame>) return split(model, topology, surface, e);
        if constexpr (std::is_same_v<T, WeldVertices>) return weldVertices(model, e);
        if constexpr (std::is_same_v<T, WeldEdges>) return weldEdges(model, topology, e);
        if constexpr (std::is_same_v<T, FlipFrames>) return flipFrames(model, e);
        if constexpr (std::is_same_v<T, MirrorFrames>) return mirrorFrames(model, e);
        // Not a pdesurf::Error: unreachable (changesStructure chose these edits).
        throw std::logic_error("restructure: not a structure edit");
      },
      edit);
  checkResult(next);
  return next;
}

VertexFrameModel newFrameModel(const NewModelOptions& options) {
  using Kind = NewModelOptions::Kind;
  const auto fail = [](const std::string& path, const std::string& problem) {
    throw ModelError("new model", path, problem);
  };
  const std::uint32_t minU = options.kind == Kind::Tube ? 3 : 1;
  if (options.u < minU || options.u > NewModelOptions::kMaxFrames)
    fail("$.u", fmt::format("{} frames {}: expected {} to {}", options.u,
                            options.kind == Kind::Tube ? "round" : "along u", minU,
                            NewModelOptions::kMaxFrames));
  if (options.v < 1 || options.v > NewModelOptions::kMaxFrames)
    fail("$.v", fmt::format("{} frames along v: expected 1 to {}", options.v,
                            NewModelOptions::kMaxFrames));
  if (!(std::isfinite(options.size) && options.size > 0.0))
    fail("$.size", fmt::format("size {} is not a finite number above 0", options.size));
  const std::uint32_t fu = options.kind == Kind::Single ? 1 : options.u;
  const std::uint32_t fv = options.kind == Kind::Single ? 1 : options.v;
  VertexFrameModel model;
  model.name = options.name;
  const double h = 0.5 * options.size;  // lattice spacing: a frame is 2 × 2 lattice steps
  const bool tube = options.kind == Kind::Tube;
  const std::uint32_t cols = tube ? 2 * fu : 2 * fu + 1, rows = 2 * fv + 1;
  const double radius = fu * options.size / (2.0 * std::numbers::pi);
  for (std::uint32_t j = 0; j < rows; ++j)
    for (std::uint32_t i = 0; i < cols; ++i) {
      if (tube) {
        const double angle = 2.0 * std::numbers::pi * i / cols;
        model.vertices.push_back(Vec3(radius * std::cos(angle), radius * std::sin(angle), j * h));
      } else {
        model.vertices.push_back(Vec3(i * h, j * h, 0.0));
      }
    }
  const auto at = [&](std::uint32_t i, std::uint32_t j) { return j * cols + i % cols; };
  for (std::uint32_t b = 0; b < fv; ++b)
    for (std::uint32_t a = 0; a < fu; ++a) model.frames.push_back(latticeFrame(at, 2 * a, 2 * b));
  // The frames' centres are lattice points no frame uses: a new model has no such vertex.
  std::vector<std::uint8_t> unused = usedVertices(model);
  for (std::uint8_t& u : unused) u = !u;
  dropVertices(model, unused);
  return model;
}

}  // namespace pdesurf
