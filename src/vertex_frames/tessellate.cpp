// Watertight tessellation of a solved vertex-frame surface.
//
// Vertex numbering (the layout, a function of the topology and the resolution alone): first
// the corners (one per model vertex used as a frame corner), then the inner points of every
// non-collapsed edge (in the direction of the edge's first side), then each patch's interior
// grid, row after row. Boundary vertices therefore come first, and their normals are
// accumulated over the patches that meet there, then normalised.
//
// Speed: along a row (v fixed) a patch is a cubic in u once its v-powers are folded
// (foldLines), and its unnormalised normal Su × Sv, a product of two quadratics, is a quartic;
// so a row costs two polynomial evaluations per point in vectorised loops, written as floats
// straight into the mesh (interior rows are contiguous there). A row's coefficients are read
// once for all its blocks (the folds are stored so that they lie at fixed offsets); rows are
// covered by whole blocks of vector width, the last block overlapping the one before (it
// rewrites the same values), so no remainder loop. A fresh tessellation writes each row's
// triangles right after the row's vertices, so that their stores drain during the next
// row's arithmetic rather than in one burst per patch. Force terms, products of per-u and
// per-v tables, are summed per row only where a force reaches it. The boundary ring (two rows
// and two columns; a column is a row with u and v exchanged) goes through small buffers,
// since its normals are summed over patches. A Tessellator keeps the layout and the
// triangles, so that a surface re-solved on the same topology rewrites positions and
// normals only.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "pdesurf/error.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "vertex_frames/row_kernel.hpp"

namespace pdesurf {

namespace {

using detail::EvaluateLine;
using detail::foldedLine;
using detail::foldLines;
using detail::ForceTables;
using detail::kDegenerate2;
using detail::kFields;
using detail::kLanes;
using detail::lineForces;
using detail::LinePolynomials;
using detail::shapeTable;

constexpr std::uint32_t kNone = ~std::uint32_t{0};

/// Mesh points per parallel task: enough (tens of microseconds) that scheduling is noise.
constexpr std::size_t kPointsPerTask = 8192;

/// A summed boundary normal shorter than this (a sum of unit vectors) has cancelled out.
constexpr float kCancelledNormal = 1e-3f;
/// Where the normal is degenerate it is taken this far inside the patch, towards its centre.
constexpr double kNormalInset = 1e-4;

/// The monomials 1 u u² u³ v v² v³ uv u²v uv² (seed eq. 4) with u and v exchanged: a column
/// (u fixed) of a patch is a row of the patch whose coefficients are permuted so.
constexpr int kSwapUV[10] = {0, 4, 5, 6, 1, 2, 3, 7, 9, 8};

/// Grid parameters: t[i] = i/(n-1), exactly 0 and 1 at the ends.
std::vector<double> gridParams(std::uint32_t n) {
  std::vector<double> t(n);
  for (std::uint32_t i = 0; i < n; ++i) t[i] = i + 1 == n ? 1.0 : static_cast<double>(i) / (n - 1);
  return t;
}

/// Quads whose four corners are patch-interior points have ids a, a+1 (row j-1) and
/// a+inner, a+inner+1 (row j): their indices are a fixed pattern plus a running base,
/// written in blocks of kQuadBlock quads so that the loop vectorises.
constexpr std::size_t kQuadBlock = 16;

std::array<std::uint32_t, 6 * kQuadBlock> interiorQuadPattern(std::uint32_t inner, bool flip) {
  const std::uint32_t noFlip[6] = {0, 1, inner + 1, 0, inner + 1, inner};
  const std::uint32_t flipped[6] = {0, inner + 1, 1, 0, inner, inner + 1};
  std::array<std::uint32_t, 6 * kQuadBlock> pattern{};
  for (std::size_t q = 0; q < kQuadBlock; ++q)
    for (std::size_t e = 0; e < 6; ++e)
      pattern[6 * q + e] = static_cast<std::uint32_t>(q) + (flip ? flipped : noFlip)[e];
  return pattern;
}

void writeInteriorQuads(std::uint32_t a0, std::size_t count,
                        const std::array<std::uint32_t, 6 * kQuadBlock>& pattern,
                        std::uint32_t* __restrict out) {
  std::size_t q = 0;
  for (; q + kQuadBlock <= count; q += kQuadBlock) {
    const auto base = static_cast<std::uint32_t>(a0 + q);
    std::uint32_t* o = out + 6 * q;
    for (std::size_t e = 0; e < 6 * kQuadBlock; ++e) o[e] = base + pattern[e];
  }
  const auto base = static_cast<std::uint32_t>(a0 + q);
  for (std::size_t e = 0; e < 6 * (count - q); ++e) out[6 * q + e] = base + pattern[e];
}

/// Triangle (a b c), or (a c b) when flipped, at o.
inline void writeTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, bool flip,
                          std::uint32_t* o) {
  o[0] = a;
  o[1] = flip ? c : b;
  o[2] = flip ? b : c;
}

/// The two triangles of each quad (a b c d) between two rows of ids, split along a–c and
/// wound by `Flip`.
template <bool Flip>
inline void writeQuadRow(const std::uint32_t* __restrict prev, const std::uint32_t* __restrict row,
                         std::size_t quads, std::uint32_t* __restrict out) {
  for (std::size_t i = 0; i < quads; ++i) {
    const std::uint32_t a = prev[i], b = prev[i + 1], c = row[i + 1], d = row[i];
    writeTriangle(a, b, c, Flip, out + 6 * i);
    writeTriangle(a, c, d, Flip, out + 6 * i + 3);
  }
}

/// Quad (a b c d) split along b–d instead of a–c.
inline void writeQuadAlt(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                         bool flip, std::uint32_t* o) {
  writeTriangle(a, b, d, flip, o);
  writeTriangle(b, c, d, flip, o + 3);
}

/// The mesh ids of one patch's boundary, side after side (Alpha, Delta, Beta, Gamma), each
/// side's n points in the side's own direction, and what the triangle writer needs to know.
struct PatchRing {
  bool collapsedSide[4];
  /// +1 (-1) when the side's inner points are the consecutive ids ring[1], ring[1] + 1, …
  /// (ring[1], ring[1] - 1, …) of an edge that is neither a loop nor collapsed; else 0.
  std::int8_t run[4];
  bool anyCollapsed;
  bool repeatsIds;  ///< some boundary points of this patch are one mesh vertex
};

/// One boundary point of a patch's side into the mesh: its position stored (the last patch's
/// stands), its normal summed, the first normal it gets kept apart.
struct RingStore {
  const float* pos;
  const float* nor;
  const std::uint32_t* ids;
  float* __restrict positions;
  float* __restrict normals;
  float* __restrict firstNormal;
  std::uint8_t* __restrict hasFirst;

