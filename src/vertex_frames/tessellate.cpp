// Watertight tessellation of a solved vertex-frame surface.
//
// Vertex numbering: first the corners (one per model vertex used as a frame corner), then
// the inner points of every non-collapsed edge (in the direction of the edge's first
// side), then each patch's interior grid. Boundary vertices therefore come first, and
// their normals are accumulated over the patches that meet there, then normalised.
//
// Speed: a patch is a cubic in u per row once its v-powers are folded (foldRow), so each
// row is one fused, vectorised loop (position, both derivatives, the unit normal, written
// as floats) over a row padded to whole vector registers; force terms, products of per-u
// and per-v tables, are summed per row only where a force reaches it. Interior rows of a
// patch are contiguous in the mesh and are copied there whole.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "pdesurf/vertex_frames.hpp"
#include "vertex_frames/force_shape.hpp"

namespace pdesurf {

namespace {

constexpr std::uint32_t kNone = ~std::uint32_t{0};

/// Doubles in one vector register (AVX-512 holds 8; rows padded to this suit AVX2 too).
constexpr std::size_t kLanes = 8;

/// A normal counts as degenerate (a pole, a cusp) when |Su × Sv| is below this fraction of
/// the patch's squared size: far below any real surface, far above rounding noise (1e-16).
constexpr double kDegenerateNormalSine = 1e-10;
/// A summed boundary normal shorter than this (a sum of unit vectors) has cancelled out.
constexpr float kCancelledNormal = 1e-3f;
/// Where the normal is degenerate it is taken this far inside the patch, towards its centre.
constexpr double kNormalInset = 1e-4;

/// Grid parameters: t[i] = i/(n-1), exactly 0 and 1 at the ends.
std::vector<double> gridParams(std::uint32_t n) {
  std::vector<double> t(n);
  for (std::uint32_t i = 0; i < n; ++i) t[i] = i + 1 == n ? 1.0 : static_cast<double>(i) / (n - 1);
  return t;
}

/// The force shape and its derivative sampled on the grid.
void shapeTable(const std::vector<double>& grid, double x0, double x1, std::vector<double>& s,
                std::vector<double>& ds) {
  s.resize(grid.size());
  ds.resize(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const detail::ForceShape f = detail::forceShape(grid[i], x0, x1);
    s[i] = f.s;
    ds[i] = f.ds;
  }
}

/// Per-u and per-v tables of each force of a patch, on the padded grid.
struct ForceTables {
  std::vector<double> su, dsu, sv, dsv;
};

/// The summed force terms of row j, as 9 rows of np values (position, ∂u, ∂v; x y z
/// each): Σ k ⊙ (s(u) s(v), s'(u) s(v), s(u) s'(v)). False when no force reaches row j.
bool rowForces(const VertexFramePatch& patch, const std::vector<ForceTables>& tables, std::size_t j,
               std::size_t np, std::vector<double>& out) {
  bool any = false;
  for (std::size_t f = 0; f < patch.forces.size(); ++f) {
    const ForceTables& ft = tables[f];
    if (ft.sv[j] == 0.0 && ft.dsv[j] == 0.0) continue;
    if (!any) out.assign(9 * np, 0.0);
    any = true;
    for (int c = 0; c < 3; ++c) {
      const double kv = patch.forces[f].k[c] * ft.sv[j], kdv = patch.forces[f].k[c] * ft.dsv[j];
      double* p = out.data() + c * np;
      double* du = out.data() + (3 + c) * np;
      double* dv = out.data() + (6 + c) * np;
      for (std::size_t i = 0; i < np; ++i) {
        p[i] += kv * ft.su[i];
        du[i] += kv * ft.dsu[i];
        dv[i] += kdv * ft.su[i];
      }
    }
  }
  return any;
}

/// Row j of a patch folded over its v-powers, per component: S = Σ_i p[i] u^i,
/// Su = Σ_i du[i] u^i, Sv = Σ_i dv[i] u^i (cubic, quadratic and quadratic in u).
struct RowPolynomials {
  double p[3][4], du[3][3], dv[3][3];
};

RowPolynomials foldRow(const double (&c)[3][10], double v) {
  RowPolynomials r;
  const double v2 = v * v, v3 = v2 * v;
  for (int k = 0; k < 3; ++k) {
    const double* a = c[k];  // monomials 1 u u² u³ v v² v³ uv u²v uv² (seed eq. 4)
    r.p[k][0] = a[0] + v * a[4] + v2 * a[5] + v3 * a[6];
    r.p[k][1] = a[1] + v * a[7] + v2 * a[9];
    r.p[k][2] = a[2] + v * a[8];
    r.p[k][3] = a[3];
    r.du[k][0] = r.p[k][1];
    r.du[k][1] = 2.0 * r.p[k][2];
    r.du[k][2] = 3.0 * a[3];
    r.dv[k][0] = a[4] + 2.0 * v * a[5] + 3.0 * v2 * a[6];
    r.dv[k][1] = a[7] + 2.0 * v * a[9];
    r.dv[k][2] = a[8];
  }
  return r;
}

/// S and the unit normal flip·(Su×Sv)/|Su×Sv| at `count` points u[i] of one row, plus
/// force terms (9 arrays at `forceStride`: position, ∂u, ∂v; x y z each) when Forces.
/// Writes positions and normals as interleaved floats and |Su×Sv|² for degeneracy checks.
/// One function with restrict parameters so that the compiler vectorises the loop.
template <bool Forces>
void evaluateRow(const double* __restrict u, std::size_t count, const RowPolynomials& r,
                 const double* __restrict force, std::size_t forceStride, double flip,
                 double invScale, float* __restrict pos, float* __restrict nor,
                 double* __restrict cross2) {
  for (std::size_t i = 0; i < count; ++i) {
    const double x = u[i];
    double p[3], du[3], dv[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = r.p[k][0] + x * (r.p[k][1] + x * (r.p[k][2] + x * r.p[k][3]));
      du[k] = r.du[k][0] + x * (r.du[k][1] + x * r.du[k][2]);
      dv[k] = r.dv[k][0] + x * (r.dv[k][1] + x * r.dv[k][2]);
      if constexpr (Forces) {
        p[k] += force[k * forceStride + i];
        du[k] += force[(3 + k) * forceStride + i];
        dv[k] += force[(6 + k) * forceStride + i];
      }
    }
    // Tangents divided by the patch's size bound: no overflow or underflow in the cross
    // product for any finite model, and |Su × Sv|² becomes a scale-free sine².
    for (int k = 0; k < 3; ++k) {
      du[k] *= invScale;
      dv[k] *= invScale;
    }
    const double nx = du[1] * dv[2] - du[2] * dv[1];
    const double ny = du[2] * dv[0] - du[0] * dv[2];
    const double nz = du[0] * dv[1] - du[1] * dv[0];
    const double len2 = nx * nx + ny * ny + nz * nz;
    const double inv = flip / std::sqrt(len2);
    cross2[i] = len2;
    pos[3 * i] = static_cast<float>(p[0]);
    pos[3 * i + 1] = static_cast<float>(p[1]);
    pos[3 * i + 2] = static_cast<float>(p[2]);
    nor[3 * i] = static_cast<float>(nx * inv);
    nor[3 * i + 1] = static_cast<float>(ny * inv);
    nor[3 * i + 2] = static_cast<float>(nz * inv);
  }
}

/// Whether any x[i] is not above `threshold` (NaN counts); vectorises as a standalone loop.
bool anyNotAbove(const double* __restrict x, std::size_t m, double threshold) {
  std::uint32_t count = 0;
  for (std::size_t i = 0; i < m; ++i) count += !(x[i] > threshold);
  return count != 0;
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

/// The two triangles of each quad between two rows of ids, wound by `Flip`.
template <bool Flip>
inline void writeQuadRow(const std::uint32_t* __restrict prev, const std::uint32_t* __restrict row,
                         std::size_t quads, std::uint32_t* __restrict out) {
  for (std::size_t i = 0; i < quads; ++i) {
    const std::uint32_t a = prev[i], b = prev[i + 1], c = row[i + 1], d = row[i];
    std::uint32_t* o = out + 6 * i;
    o[0] = a;
    o[1] = Flip ? c : b;
    o[2] = Flip ? b : c;
    o[3] = a;
    o[4] = Flip ? d : c;
    o[5] = Flip ? c : d;
  }
}

/// Quad (a b c d) split along b–d instead of a–c.
inline void writeQuadAlt(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                         bool flip, std::uint32_t* o) {
  o[0] = a;
  o[1] = flip ? d : b;
  o[2] = flip ? b : d;
  o[3] = b;
  o[4] = flip ? d : c;
  o[5] = flip ? c : d;
}

}  // namespace

Mesh tessellate(const VertexFrameSurface& surface, const TessellateOptions& options) {
  Mesh mesh;
  tessellate(surface, options, mesh);
  return mesh;
}

void tessellate(const VertexFrameSurface& surface, const TessellateOptions& options, Mesh& mesh) {
  const FrameTopology& topo = *surface.topology;
  const std::uint32_t n = std::max<std::uint32_t>(2, options.resolution);
  const std::uint32_t inner = n - 2;
  // The patch's grid buffers hold rows of np ≥ n points, np a multiple of kLanes, so the
  // row kernel's vector loop covers every row without a scalar remainder.
  const std::size_t np = (n + kLanes - 1) / kLanes * kLanes;
  const std::size_t m = std::size_t{n} * np;
  const auto nFrames = static_cast<std::uint32_t>(surface.patches.size());

  // --- Vertex numbering.
  std::uint32_t next = 0;
  std::uint32_t maxVertex = 0;
  for (const ModelEdge& e : topo.edges)
    maxVertex = std::max({maxVertex, e.vertices[0], e.vertices[2]});
  std::vector<std::uint32_t> cornerId(std::size_t{maxVertex} + 1, kNone);
  for (std::uint32_t k = 0; k < nFrames; ++k)
    for (std::uint32_t e : topo.edgeOf[k])
      for (std::uint32_t v : {topo.edges[e].vertices[0], topo.edges[e].vertices[2]})
        if (cornerId[v] == kNone) cornerId[v] = next++;
  // Indices are 32-bit (as in glTF and GL): refuse meshes that do not fit.
  // Points inside an edge: none on a collapsed edge; on a loop a→m→a (pinned flat, so
  // symmetric: S(t) = S(1-t)) only the first half, its mirror image shares them.
  auto edgeInner = [&](const ModelEdge& e) -> std::uint32_t {
    if (e.collapsed()) return 0;
    return e.vertices[0] == e.vertices[2] ? (n - 1) / 2 : inner;
  };
  std::uint64_t edgePoints = 0;
  for (const ModelEdge& e : topo.edges) edgePoints += edgeInner(e);
  const std::uint64_t vertices64 =
      std::uint64_t{next} + edgePoints + std::uint64_t{nFrames} * inner * inner;
  const std::uint64_t triangles64 = std::uint64_t{nFrames} * (n - 1) * (n - 1) * 2;
  if (vertices64 >= kNone || triangles64 * 3 >= kNone)
    throw std::length_error(fmt::format(
        "a mesh of {} frames at resolution {} would have {} vertices and {} triangles, more "
        "than 32-bit indices can address: lower the resolution",
        nFrames, n, vertices64, triangles64));
  std::vector<std::uint32_t> edgeBase(topo.edges.size(), kNone);
  for (std::size_t e = 0; e < topo.edges.size(); ++e) {
    edgeBase[e] = next;
    next += edgeInner(topo.edges[e]);
  }
  const std::uint32_t boundaryCount = next;
  const std::uint32_t interiorBase = next;
  const auto vertexCount = static_cast<std::uint32_t>(vertices64);

  mesh.positions.resize(std::size_t{vertexCount} * 3);
  mesh.normals.resize(std::size_t{vertexCount} * 3);
  // Room for every quad's two triangles; collapsed sides drop some, trimmed at the end.
  mesh.indices.resize(std::size_t{nFrames} * (n - 1) * (n - 1) * 6);
  mesh.patchIds.resize(std::size_t{nFrames} * (n - 1) * (n - 1) * 2);
  std::size_t triangles = 0;
  // Boundary normals are sums over the patches that meet there, normalised at the end.
  std::fill_n(mesh.normals.begin(), std::size_t{boundaryCount} * 3, 0.0f);
  std::vector<float> firstNormal(std::size_t{boundaryCount} * 3);
  std::vector<std::uint8_t> hasFirst(boundaryCount, 0);

  // The flattened grid: point j·n + i at (t[i], t[j]).
  const std::vector<double> t = gridParams(n);
  std::vector<double> tp(np, 1.0);  // t padded with copies of its last value
  std::copy(t.begin(), t.end(), tp.begin());
  std::vector<float> pos(3 * m), nor(3 * m);
  std::vector<double> cross2(m);
  std::vector<std::uint32_t> ids0(n), ids1(n), ring(std::size_t{n} * 4);
  std::vector<ForceTables> forceTables;
  std::vector<double> forceRow;
  const auto pattern = interiorQuadPattern(inner, false);
  const auto patternFlip = interiorQuadPattern(inner, true);

  for (std::uint32_t k = 0; k < nFrames; ++k) {
    const VertexFramePatch& patch = surface.patches[k];
    const double flip = topo.flipped[k] ? -1.0 : 1.0;
    double c[3][10];
    for (int comp = 0; comp < 3; ++comp)
      for (int i = 0; i < 10; ++i) c[comp][i] = patch.c[i][comp];
    // A bound on |Su| and |Sv| over the patch (each monomial's derivative is at most 3 on
    // the unit square, |x| ≤ 2 max|x_c| in 3D), formed from maxima so it cannot overflow
    // before the coordinates themselves would.
    double scale = 0.0;
    for (int i = 1; i < 10; ++i) scale += 6.0 * patch.c[i].cwiseAbs().maxCoeff();
    for (const ForceTerm& f : patch.forces)
      scale += 2.0 * M_PI * f.k.cwiseAbs().maxCoeff() /
               std::min(f.region.u1 - f.region.u0, f.region.v1 - f.region.v0);
    const double invScale = scale > 0.0 && std::isfinite(scale) ? 1.0 / scale : 1.0;
    constexpr double degenerate2 = kDegenerateNormalSine * kDegenerateNormalSine;
    forceTables.resize(patch.forces.size());
    for (std::size_t f = 0; f < patch.forces.size(); ++f) {
      const Region& r = patch.forces[f].region;
      shapeTable(tp, r.u0, r.u1, forceTables[f].su, forceTables[f].dsu);
      shapeTable(tp, r.v0, r.v1, forceTables[f].sv, forceTables[f].dsv);
    }
    for (std::uint32_t j = 0; j < n; ++j) {
      const RowPolynomials rp = foldRow(c, t[j]);
      const std::size_t g = j * np;
      if (!rowForces(patch, forceTables, j, np, forceRow))
        evaluateRow<false>(tp.data(), np, rp, nullptr, np, flip, invScale, pos.data() + 3 * g,
                           nor.data() + 3 * g, cross2.data() + g);
      else
        evaluateRow<true>(tp.data(), np, rp, forceRow.data(), np, flip, invScale,
                          pos.data() + 3 * g, nor.data() + 3 * g, cross2.data() + g);
    }
    const std::uint32_t patchBase = interiorBase + k * inner * inner;

    // Mesh ids of the patch's boundary ring, side by side in the side's own direction.
    bool collapsedSide[4];
    bool repeatsIds = false;  // some boundary points of this patch are one mesh vertex
    for (int s = 0; s < 4; ++s) {
      const std::uint32_t e = topo.edgeOf[k][s];
      const ModelEdge& edge = topo.edges[e];
      const bool rev = topo.sideReversed[k][s] != 0;
      const bool loop = edge.vertices[0] == edge.vertices[2];
      collapsedSide[s] = edge.collapsed();
      repeatsIds |= loop;
      for (int s2 = 0; s2 < s; ++s2) repeatsIds |= topo.edgeOf[k][s2] == e;
      std::uint32_t* ids = ring.data() + s * n;
      ids[0] = cornerId[rev ? edge.vertices[2] : edge.vertices[0]];
      ids[n - 1] = cornerId[rev ? edge.vertices[0] : edge.vertices[2]];
      for (std::uint32_t q = 1; q + 1 < n; ++q) {
        if (edge.collapsed())
          ids[q] = ids[0];
        else if (loop)
          ids[q] = edgeBase[e] + std::min(q, n - 1 - q) - 1;
        else
          ids[q] = edgeBase[e] + (rev ? n - 1 - q : q) - 1;
      }
    }
    const bool anyCollapsed =
        collapsedSide[0] || collapsedSide[1] || collapsedSide[2] || collapsedSide[3];
    {
      const std::uint32_t corners[4] = {ring[0], ring[n - 1], ring[2 * n + n - 1], ring[2 * n]};
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < a; ++b) repeatsIds |= corners[a] == corners[b];
    }
    repeatsIds |= anyCollapsed;

    // Degenerate normals: |Su × Sv| < kDegenerateNormalSine · scale² (rounding noise at a
    // pole, a cusp). Points on a collapsed side are a pole whatever rounding says. There
    // the normal is taken from just inside the patch.
    auto insetNormal = [&](std::size_t i, std::size_t j) {
      const double uu = t[i] + kNormalInset * (0.5 - t[i]);
      const double vv = t[j] + kNormalInset * (0.5 - t[j]);
      const SurfacePoint sp = patch.evaluate(uu, vv);
      Vec3 nrm = (sp.du * invScale).cross(sp.dv * invScale);
      const double nl = nrm.norm();
      nrm = nl > 0.0 ? Vec3(flip * nrm / nl) : Vec3::Zero();
      for (int comp = 0; comp < 3; ++comp)
        nor[3 * (j * np + i) + comp] = static_cast<float>(nrm[comp]);
    };
    for (std::size_t j = 0; j < n; ++j)
      if (anyNotAbove(cross2.data() + j * np, n, degenerate2))
        for (std::size_t i = 0; i < n; ++i)
          if (!(cross2[j * np + i] > degenerate2)) insetNormal(i, j);
    if (anyCollapsed)
      for (std::size_t q = 0; q < n; ++q) {
        if (collapsedSide[0]) insetNormal(q, 0);      // Alpha: row 0
        if (collapsedSide[2]) insetNormal(q, n - 1);  // Beta: row n-1
        if (collapsedSide[3]) insetNormal(0, q);      // Gamma: column 0
        if (collapsedSide[1]) insetNormal(n - 1, q);  // Delta: column n-1
      }

    // Interior rows are contiguous in the mesh: copy them whole.
    for (std::uint32_t j = 1; j + 1 < n; ++j) {
      const std::size_t dst = std::size_t{patchBase + (j - 1) * inner} * 3;
      const std::size_t src = (j * np + 1) * 3;
      std::copy_n(pos.data() + src, 3 * inner, mesh.positions.data() + dst);
      std::copy_n(nor.data() + src, 3 * inner, mesh.normals.data() + dst);
    }

    // Rows of mesh ids; boundary points set their position and add their normal.
    std::uint32_t* rowIds = ids1.data();
    std::uint32_t* prevIds = ids0.data();
    for (std::uint32_t j = 0; j < n; ++j) {
      std::swap(rowIds, prevIds);
      if (j == 0) {
        std::copy_n(ring.data(), n, rowIds);  // Alpha
      } else if (j + 1 == n) {
        std::copy_n(ring.data() + 2 * n, n, rowIds);  // Beta
      } else {
        rowIds[0] = ring[3 * n + j];      // Gamma
        rowIds[n - 1] = ring[1 * n + j];  // Delta
        const std::uint32_t base = patchBase + (j - 1) * inner - 1;
        // Rows next to Alpha or Beta (and all rows of small or pole patches) take the
        // generic quad writer, which reads the whole row; the pattern writer needs 4 ids.
        const bool fullRow = j == 1 || j + 2 == n || repeatsIds || n < 4;
        if (fullRow) {
          for (std::uint32_t i = 1; i + 1 < n; ++i) rowIds[i] = base + i;
        } else {
          rowIds[1] = base + 1;
          rowIds[n - 2] = base + n - 2;
        }
      }
      auto storeBoundary = [&](std::uint32_t i) {
        const std::size_t o = std::size_t{rowIds[i]} * 3, g = (j * np + i) * 3;
        if (!hasFirst[rowIds[i]]) {
          hasFirst[rowIds[i]] = 1;
          std::copy_n(nor.data() + g, 3, firstNormal.data() + o);
        }
        for (int comp = 0; comp < 3; ++comp) {
          mesh.positions[o + comp] = pos[g + comp];
          mesh.normals[o + comp] += nor[g + comp];
        }
      };
      if (j == 0 || j + 1 == n) {
        for (std::uint32_t i = 0; i < n; ++i) storeBoundary(i);
      } else {
        storeBoundary(0);
        storeBoundary(n - 1);
      }

      // Triangles between row j-1 and row j: quad (prev i, prev i+1, row i+1, row i).
      if (j == 0) continue;
      std::uint32_t* out = mesh.indices.data() + triangles * 3;
      std::uint32_t* outPatch = mesh.patchIds.data() + triangles;
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
      if (!repeatsIds) {  // no repeated ids: every quad gives two triangles
        if (j >= 2 && j + 2 <= n && n >= 4) {
          // Boundary quads at both ends, the patch-interior quads between them by pattern.
          quadAt(0, out);
          writeInteriorQuads(prevIds[1], n - 3, flip < 0 ? patternFlip : pattern, out + 6);
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
      triangles = static_cast<std::size_t>(outPatch - mesh.patchIds.data());
    }
  }
  mesh.indices.resize(triangles * 3);
  mesh.patchIds.resize(triangles);

  for (std::uint32_t v = 0; v < boundaryCount; ++v) {
    float* nv = mesh.normals.data() + std::size_t{v} * 3;
    const float len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (len > kCancelledNormal) {
      for (int comp = 0; comp < 3; ++comp) nv[comp] /= len;
    } else {
      // The patches' normals cancel (the rim of a pillow, a fin folded back): no average
      // direction exists, so the first patch's normal stands for all.
      std::copy_n(firstNormal.data() + std::size_t{v} * 3, 3, nv);
    }
  }
}

}  // namespace pdesurf
