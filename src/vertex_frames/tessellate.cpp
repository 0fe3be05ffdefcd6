// Watertight tessellation of a solved vertex-frame surface.
//
// Vertex numbering: first the corners (one per model vertex used as a frame corner), then
// the inner points of every non-collapsed edge (in the direction of the edge's first
// side), then each patch's interior grid. Boundary vertices therefore come first, and
// their normals are accumulated over the patches that meet there, then normalised.
//
// Speed: a patch on a grid is a 4×4 tensor product per component (plus force terms that
// are products of per-u and per-v tables), so each row j folds the v-powers into four
// coefficients and the inner loop over u is a few fused multiply-adds per component.
#include <algorithm>
#include <cmath>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

namespace {

constexpr std::uint32_t kNone = ~std::uint32_t{0};

/// A normal counts as degenerate (a pole, a cusp) when |Su × Sv| is below this fraction of
/// the patch's squared size: far below any real surface, far above rounding noise (1e-16).
constexpr double kDegenerateNormalSine = 1e-10;
/// Where the normal is degenerate it is taken this far inside the patch, towards its centre.
constexpr double kNormalInset = 1e-4;

struct PowerTables {
  std::vector<std::array<double, 4>> b, db;  // [1, t, t², t³] and its derivative
  std::vector<double> t;
};

PowerTables powerTables(std::uint32_t n) {
  PowerTables pt;
  pt.b.resize(n);
  pt.db.resize(n);
  pt.t.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const double t = i + 1 == n ? 1.0 : static_cast<double>(i) / (n - 1);
    pt.t[i] = t;
    pt.b[i] = {1.0, t, t * t, t * t * t};
    pt.db[i] = {0.0, 1.0, 2.0 * t, 3.0 * t * t};
  }
  return pt;
}

/// sin(π s) and its derivative on a force region, sampled on the grid (cf. forceShape).
void shapeTable(const PowerTables& pt, double x0, double x1, std::vector<double>& s,
                std::vector<double>& ds) {
  const std::size_t n = pt.t.size();
  s.assign(n, 0.0);
  ds.assign(n, 0.0);
  const double len = x1 - x0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = pt.t[i];
    if (x < x0 || x > x1) continue;
    const double t = (x - x0) / len;
    s[i] = std::sin(M_PI * std::min(t, 1.0 - t));
    ds[i] = M_PI / len * std::cos(M_PI * t);
  }
}

/// o = flip · (u × v) / |u × v| and l = |u × v|², over SoA arrays (kept as a separate
/// function with restrict parameters: that is what lets the compiler vectorise it).
void unitNormals(const double* __restrict ux, const double* __restrict uy,
                 const double* __restrict uz, const double* __restrict vx,
                 const double* __restrict vy, const double* __restrict vz, double* __restrict ox,
                 double* __restrict oy, double* __restrict oz, double* __restrict l, std::size_t n,
                 double flip) {
  for (std::size_t i = 0; i < n; ++i) {
    const double cx = uy[i] * vz[i] - uz[i] * vy[i];
    const double cy = uz[i] * vx[i] - ux[i] * vz[i];
    const double cz = ux[i] * vy[i] - uy[i] * vx[i];
    const double len2 = cx * cx + cy * cy + cz * cz;
    l[i] = len2;
    const double inv = flip / std::sqrt(len2);
    ox[i] = cx * inv;
    oy[i] = cy * inv;
    oz[i] = cz * inv;
  }
}

/// out[3i..3i+2] = (x[i], y[i], z[i]) as floats.
void storeInterleaved(const double* __restrict x, const double* __restrict y,
                      const double* __restrict z, float* __restrict out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    out[3 * i] = static_cast<float>(x[i]);
    out[3 * i + 1] = static_cast<float>(y[i]);
    out[3 * i + 2] = static_cast<float>(z[i]);
  }
}