  void operator()(std::size_t q) const {
    const std::size_t o = std::size_t{ids[q]} * 3;
    if (!hasFirst[ids[q]]) {
      hasFirst[ids[q]] = 1;
      for (int comp = 0; comp < 3; ++comp) firstNormal[o + comp] = nor[3 * q + comp];
    }
    for (int comp = 0; comp < 3; ++comp) {
      positions[o + comp] = pos[3 * q + comp];
      normals[o + comp] += nor[3 * q + comp];
    }
  }
};

/// Tessellates surfaces laid out for one topology and resolution: layOut numbers the
/// vertices and the triangles (and checks that the mesh fits 32-bit indices), run writes a
/// surface's vertices, and its triangles when asked. Patches are tessellated in parallel
/// (oneTBB), each into its own ranges of the mesh; the boundary points that patches share
/// are then stored and their normals summed in patch order (storeRings: edges in parallel,
/// each point's operations in a fixed order), so the mesh is the same bytes for any number
/// of threads. Holds every buffer, so repeated runs do not allocate.
class TessellationEngine {
 public:
  void layOut(const FrameTopology& topo, std::uint32_t frames, std::uint32_t resolution);
  void run(const VertexFrameSurface& surface, Mesh& mesh, bool writeTriangles);

 private:
  PatchRing ring(const FrameTopology& topo, std::uint32_t k, std::uint32_t* ids) const;
  /// One thread's buffers.
  struct Scratch {
    std::vector<std::uint32_t> ids0, ids1;
    std::vector<float> linePos, lineNor;
    std::vector<double> lineCross2, rowCross2, rowFolds, columnFolds, forceRow;
    std::vector<ForceTables> forceTables;
  };
  /// Where the triangles of the patch being tessellated go, row by row.
  struct TriangleRows {
    std::uint32_t k;      ///< the patch
    double flip;          ///< -1 when its triangles are wound the other way
    const PatchRing* pr;  ///< its boundary ring (ids at `ring`)
    const std::uint32_t* ring;
    std::uint32_t patchBase;          ///< mesh id of its first interior point
    std::size_t triangles;            ///< the next triangle's index in the mesh
    std::uint32_t *rowIds, *prevIds;  ///< mesh ids of the last row and the one before
  };
  /// Patch k's interior points (and triangles when writeTriangles) into the mesh, its
  /// boundary ring into ringPos_ and ringNor_.
  void evaluatePatch(const VertexFrameSurface& surface, std::uint32_t k, bool writeTriangles,
                     Scratch& scratch, Mesh& mesh);
  /// The patches' boundary rings into the mesh: positions stored, normals summed (in patch
  /// order, deterministically) and normalised.
  void storeRings(Mesh& mesh);
  RingStore ringStore(std::uint32_t k, int s, Mesh& mesh);
  /// Patch k's corners (and the points of its collapsed sides, which are corners).
  void storeCorners(std::uint32_t k, Mesh& mesh);
  /// The inner points of patch k's side s, whose edge is not collapsed.
  void storeEdgeSide(std::uint32_t k, int s, Mesh& mesh);
  void writeTriangleRow(TriangleRows& rows, std::uint32_t j, std::uint32_t* indices,
                        std::uint32_t* patchIds) const;
  void fitScratch(Scratch& scratch) const;

