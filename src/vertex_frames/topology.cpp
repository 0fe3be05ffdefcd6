// Strips, edges and orientation of a vertex-frame model (docs/derivations.md §1.4).
#include <algorithm>
#include <utility>

#include "pdesurf/vertex_frames.hpp"
#include "vertex_frames/parity_union_find.hpp"

namespace pdesurf {

std::array<int, 3> sideSlots(Side side) {
  switch (side) {
    case Side::Alpha:
      return {0, 1, 2};
    case Side::Delta:
      return {2, 3, 4};
    case Side::Beta:
      return {6, 5, 4};
    default:
      return {0, 7, 6};
  }
}

namespace {

constexpr std::array<Side, 4> kSides = {Side::Alpha, Side::Delta, Side::Beta, Side::Gamma};

/// +1 where the counter-clockwise boundary walk P1→P3→P5→P7 runs a side forwards.
int walkSign(Side side) { return (side == Side::Alpha || side == Side::Delta) ? 1 : -1; }

}  // namespace

FrameTopology buildTopology(const VertexFrameModel& model) {
  const auto nFrames = static_cast<std::uint32_t>(model.frames.size());
  FrameTopology topo;
  topo.edgeOf.resize(nFrames);
  topo.sideReversed.resize(nFrames);
  topo.edges.reserve(std::size_t{nFrames} * 2 + 4);

  // 1. Edges: sides through the same corners are one edge. Sides whose corners coincide
  //    (poles, loops) also need the same middle: a loop a→m→a is its own edge.
  //    Sides are bucketed by their lower corner (counting sort over vertices: no hashing,
  //    and memory is walked in the model's own vertex order), then grouped in each bucket.
  const std::size_t nVertices = model.vertices.size();
  std::vector<std::uint32_t> bucketStart(nVertices + 1, 0);
  auto sideCorners = [&](std::uint32_t k, int s) {
    const auto slots = sideSlots(static_cast<Side>(s));
    const auto& fv = model.frames[k].vertices;
    return std::array<std::uint32_t, 3>{fv[slots[0]], fv[slots[1]], fv[slots[2]]};
  };
  for (std::uint32_t k = 0; k < nFrames; ++k)
    for (int s = 0; s < 4; ++s) {
      const auto v = sideCorners(k, s);
      ++bucketStart[std::min(v[0], v[2]) + 1];
    }
  for (std::size_t v = 0; v < nVertices; ++v) bucketStart[v + 1] += bucketStart[v];
  std::vector<std::uint32_t> bucket(std::size_t{nFrames} * 4);  // entries: 4k + side
  {
    std::vector<std::uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (int s = 0; s < 4; ++s) {
        const auto v = sideCorners(k, s);
        bucket[fill[std::min(v[0], v[2])]++] = 4 * k + static_cast<std::uint32_t>(s);
      }
  }
  std::vector<std::uint32_t> counts;
  counts.reserve(std::size_t{nFrames} * 2 + 4);
  constexpr std::uint32_t kUnassigned = ~std::uint32_t{0};
  for (auto& e : topo.edgeOf) e.fill(kUnassigned);
  for (std::size_t v = 0; v < nVertices; ++v) {
    const std::uint32_t* first = bucket.data() + bucketStart[v];
    const std::uint32_t* last = bucket.data() + bucketStart[v + 1];
    for (const std::uint32_t* i = first; i != last; ++i) {
      const std::uint32_t k = *i / 4, s = *i % 4;
      if (topo.edgeOf[k][s] != kUnassigned) continue;
      // A new edge, led by the earliest side in frame order; gather its other sides.
      const auto lead = sideCorners(k, static_cast<int>(s));
      const std::uint32_t other = std::max(lead[0], lead[2]);
      const bool loop = lead[0] == lead[2];
      const auto id = static_cast<std::uint32_t>(topo.edges.size());
      ModelEdge edge;
      edge.vertices = lead;
      topo.edges.push_back(edge);
      counts.push_back(0);
      for (const std::uint32_t* j = i; j != last; ++j) {
        const std::uint32_t kj = *j / 4, sj = *j % 4;
        const auto c = sideCorners(kj, static_cast<int>(sj));
        if (std::max(c[0], c[2]) != other || topo.edgeOf[kj][sj] != kUnassigned) continue;
        if (loop && c[1] != lead[1]) continue;  // another loop at the same vertex
        if (c[1] != lead[1] && topo.error.kind == TopologyError::Kind::None) {
          topo.error.kind = TopologyError::Kind::MiddleVertexDiffers;
          topo.error.first = {k, static_cast<Side>(s)};
          topo.error.second = {kj, static_cast<Side>(sj)};
        }
        topo.edgeOf[kj][sj] = id;
        topo.sideReversed[kj][sj] = static_cast<std::uint8_t>(!loop && c[0] != lead[0]);
        ++counts[id];
      }
    }
  }
  // Lay the sides out edge after edge, each edge's in frame order.
  std::uint32_t offset = 0;
  for (std::size_t e = 0; e < topo.edges.size(); ++e) {
    topo.edges[e].firstSide = offset;
    topo.edges[e].sideCount = 0;
    offset += counts[e];
  }
  topo.edgeSides.resize(offset);
  topo.edgeSideReversed.resize(offset);
  for (std::uint32_t k = 0; k < nFrames; ++k)
    for (Side s : kSides) {
      const auto si = static_cast<std::size_t>(s);
      ModelEdge& e = topo.edges[topo.edgeOf[k][si]];
      const std::uint32_t at = e.firstSide + e.sideCount++;
      topo.edgeSides[at] = {k, s};
      topo.edgeSideReversed[at] = topo.sideReversed[k][si];
    }

  // 2. Strips: node 2k+d is frame k's cubic coefficient in direction d. Sides on one edge
  //    have equal cubics, negated when they run the edge in opposite directions.
  //    Edges with coinciding corners pin their strip: only 0 keeps a pole a point and a
  //    loop the same curve whichever way a patch runs it.
  detail::ParityUnionFind strips(std::size_t{nFrames} * 2);
  detail::ParityUnionFind orient(nFrames);
  for (std::uint32_t e = 0; e < topo.edges.size(); ++e) {
    const auto sides = topo.sides(e);
    const auto reversed = topo.reversed(e);
    const FrameSide first = sides.front();
    const std::uint32_t n0 = 2 * first.frame + sideDirection(first.side);
    if (topo.edges[e].vertices[0] == topo.edges[e].vertices[2]) {
      for (const FrameSide& fs : sides) strips.markConflict(2 * fs.frame + sideDirection(fs.side));
      continue;  // no orientation constraint across a point or a loop
    }
    const int walk0 = walkSign(first.side);
    for (std::size_t i = 1; i < sides.size(); ++i) {
      const FrameSide fs = sides[i];
      const std::int8_t rel = reversed[i] ? -1 : 1;
      strips.unite(n0, 2 * fs.frame + sideDirection(fs.side), rel);
      // Consistently oriented neighbours walk a shared edge in opposite directions.
      const int walk = walkSign(fs.side) * rel;
      orient.unite(first.frame, fs.frame, static_cast<std::int8_t>(-walk0 * walk));
    }
  }

  // 3. Number the strips densely, in order of first appearance.
  topo.strip.resize(nFrames);
  topo.parity.resize(nFrames);
  std::vector<std::uint32_t> id(std::size_t{nFrames} * 2, ~std::uint32_t{0});
  for (std::uint32_t node = 0; node < 2 * nFrames; ++node) {
    const auto r = strips.find(node);
    if (id[r.root] == ~std::uint32_t{0}) {
      id[r.root] = topo.stripCount++;
      topo.stripPinned.push_back(static_cast<std::uint8_t>(strips.conflicting(node)));
    }
    topo.strip[node / 2][node % 2] = id[r.root];
    topo.parity[node / 2][node % 2] = r.sign;
  }

  topo.flipped.resize(nFrames);
  for (std::uint32_t k = 0; k < nFrames; ++k) {
    topo.flipped[k] = static_cast<std::uint8_t>(orient.find(k).sign < 0);
    if (orient.conflicting(k)) topo.orientable = false;
  }
  return topo;
}

}  // namespace pdesurf