/// The two triangles of each quad between two rows of ids, wound by `flip`.
void writeQuadRow(const std::uint32_t* __restrict prev, const std::uint32_t* __restrict row,
                  std::size_t quads, bool flip, std::uint32_t* __restrict out) {
  for (std::size_t i = 0; i < quads; ++i) {
    const std::uint32_t a = prev[i], b = prev[i + 1], c = row[i + 1], d = row[i];
    std::uint32_t* o = out + 6 * i;
    o[0] = a;
    o[1] = flip ? c : b;
    o[2] = flip ? b : c;
    o[3] = a;
    o[4] = flip ? d : c;
    o[5] = flip ? c : d;
  }
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
  std::vector<std::uint32_t> edgeBase(topo.edges.size(), kNone);
  for (std::size_t e = 0; e < topo.edges.size(); ++e)
    if (!topo.edges[e].collapsed()) {
      edgeBase[e] = next;
      next += inner;
    }
  const std::uint32_t boundaryCount = next;
  const std::uint32_t interiorBase = next;
  const std::uint32_t vertexCount = next + nFrames * inner * inner;

  mesh.positions.resize(std::size_t{vertexCount} * 3);
  mesh.normals.resize(std::size_t{vertexCount} * 3);
  // Room for every quad's two triangles; collapsed sides drop some, trimmed at the end.
  mesh.indices.resize(std::size_t{nFrames} * (n - 1) * (n - 1) * 6);
  mesh.patchIds.resize(std::size_t{nFrames} * (n - 1) * (n - 1) * 2);
  std::size_t triangles = 0;
  // Boundary normals are sums over the patches that meet there, normalised at the end.
  std::fill_n(mesh.normals.begin(), std::size_t{boundaryCount} * 3, 0.0f);

  const PowerTables pt = powerTables(n);
  std::vector<double> row(std::size_t{n} * 13);  // SoA: p, du, dv, normal (xyz each), |Su×Sv|²
  double* px = row.data();
  double* dux = px + 3 * n;
  double* dvx = px + 6 * n;
  double* nx = px + 9 * n;
  double* cross2 = px + 12 * n;
  std::vector<std::uint32_t> ids0(n), ids1(n), ring(std::size_t{n} * 4);
  struct ForceTables {
    std::vector<double> su, dsu, sv, dsv;
  };
  std::vector<ForceTables> ft;

  for (std::uint32_t k = 0; k < nFrames; ++k) {
    const VertexFramePatch& patch = surface.patches[k];
    const double flip = topo.flipped[k] ? -1.0 : 1.0;
    // A[c][i][j]: coefficient of u^i v^j in component c.
    double a[3][4][4] = {};
    for (int c = 0; c < 3; ++c) {
      a[c][0][0] = patch.c[0][c];
      a[c][1][0] = patch.c[1][c];
      a[c][2][0] = patch.c[2][c];
      a[c][3][0] = patch.c[3][c];
      a[c][0][1] = patch.c[4][c];
      a[c][0][2] = patch.c[5][c];
      a[c][0][3] = patch.c[6][c];
      a[c][1][1] = patch.c[7][c];
      a[c][2][1] = patch.c[8][c];
      a[c][1][2] = patch.c[9][c];
    }
    ft.resize(patch.forces.size());
    for (std::size_t f = 0; f < patch.forces.size(); ++f) {
      const Region& r = patch.forces[f].region;
      shapeTable(pt, r.u0, r.u1, ft[f].su, ft[f].dsu);
      shapeTable(pt, r.v0, r.v1, ft[f].sv, ft[f].dsv);
    }

    // Mesh ids of the patch's boundary ring, side by side in the side's own direction.
    const std::uint32_t patchBase = interiorBase + k * inner * inner;
    bool collapsedSide[4];
    for (int s = 0; s < 4; ++s) {
      const std::uint32_t e = topo.edgeOf[k][s];
      const ModelEdge& edge = topo.edges[e];
      const bool rev = topo.sideReversed[k][s] != 0;
      collapsedSide[s] = edge.collapsed();
      std::uint32_t* ids = ring.data() + s * n;
      ids[0] = cornerId[rev ? edge.vertices[2] : edge.vertices[0]];
      ids[n - 1] = cornerId[rev ? edge.vertices[0] : edge.vertices[2]];
      for (std::uint32_t t = 1; t + 1 < n; ++t)
        ids[t] = edge.collapsed() ? ids[0] : edgeBase[e] + (rev ? n - 1 - t : t) - 1;
    }
    const bool anyCollapsed =
        collapsedSide[0] || collapsedSide[1] || collapsedSide[2] || collapsedSide[3];
    // |Su|, |Sv| ≤ scale everywhere on the patch; a normal is degenerate when
    // |Su × Sv| < kDegenerateNormalSine · scale² (rounding noise at a pole, a cusp).
    double scale = 0.0;
    for (int i = 1; i < 10; ++i) scale += 3.0 * patch.c[i].norm();
    for (std::size_t f = 0; f < patch.forces.size(); ++f) {
      const Region& r = patch.forces[f].region;
      scale += M_PI * patch.forces[f].k.norm() / std::min(r.u1 - r.u0, r.v1 - r.v0);
    }
    const double degenerate2 = std::pow(kDegenerateNormalSine * scale * scale, 2);

    std::uint32_t* rowIds = ids1.data();
    std::uint32_t* prevIds = ids0.data();
    for (std::uint32_t j = 0; j < n; ++j) {
      // Fold the v-powers of row j: r[c][i] (position) and rv[c][i] (∂/∂v).
      double r[3][4], rv[3][4];
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 4; ++i) {
          r[c][i] = a[c][i][0] * pt.b[j][0] + a[c][i][1] * pt.b[j][1] + a[c][i][2] * pt.b[j][2] +
                    a[c][i][3] * pt.b[j][3];
          rv[c][i] = a[c][i][1] * pt.db[j][1] + a[c][i][2] * pt.db[j][2] + a[c][i][3] * pt.db[j][3];
        }
      for (int c = 0; c < 3; ++c) {
        double* __restrict p = px + c * n;
        double* __restrict du = dux + c * n;
        double* __restrict dv = dvx + c * n;
        const double* __restrict tt = pt.t.data();
        const double r0 = r[c][0], r1 = r[c][1], r2 = r[c][2], r3 = r[c][3];
        const double v0 = rv[c][0], v1 = rv[c][1], v2 = rv[c][2], v3 = rv[c][3];
        for (std::uint32_t i = 0; i < n; ++i) {
          const double t = tt[i];
          p[i] = r0 + t * (r1 + t * (r2 + t * r3));
          du[i] = r1 + t * (2.0 * r2 + t * 3.0 * r3);
          dv[i] = v0 + t * (v1 + t * (v2 + t * v3));
        }
        for (std::size_t f = 0; f < ft.size(); ++f) {
          const double kc = patch.forces[f].k[c];
          const double kv = kc * ft[f].sv[j], kdv = kc * ft[f].dsv[j];
          if (kv == 0.0 && kdv == 0.0) continue;
          const double* __restrict su = ft[f].su.data();
          const double* __restrict dsu = ft[f].dsu.data();
          for (std::uint32_t i = 0; i < n; ++i) {
            p[i] += kv * su[i];
            du[i] += kv * dsu[i];
            dv[i] += kdv * su[i];
          }
        }
      }
      unitNormals(dux, dux + n, dux + 2 * n, dvx, dvx + n, dvx + 2 * n, nx, nx + n, nx + 2 * n,
                  cross2, n, flip);
      // Points on a collapsed side are a pole whatever rounding says; there, and wherever
      // the tangents degenerate, the normal is taken from just inside the patch.
      const bool poleRow = (j == 0 && collapsedSide[0]) || (j + 1 == n && collapsedSide[2]);
      bool degenerate = false;
      for (std::uint32_t i = 0; i < n; ++i) degenerate |= !(cross2[i] > degenerate2);
      if (degenerate || poleRow || anyCollapsed) {
        for (std::uint32_t i = 0; i < n; ++i) {
          const bool pole =
              poleRow || (i == 0 && collapsedSide[3]) || (i + 1 == n && collapsedSide[1]);
          if (!pole) {
            if (cross2[i] > degenerate2) continue;
          }
          const double u = pt.t[i] + kNormalInset * (0.5 - pt.t[i]);
          const double v = pt.t[j] + kNormalInset * (0.5 - pt.t[j]);
          const SurfacePoint sp = patch.evaluate(u, v);
          Vec3 nrm = sp.du.cross(sp.dv);
          const double nl = nrm.norm();
          nrm = nl > 0.0 ? Vec3(flip * nrm / nl) : Vec3::Zero();
          nx[i] = nrm.x();
          nx[n + i] = nrm.y();
          nx[2 * n + i] = nrm.z();
        }
      }

      // Mesh ids of row j.
      std::swap(rowIds, prevIds);
      if (j == 0) {
        std::copy_n(ring.data(), n, rowIds);  // Alpha
      } else if (j + 1 == n) {
        std::copy_n(ring.data() + 2 * n, n, rowIds);  // Beta
      } else {
        rowIds[0] = ring[3 * n + j];      // Gamma
        rowIds[n - 1] = ring[1 * n + j];  // Delta
        const std::uint32_t base = patchBase + (j - 1) * inner - 1;
        for (std::uint32_t i = 1; i + 1 < n; ++i) rowIds[i] = base + i;
      }

      // Store: interior points straight into the mesh, boundary points accumulate normals.
      float* pos = mesh.positions.data();
      float* nor = mesh.normals.data();
      const bool innerRow = j > 0 && j + 1 < n;
      if (innerRow && inner > 0) {
        const std::size_t base = std::size_t{patchBase + (j - 1) * inner} * 3;
        storeInterleaved(px + 1, px + n + 1, px + 2 * n + 1, pos + base, inner);
        storeInterleaved(nx + 1, nx + n + 1, nx + 2 * n + 1, nor + base, inner);
      }
      auto storeBoundary = [&](std::uint32_t i) {
        const std::size_t o = std::size_t{rowIds[i]} * 3;
        pos[o] = static_cast<float>(px[i]);
        pos[o + 1] = static_cast<float>(px[n + i]);
        pos[o + 2] = static_cast<float>(px[2 * n + i]);
        nor[o] += static_cast<float>(nx[i]);
        nor[o + 1] += static_cast<float>(nx[n + i]);
        nor[o + 2] += static_cast<float>(nx[2 * n + i]);
      };
      if (innerRow) {
        storeBoundary(0);
        storeBoundary(n - 1);
      } else {
        for (std::uint32_t i = 0; i < n; ++i) storeBoundary(i);
      }

      // Triangles between row j-1 and row j: quad (a b c d) = (prev i, prev i+1, row i+1, row i).
      if (j == 0) continue;
      std::uint32_t* out = mesh.indices.data() + triangles * 3;
      std::uint32_t* outPatch = mesh.patchIds.data() + triangles;
      if (!anyCollapsed) {  // no repeated ids: every quad gives two triangles
        writeQuadRow(prevIds, rowIds, n - 1, flip < 0, out);
        std::fill_n(outPatch, 2 * (n - 1), k);
        outPatch += 2 * (n - 1);
      } else {
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
          std::uint32_t quad[6];
          writeQuadRow(prevIds + i, rowIds + i, 1, flip < 0, quad);
          for (const std::uint32_t* t : {quad, quad + 3}) {
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
            std::copy_n(t, 3, out);
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
    const float inv = len > 0.0f ? 1.0f / len : 0.0f;
    for (int c = 0; c < 3; ++c) nv[c] *= inv;
  }
}

}  // namespace pdesurf