  // The layout.
  std::uint32_t n_ = 0, inner_ = 0, frames_ = 0;
  std::size_t np_ = 0;  ///< n rounded up to whole vectors: the length of line buffers
  std::vector<std::uint32_t> cornerId_, edgeBase_;
  std::uint32_t cornerCount_ = 0, boundaryCount_ = 0, vertexCount_ = 0;
  /// Per edge, its inner points' count (from edgeBase_); and the sides (4k + s) on edges
  /// that are not collapsed, edge after edge (from edgeSideStart_), in patch and side order.
  std::vector<std::uint32_t> edgeInner_, edgeSideStart_, edgeSides_;
  std::vector<double> t_, tp_;  ///< grid parameters; tp_ padded with copies of 1
  std::array<std::uint32_t, 6 * kQuadBlock> pattern_{}, patternFlip_{};
  /// Per patch: its boundary ring's 4n mesh ids (see PatchRing) and what the ring repeats.
  std::vector<std::uint32_t> rings_;
  std::vector<PatchRing> patchRings_;
  /// Per patch, the index of its first triangle (one more entry: the mesh's count).
  std::vector<std::size_t> firstTriangle_;

  EvaluateLine evaluateLine_ = nullptr;  ///< the row kernel for this CPU (run sets it)

  /// Per patch, its four sides' points (n each, at a stride of np_): positions and unit
  /// normals, interleaved floats, as the sides' own directions run. Written before they are
  /// read (as firstNormal_), so left uninitialised (MeshBuffer).
  MeshBuffer<float> ringPos_, ringNor_;
  MeshBuffer<float> firstNormal_;
  std::vector<std::uint8_t> hasFirst_;
  tbb::enumerable_thread_specific<Scratch> scratch_;
};

void TessellationEngine::layOut(const FrameTopology& topo, std::uint32_t frames,
                                std::uint32_t resolution) {
  const std::uint32_t n = std::max<std::uint32_t>(2, resolution);
  const std::uint32_t inner = n - 2;
  std::uint32_t next = 0;
  std::uint32_t maxVertex = 0;
  for (const ModelEdge& e : topo.edges)
    maxVertex = std::max({maxVertex, e.vertices[0], e.vertices[2]});
  cornerId_.assign(std::size_t{maxVertex} + 1, kNone);
  for (std::uint32_t k = 0; k < frames; ++k)
    for (std::uint32_t e : topo.edgeOf[k])
      for (std::uint32_t v : {topo.edges[e].vertices[0], topo.edges[e].vertices[2]})
        if (cornerId_[v] == kNone) cornerId_[v] = next++;
  // Points inside an edge: none on a collapsed edge; on a loop a→m→a (pinned flat, so
  // symmetric: S(t) = S(1-t)) only the first half, its mirror image shares them.
  auto edgeInner = [&](const ModelEdge& e) -> std::uint32_t {
    if (e.collapsed()) return 0;
    return e.vertices[0] == e.vertices[2] ? (n - 1) / 2 : inner;
  };
  std::uint64_t edgePoints = 0;
  for (const ModelEdge& e : topo.edges) edgePoints += edgeInner(e);
  const std::uint64_t vertices64 =
      std::uint64_t{next} + edgePoints + std::uint64_t{frames} * inner * inner;
  const std::uint64_t triangles64 = std::uint64_t{frames} * (n - 1) * (n - 1) * 2;
  // Indices are 32-bit (as in glTF and GL): refuse meshes that do not fit.
  if (vertices64 >= kNone || triangles64 * 3 >= kNone) {
    frames_ = 0;  // no valid layout
    throw InvalidArgument(fmt::format(
        "a mesh of {} frames at resolution {} would have {} vertices and {} triangles, more "
        "than 32-bit indices can address: lower the resolution",
        frames, n, vertices64, triangles64));
  }
  cornerCount_ = next;
  edgeBase_.assign(topo.edges.size(), kNone);
  edgeInner_.assign(topo.edges.size(), 0);
  for (std::size_t e = 0; e < topo.edges.size(); ++e) {
    edgeBase_[e] = next;
    edgeInner_[e] = edgeInner(topo.edges[e]);
    next += edgeInner_[e];
  }
  // The sides on each edge with inner points, in patch and side order (a counting sort).
  edgeSideStart_.assign(topo.edges.size() + 1, 0);
  for (std::uint32_t k = 0; k < frames; ++k)
    for (std::uint32_t e : topo.edgeOf[k])
      if (edgeInner_[e] > 0) ++edgeSideStart_[e + 1];
  for (std::size_t e = 0; e < topo.edges.size(); ++e) edgeSideStart_[e + 1] += edgeSideStart_[e];
  edgeSides_.resize(edgeSideStart_.back());
  {
    std::vector<std::uint32_t> fill(edgeSideStart_.begin(), edgeSideStart_.end() - 1);
    for (std::uint32_t k = 0; k < frames; ++k)
      for (std::uint32_t s = 0; s < 4; ++s)
        if (const std::uint32_t e = topo.edgeOf[k][s]; edgeInner_[e] > 0)
          edgeSides_[fill[e]++] = 4 * k + s;
  }
  n_ = n;
  inner_ = inner;
  frames_ = frames;
  np_ = (n + kLanes - 1) / kLanes * kLanes;
  boundaryCount_ = next;
  vertexCount_ = static_cast<std::uint32_t>(vertices64);
  t_ = gridParams(n);
  tp_.assign(np_, 1.0);
  std::copy(t_.begin(), t_.end(), tp_.begin());
  pattern_ = interiorQuadPattern(inner, false);
  patternFlip_ = interiorQuadPattern(inner, true);
  rings_.resize(std::size_t{frames} * 4 * n);
  patchRings_.resize(frames);
  for (std::uint32_t k = 0; k < frames; ++k)
    patchRings_[k] = ring(topo, k, rings_.data() + std::size_t{k} * 4 * n);
  // Each patch's triangles start where the ones before end: two per quad, fewer where the
  // ring repeats ids (degenerate triangles are dropped), counted here by writing them once.
  firstTriangle_.assign(std::size_t{frames} + 1, 0);
  const std::size_t perPatch = std::size_t{2} * (n - 1) * (n - 1);
  std::vector<std::uint32_t> countIndices, countPatchIds, ids0(n), ids1(n);
  for (std::uint32_t k = 0; k < frames; ++k) {
    std::size_t count = perPatch;
    if (patchRings_[k].repeatsIds) {
      countIndices.resize(3 * perPatch);
      countPatchIds.resize(perPatch);
      const std::uint32_t patchBase = boundaryCount_ + k * inner * inner;
      TriangleRows rows{k,
                        topo.flipped[k] ? -1.0 : 1.0,
                        &patchRings_[k],
                        rings_.data() + std::size_t{k} * 4 * n,
                        patchBase,
                        0,
                        ids0.data(),
                        ids1.data()};
      for (std::uint32_t j = 0; j < n; ++j)
        writeTriangleRow(rows, j, countIndices.data(), countPatchIds.data());
      count = rows.triangles;
    }
    firstTriangle_[k + 1] = firstTriangle_[k] + count;
  }
  ringPos_.resize(std::size_t{frames} * 4 * 3 * np_);
  ringNor_.resize(std::size_t{frames} * 4 * 3 * np_);
  firstNormal_.resize(std::size_t{boundaryCount_} * 3);
  hasFirst_.resize(boundaryCount_);
}

PatchRing TessellationEngine::ring(const FrameTopology& topo, std::uint32_t k,
                                   std::uint32_t* ring) const {
  const std::uint32_t n = n_;
  PatchRing pr{};
  for (int s = 0; s < 4; ++s) {
    const std::uint32_t e = topo.edgeOf[k][s];
    const ModelEdge& edge = topo.edges[e];
    const bool rev = topo.sideReversed[k][s] != 0;
    const bool loop = edge.vertices[0] == edge.vertices[2];
    pr.collapsedSide[s] = edge.collapsed();
    pr.run[s] = static_cast<std::int8_t>(edge.collapsed() || loop ? 0 : (rev ? -1 : 1));
    pr.repeatsIds |= loop;
    for (int s2 = 0; s2 < s; ++s2) pr.repeatsIds |= topo.edgeOf[k][s2] == e;
    std::uint32_t* ids = ring + s * n;
    ids[0] = cornerId_[rev ? edge.vertices[2] : edge.vertices[0]];
    ids[n - 1] = cornerId_[rev ? edge.vertices[0] : edge.vertices[2]];
    for (std::uint32_t q = 1; q + 1 < n; ++q) {
      if (edge.collapsed())
        ids[q] = ids[0];
      else if (loop)
        ids[q] = edgeBase_[e] + std::min(q, n - 1 - q) - 1;
      else
        ids[q] = edgeBase_[e] + (rev ? n - 1 - q : q) - 1;
    }
  }
  pr.anyCollapsed =
      pr.collapsedSide[0] || pr.collapsedSide[1] || pr.collapsedSide[2] || pr.collapsedSide[3];
  const std::uint32_t corners[4] = {ring[0], ring[n - 1], ring[2 * n + n - 1], ring[2 * n]};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < a; ++b) pr.repeatsIds |= corners[a] == corners[b];
  pr.repeatsIds |= pr.anyCollapsed;
  return pr;
}

