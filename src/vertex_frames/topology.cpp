// Strips, edges and orientation of a vertex-frame model (math-notes §1, "strips").
#include <algorithm>
#include <bit>
#include <map>
#include <utility>

#include "pdesurf/vertex_frames.hpp"
#include "vertex_frames/parity_union_find.hpp"

namespace pdesurf {

std::array<int, 3> sideSlots(Side side) {
  switch (side) {
    case Side::Alpha: return {0, 1, 2};
    case Side::Delta: return {2, 3, 4};
    case Side::Beta: return {6, 5, 4};
    default: return {0, 7, 6};
  }
}

namespace {

constexpr std::array<Side, 4> kSides = {Side::Alpha, Side::Delta, Side::Beta, Side::Gamma};

/// +1 where the counter-clockwise boundary walk P1→P3→P5→P7 runs a side forwards.
int walkSign(Side side) { return (side == Side::Alpha || side == Side::Delta) ? 1 : -1; }

/// Open-addressing map from an unordered corner pair to an edge index: the hot part of
/// topology building for large models, so no node allocations.
class EdgeTable {
 public:
  explicit EdgeTable(std::size_t expected) {
    const std::size_t cap = std::bit_ceil(std::max<std::size_t>(16, expected * 2));
    keys_.assign(cap, kEmpty);
    values_.resize(cap);
    mask_ = cap - 1;
  }
  /// The slot value for `key`, inserting `fresh` when absent; second = inserted.
  std::pair<std::uint32_t, bool> findOrInsert(std::uint64_t key, std::uint32_t fresh) {
    std::size_t i = hash(key) & mask_;
    while (true) {
      if (keys_[i] == key) return {values_[i], false};
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        values_[i] = fresh;
        return {fresh, true};
      }
      i = (i + 1) & mask_;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  static std::size_t hash(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return static_cast<std::size_t>(k);
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t mask_ = 0;
};

}  // namespace

FrameTopology buildTopology(const VertexFrameModel& model) {
  const auto nFrames = static_cast<std::uint32_t>(model.frames.size());
  FrameTopology topo;
  topo.edgeOf.resize(nFrames);
  topo.sideReversed.resize(nFrames);
  topo.edges.reserve(std::size_t{nFrames} * 2 + 4);

  // 1. Edges: sides through the same corners are one edge. Sides whose corners coincide
  //    (poles, loops) are keyed by their middle vertex too: a loop a→m→a is its own edge.
  EdgeTable table(std::size_t{nFrames} * 4);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> loops;
  for (std::uint32_t k = 0; k < nFrames; ++k) {
    const auto& fv = model.frames[k].vertices;
    for (Side s : kSides) {
      const auto slots = sideSlots(s);
      const std::uint32_t a = fv[slots[0]], m = fv[slots[1]], b = fv[slots[2]];
      const auto fresh = static_cast<std::uint32_t>(topo.edges.size());
      std::pair<std::uint32_t, bool> found;
      if (a == b) {
        auto [it, inserted] = loops.try_emplace({a, m}, fresh);
        found = {it->second, inserted};
      } else {
        const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
        found = table.findOrInsert(key, fresh);
      }
      const auto si = static_cast<std::size_t>(s);
      topo.edgeOf[k][si] = found.first;
      if (found.second) {
        ModelEdge e;
        e.vertices = {a, m, b};
        topo.edges.push_back(std::move(e));
      }
      ModelEdge& e = topo.edges[found.first];
      if (e.vertices[1] != m && topo.error.kind == TopologyError::Kind::None) {
        topo.error.kind = TopologyError::Kind::MiddleVertexDiffers;
        topo.error.first = e.sides.front();
        topo.error.second = {k, s};
      }
      const bool reversed = a != b && e.vertices[0] != a;
      e.sides.push_back({k, s});
      e.reversed.push_back(static_cast<std::uint8_t>(reversed));
      topo.sideReversed[k][si] = static_cast<std::uint8_t>(reversed);
    }
  }

  // 2. Strips: node 2k+d is frame k's cubic coefficient in direction d. Sides on one edge
  //    have equal cubics, negated when they run the edge in opposite directions.
  //    Edges with coinciding corners pin their strip: only 0 keeps a pole a point and a
  //    loop the same curve whichever way a patch runs it.
  detail::ParityUnionFind strips(std::size_t{nFrames} * 2);
  detail::ParityUnionFind orient(nFrames);
  for (const ModelEdge& e : topo.edges) {
    const FrameSide first = e.sides.front();
    const std::uint32_t n0 = 2 * first.frame + sideDirection(first.side);
    if (e.vertices[0] == e.vertices[2]) {
      for (const FrameSide& fs : e.sides) strips.markConflict(2 * fs.frame + sideDirection(fs.side));
      continue;  // no orientation constraint across a point or a loop
    }
    const int walk0 = walkSign(first.side);
    for (std::size_t i = 1; i < e.sides.size(); ++i) {
      const FrameSide fs = e.sides[i];
      const std::int8_t rel = e.reversed[i] ? -1 : 1;
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