void TessellationEngine::evaluatePatch(const VertexFrameSurface& surface, std::uint32_t k,
                                       bool writeTriangles, Scratch& sc, Mesh& mesh) {
  const std::uint32_t n = n_, inner = inner_;
  const std::size_t np = np_;
  const VertexFramePatch& patch = surface.patches[k];
  const double flip = surface.topology->flipped[k] ? -1.0 : 1.0;
  const PatchRing& pr = patchRings_[k];
  const std::uint32_t* ring = rings_.data() + std::size_t{k} * 4 * n;
  const std::uint32_t patchBase = boundaryCount_ + k * inner * inner;
  TriangleRows rows{
      k, flip, &pr, ring, patchBase, firstTriangle_[k], sc.ids0.data(), sc.ids1.data()};
  TriangleRows* triangles = writeTriangles ? &rows : nullptr;
  double c[3][10], cSwapped[3][10];
  for (int comp = 0; comp < 3; ++comp)
    for (int i = 0; i < 10; ++i) {
      c[comp][i] = patch.c[i][comp];
      cSwapped[comp][i] = patch.c[kSwapUV[i]][comp];
    }
  // A bound on |Su| and |Sv| over the patch (each monomial's derivative is at most 3 on
  // the unit square, |x| ≤ 2 max|x_c| in 3D), formed from maxima so it cannot overflow
  // before the coordinates themselves would. Dividing the tangents by it keeps the cross
  // product clear of overflow and underflow and makes |Su × Sv|² a scale-free sine².
  double scale = 0.0;
  for (int i = 1; i < 10; ++i) scale += 6.0 * patch.c[i].cwiseAbs().maxCoeff();
  for (const ForceTerm& f : patch.forces)
    scale += 2.0 * M_PI * f.k.cwiseAbs().maxCoeff() /
             std::min(f.region.u1 - f.region.u0, f.region.v1 - f.region.v0);
  const double invScale = scale > 0.0 && std::isfinite(scale) ? 1.0 / scale : 1.0;
  sc.forceTables.resize(patch.forces.size());
  for (std::size_t f = 0; f < patch.forces.size(); ++f) {
    const Region& r = patch.forces[f].region;
    shapeTable(tp_, r.u0, r.u1, sc.forceTables[f].su, sc.forceTables[f].dsu);
    shapeTable(tp_, r.v0, r.v1, sc.forceTables[f].sv, sc.forceTables[f].dsv);
  }
  // Row j (column when `column`) of the patch, `count` points from parameter index `from`.
  // Every row, and the two boundary columns; Sa × Sc is Su × Sv on a row, Sv × Su on a column.
  foldLines(c, tp_.data(), n, flip, invScale, sc.rowFolds.data());
  const double columnParams[kLanes] = {0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};  // padded
  foldLines(cSwapped, columnParams, 2, -flip, invScale, sc.columnFolds.data());
  auto line = [&](bool column, std::size_t j, std::size_t from, std::size_t count, float* pos,
                  float* nor, double* cross2) {
    const LinePolynomials r = column ? foldedLine(sc.columnFolds.data(), j == 0 ? 0 : 1, -flip)
                                     : foldedLine(sc.rowFolds.data(), j, flip);
    const bool forces = lineForces(patch, sc.forceTables, column, j, np, invScale, sc.forceRow);
    return evaluateLine_(tp_.data() + from, count, r, forces ? sc.forceRow.data() + from : nullptr,
                         np, pos, nor, cross2);
  };
  // Degenerate normals: |Su × Sv| < kDegenerateNormalSine · scale² (rounding noise at a
  // pole, a cusp). Points on a collapsed side are a pole whatever rounding says. There
  // the normal is taken from just inside the patch.
  auto insetNormal = [&](std::size_t i, std::size_t j, float* out) {
    const double uu = t_[i] + kNormalInset * (0.5 - t_[i]);
    const double vv = t_[j] + kNormalInset * (0.5 - t_[j]);
    const SurfacePoint sp = patch.evaluate(uu, vv);
    Vec3 nrm = (sp.du * invScale).cross(sp.dv * invScale);
    const double nl = nrm.norm();
    nrm = nl > 0.0 ? Vec3(flip * nrm / nl) : Vec3::Zero();
    for (int comp = 0; comp < 3; ++comp) out[comp] = static_cast<float>(nrm[comp]);
  };

  // Interior rows, straight into the mesh (short rows through the line buffer), each
  // followed by the triangles between it and the row before: the triangles' stores, which
  // go to memory, then drain while the next row is computed instead of stalling in a burst.
  if (triangles) writeTriangleRow(*triangles, 0, mesh.indices.data(), mesh.patchIds.data());
  for (std::uint32_t j = 1; j + 1 < n; ++j) {
    const std::size_t first = std::size_t{patchBase + (j - 1) * inner} * 3;
    float* pos = mesh.positions.data() + first;
    float* nor = mesh.normals.data() + first;
    bool degenerate;
    if (inner >= kLanes) {
      degenerate = line(false, j, 1, inner, pos, nor, sc.rowCross2.data());
    } else {
      line(false, j, 0, np, sc.linePos.data(), sc.lineNor.data(), sc.rowCross2.data());
      std::copy_n(sc.linePos.data() + 3, 3 * inner, pos);
      std::copy_n(sc.lineNor.data() + 3, 3 * inner, nor);
      std::copy_n(sc.rowCross2.data() + 1, inner, sc.rowCross2.data());
      degenerate = true;  // checked point by point below
    }
    if (degenerate)
      for (std::uint32_t i = 0; i < inner; ++i)
        if (!(sc.rowCross2[i] > kDegenerate2)) insetNormal(i + 1, j, nor + 3 * i);
    if (triangles) writeTriangleRow(*triangles, j, mesh.indices.data(), mesh.patchIds.data());
  }
  if (triangles) writeTriangleRow(*triangles, n - 1, mesh.indices.data(), mesh.patchIds.data());

  // The boundary ring, side by side in each side's own direction (as the ring's ids run):
  // Alpha (v = 0) and Beta (v = 1) are rows, Delta (u = 1) and Gamma (u = 0) columns.
  for (int s = 0; s < 4; ++s) {
    const bool column = s == 1 || s == 3;
    const std::size_t fixed = s == 0 || s == 3 ? 0 : n - 1;
    float* pos = ringPos_.data() + (std::size_t{k} * 4 + s) * 3 * np;
    float* nor = ringNor_.data() + (std::size_t{k} * 4 + s) * 3 * np;
    double* cross2 = sc.lineCross2.data();
    const bool degenerate = line(column, fixed, 0, n >= kLanes ? n : np, pos, nor, cross2);
    auto at = [&](std::size_t q) -> std::array<std::size_t, 2> {  // grid (i, j) of point q
      return column ? std::array<std::size_t, 2>{fixed, q} : std::array<std::size_t, 2>{q, fixed};
    };
    if (degenerate || pr.collapsedSide[s])
      for (std::size_t q = 0; q < n; ++q)
        if (pr.collapsedSide[s] || !(cross2[q] > kDegenerate2))
          insetNormal(at(q)[0], at(q)[1], nor + 3 * q);
  }
}

RingStore TessellationEngine::ringStore(std::uint32_t k, int s, Mesh& mesh) {
  const std::size_t side = (std::size_t{k} * 4 + s) * 3 * np_;
  return {
      ringPos_.data() + side, ringNor_.data() + side, rings_.data() + (std::size_t{k} * 4 + s) * n_,
      mesh.positions.data(),  mesh.normals.data(),    firstNormal_.data(),
      hasFirst_.data()};
}

void TessellationEngine::storeCorners(std::uint32_t k, Mesh& mesh) {
  const std::uint32_t n = n_;
  const PatchRing& pr = patchRings_[k];
  for (int s = 0; s < 4; ++s) {
    const RingStore store = ringStore(k, s, mesh);
    // Corners come with the rows (Alpha, Beta); a collapsed side's points are its corner.
    if (s == 0 || s == 2) {
      store(0);
      store(n - 1);
    }
    if (pr.collapsedSide[s])
      for (std::size_t q = 1; q + 1 < n; ++q) store(q);
  }
}

void TessellationEngine::storeEdgeSide(std::uint32_t k, int s, Mesh& mesh) {
  const std::uint32_t n = n_, inner = inner_;
  const PatchRing& pr = patchRings_[k];
  const RingStore store = ringStore(k, s, mesh);
  if (pr.run[s] == 0) {  // a loop a→m→a: its mirrored halves share ids
    for (std::size_t q = 1; q + 1 < n; ++q) store(q);
    return;
  }
  // An edge's inner points are visited together, by the same patches in the same order:
  // one of them tells whether this is the first visit. Then whole runs, which vectorise.
  const float* pos = store.pos;
  const float* nor = store.nor;
  float* __restrict positions = store.positions;
  float* __restrict normals = store.normals;
  float* __restrict firstNormal = store.firstNormal;
  std::uint8_t* __restrict hasFirst = store.hasFirst;
  const std::size_t count = inner, o = std::size_t{store.ids[1]} * 3;
  const bool reversed = pr.run[s] < 0;
  const std::size_t start = reversed ? o - 3 * (count - 1) : o;  // lowest id's first float
  if (!hasFirst[store.ids[1]]) {
    std::fill_n(hasFirst + start / 3, count, std::uint8_t{1});
    for (std::size_t r = 0; r < count; ++r)
      for (int comp = 0; comp < 3; ++comp)
        firstNormal[start + 3 * r + comp] = nor[3 * (reversed ? count - r : r + 1) + comp];
  }
  if (reversed) {
    for (std::size_t r = 0; r < count; ++r)
      for (int comp = 0; comp < 3; ++comp) {
        positions[start + 3 * r + comp] = pos[3 * (count - r) + comp];
        normals[start + 3 * r + comp] += nor[3 * (count - r) + comp];
      }
  } else {
    for (std::size_t e = 0; e < 3 * count; ++e) {
      positions[start + e] = pos[3 + e];
      normals[start + e] += nor[3 + e];
    }
  }
}

void TessellationEngine::storeRings(Mesh& mesh) {
  // Every boundary point is either a corner or inside one edge, and its stores (position,
  // normal sum, first normal) come from the patches that touch it in patch order, side order:
  // corners in one pass over the patches, each edge's inner points from the edge's own sides
  // (edgeSides_, in that order), edges in parallel. The same operations in the same order
  // whatever the thread count, so the same bytes.
  float* __restrict normals = mesh.normals.data();
  std::fill_n(normals, std::size_t{cornerCount_} * 3, 0.0f);
  std::fill_n(hasFirst_.data(), cornerCount_, std::uint8_t{0});
  for (std::uint32_t k = 0; k < frames_; ++k) storeCorners(k, mesh);
  const auto edges = static_cast<std::uint32_t>(edgeSideStart_.size() - 1);
  const std::size_t grain =
      std::max<std::size_t>(1, kPointsPerTask / std::max<std::uint32_t>(1, n_));
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, edges, static_cast<std::uint32_t>(grain)),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      for (std::uint32_t e = range.begin(); e != range.end(); ++e) {
                        const std::uint32_t first = edgeBase_[e], count = edgeInner_[e];
                        std::fill_n(normals + std::size_t{first} * 3, std::size_t{count} * 3, 0.0f);
                        std::fill_n(hasFirst_.data() + first, count, std::uint8_t{0});
                        for (std::uint32_t i = edgeSideStart_[e]; i < edgeSideStart_[e + 1]; ++i)
                          storeEdgeSide(edgeSides_[i] / 4, static_cast<int>(edgeSides_[i] % 4),
                                        mesh);
                      }
                    });
  // Where the patches' normals cancel (the rim of a pillow, a fin folded back) no average
  // direction exists, and the first patch's normal stands for all. Branch-free: vectorises.
  const float* __restrict first = firstNormal_.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boundaryCount_, kPointsPerTask),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t v = range.begin(); v != range.end(); ++v) {
                        float* nv = normals + 3 * v;
                        const float len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
                        const bool cancelled = !(len > kCancelledNormal);
                        for (int comp = 0; comp < 3; ++comp)
                          nv[comp] = cancelled ? first[3 * v + comp] : nv[comp] / len;
                      }
                    });
}

void TessellationEngine::writeTriangleRow(TriangleRows& rows, std::uint32_t j,
                                          std::uint32_t* indices, std::uint32_t* patchIds) const {
  const std::uint32_t n = n_, inner = inner_, k = rows.k, patchBase = rows.patchBase;
  const double flip = rows.flip;
  const PatchRing& pr = *rows.pr;
  const std::uint32_t* ring = rows.ring;
  std::swap(rows.rowIds, rows.prevIds);
  std::uint32_t* rowIds = rows.rowIds;
  const std::uint32_t* prevIds = rows.prevIds;
  if (j == 0) {
    std::copy_n(ring, n, rowIds);  // Alpha
  } else if (j + 1 == n) {
    std::copy_n(ring + 2 * n, n, rowIds);  // Beta
  } else {
    rowIds[0] = ring[3 * n + j];      // Gamma
    rowIds[n - 1] = ring[1 * n + j];  // Delta
    const std::uint32_t base = patchBase + (j - 1) * inner - 1;
    // Rows next to Alpha or Beta (and all rows of small or pole patches) take the
    // generic quad writer, which reads the whole row; the pattern writer needs 4 ids.
    const bool fullRow = j == 1 || j + 2 == n || pr.repeatsIds || n < 4;
    if (fullRow) {
      for (std::uint32_t i = 1; i + 1 < n; ++i) rowIds[i] = base + i;
    } else {
      rowIds[1] = base + 1;
      rowIds[n - 2] = base + n - 2;
    }
  }

  // Triangles between row j-1 and row j: quad (prev i, prev i+1, row i+1, row i).
  if (j == 0) return;
  std::uint32_t* out = indices + rows.triangles * 3;
  std::uint32_t* outPatch = patchIds + rows.triangles;
  // The quads at corners (1,0) and (0,1) are split through the corner, so that no
  // triangle is made of boundary points alone: two frames that share both sides at a
  // corner (a pillow) would otherwise emit the same triangle twice.
  const std::uint32_t altQuad = n < 3 ? n : (j == 1 ? n - 2 : (j + 1 == n ? 0 : n));
  auto quadAt = [&](std::uint32_t i, std::uint32_t* o) {
    if (i == altQuad)
      writeQuadAlt(prevIds[i], prevIds[i + 1], rowIds[i + 1], rowIds[i], flip < 0, o);
    else if (flip < 0)
      writeQuadRow<true>(prevIds + i, rowIds + i, 1, o);
    else
      writeQuadRow<false>(prevIds + i, rowIds + i, 1, o);
  };
  if (!pr.repeatsIds) {  // no repeated ids: every quad gives two triangles
    if (j >= 2 && j + 2 <= n && n >= 4) {
      // Boundary quads at both ends, the patch-interior quads between them by pattern.
      quadAt(0, out);
      writeInteriorQuads(prevIds[1], n - 3, flip < 0 ? patternFlip_ : pattern_, out + 6);
      quadAt(n - 2, out + 6 * (n - 2));
    } else {
      if (flip < 0)
        writeQuadRow<true>(prevIds, rowIds, n - 1, out);
      else
        writeQuadRow<false>(prevIds, rowIds, n - 1, out);
      if (altQuad < n) quadAt(altQuad, out + 6 * altQuad);
    }
    std::fill_n(outPatch, 2 * (n - 1), k);
    outPatch += 2 * (n - 1);
  } else {
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
      std::uint32_t quad[6];
      quadAt(i, quad);
      for (const std::uint32_t* tri : {quad, quad + 3}) {
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
        std::copy_n(tri, 3, out);
        out += 3;
        *outPatch++ = k;
      }
    }
  }
  rows.triangles = static_cast<std::size_t>(outPatch - patchIds);
}

void TessellationEngine::run(const VertexFrameSurface& surface, Mesh& mesh, bool writeTriangles) {
  evaluateLine_ = detail::rowKernel();
  mesh.positions.resize(std::size_t{vertexCount_} * 3);
  mesh.normals.resize(std::size_t{vertexCount_} * 3);
  if (writeTriangles) {
    mesh.indices.resize(firstTriangle_[frames_] * 3);
    mesh.patchIds.resize(firstTriangle_[frames_]);
  }
  // Patches in parallel, in blocks of about kPointsPerTask points.
  const std::size_t grain = std::max<std::size_t>(1, kPointsPerTask / (std::size_t{n_} * n_));
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, frames_, grain),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      Scratch& sc = scratch_.local();
                      fitScratch(sc);
                      for (std::uint32_t k = range.begin(); k != range.end(); ++k)
                        evaluatePatch(surface, k, writeTriangles, sc, mesh);
                    });
  // The boundary points, which patches share: positions stored, normals summed and
  // normalised.
  storeRings(mesh);
}

void TessellationEngine::fitScratch(Scratch& sc) const {
  sc.ids0.resize(n_);
  sc.ids1.resize(n_);
  sc.linePos.resize(3 * np_);
  sc.lineNor.resize(3 * np_);
  sc.lineCross2.resize(np_);
  sc.rowCross2.resize(np_);
  sc.rowFolds.resize(kFields * np_);
  sc.columnFolds.resize(kFields * kLanes);
}

}  // namespace

Mesh tessellate(const VertexFrameSurface& surface, const TessellateOptions& options) {
  Mesh mesh;
  tessellate(surface, options, mesh);
  return mesh;
}

void tessellate(const VertexFrameSurface& surface, const TessellateOptions& options, Mesh& mesh) {
  checkTessellateOptions(options);
  TessellationEngine engine;
  engine.layOut(*surface.topology, static_cast<std::uint32_t>(surface.patches.size()),
                options.resolution);
  engine.run(surface, mesh, true);
}

struct Tessellator::Cache {
  TessellationEngine engine;
  std::shared_ptr<const FrameTopology> topology;  ///< held, so its address is not reused
  std::uint32_t resolution = 0;
  std::size_t frames = 0;
  bool valid = false;
};

Tessellator::Tessellator() : cache_(std::make_unique<Cache>()) {}
Tessellator::~Tessellator() = default;
Tessellator::Tessellator(Tessellator&&) noexcept = default;
Tessellator& Tessellator::operator=(Tessellator&&) noexcept = default;

const Mesh& Tessellator::tessellate(const VertexFrameSurface& surface,
                                    const TessellateOptions& options) {
  checkTessellateOptions(options);
  if (!cache_) cache_ = std::make_unique<Cache>();  // moved from
  Cache& c = *cache_;
  const bool same = c.valid && c.topology == surface.topology &&
                    c.resolution == options.resolution && c.frames == surface.patches.size();
  if (!same) {
    c.valid = false;
    c.topology.reset();
    c.engine.layOut(*surface.topology, static_cast<std::uint32_t>(surface.patches.size()),
                    options.resolution);
    ++layoutVersion_;
  }
  c.engine.run(surface, mesh_, !same);
  if (!same) {
    c.topology = surface.topology;
    c.resolution = options.resolution;
    c.frames = surface.patches.size();
    c.valid = true;
  }
  return mesh_;
}

}  // namespace pdesurf
