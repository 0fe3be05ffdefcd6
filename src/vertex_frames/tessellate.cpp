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
/// |Su| |Sv|: the sine of the angle between the tangents, far below any real crease.
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

}  // namespace

Mesh tessellate(const VertexFrameSurface& surface, const TessellateOptions& options) {
  const FrameTopology& topo = surface.topology;
  const std::uint32_t n = std::max<std::uint32_t>(2, options.resolution);
  const std::uint32_t inner = n - 2;
  const auto nFrames = static_cast<std::uint32_t>(surface.patches.size());

  // --- Vertex numbering.
  std::uint32_t next = 0;
  std::uint32_t maxVertex = 0;
  for (const ModelEdge& e : topo.edges) maxVertex = std::max({maxVertex, e.vertices[0], e.vertices[2]});
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

  Mesh mesh;
  mesh.positions.resize(std::size_t{vertexCount} * 3);
  mesh.normals.resize(std::size_t{vertexCount} * 3);
  mesh.indices.reserve(std::size_t{nFrames} * (n - 1) * (n - 1) * 6);
  mesh.patchIds.reserve(std::size_t{nFrames} * (n - 1) * (n - 1) * 2);
  std::vector<double> accum(std::size_t{boundaryCount} * 3, 0.0);

  const PowerTables pt = powerTables(n);
  std::vector<double> row(std::size_t{n} * 12);  // SoA: p, du, dv (xyz each), normal
  double* px = row.data();
  double* dux = px + 3 * n;
  double* dvx = px + 6 * n;
  double* nx = px + 9 * n;
  std::vector<std::uint32_t> ids0(n), ids1(n);
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

    auto sideId = [&](int s, std::uint32_t t) -> std::uint32_t {
      const std::uint32_t e = topo.edgeOf[k][s];
      const ModelEdge& edge = topo.edges[e];
      const bool rev = topo.sideReversed[k][s] != 0;
      if (t == 0) return cornerId[rev ? edge.vertices[2] : edge.vertices[0]];
      if (t == n - 1) return cornerId[rev ? edge.vertices[0] : edge.vertices[2]];
      if (edge.collapsed()) return cornerId[edge.vertices[0]];
      return edgeBase[e] + (rev ? n - 1 - t : t) - 1;
    };
    const std::uint32_t patchBase = interiorBase + k * inner * inner;
    auto idOf = [&](std::uint32_t i, std::uint32_t j) -> std::uint32_t {
      if (j == 0) return sideId(0, i);      // Alpha
      if (j == n - 1) return sideId(2, i);  // Beta
      if (i == 0) return sideId(3, j);      // Gamma
      if (i == n - 1) return sideId(1, j);  // Delta
      return patchBase + (j - 1) * inner + (i - 1);
    };

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
        const double r0 = r[c][0], r1 = r[c][1], r2 = r[c][2], r3 = r[c][3];
        const double v0 = rv[c][0], v1 = rv[c][1], v2 = rv[c][2], v3 = rv[c][3];
        for (std::uint32_t i = 0; i < n; ++i) {
          const double t = pt.t[i], t2 = t * t;
          p[i] = r0 + t * r1 + t2 * r2 + t2 * t * r3;
          du[i] = r1 + 2.0 * t * r2 + 3.0 * t2 * r3;
          dv[i] = v0 + t * v1 + t2 * v2 + t2 * t * v3;
        }
        for (std::size_t f = 0; f < ft.size(); ++f) {
          const double kc = patch.forces[f].k[c];
          const double kv = kc * ft[f].sv[j], kdv = kc * ft[f].dsv[j];
          if (kv == 0.0 && kdv == 0.0) continue;
          const double* su = ft[f].su.data();
          const double* dsu = ft[f].dsu.data();
          for (std::uint32_t i = 0; i < n; ++i) {
            p[i] += kv * su[i];
            du[i] += kv * dsu[i];
            dv[i] += kdv * su[i];
          }
        }
      }
      bool degenerate = false;
      {
        const double *ux = dux, *uy = dux + n, *uz = dux + 2 * n;
        const double *vx = dvx, *vy = dvx + n, *vz = dvx + 2 * n;
        double* __restrict ox = nx;
        double* __restrict oy = nx + n;
        double* __restrict oz = nx + 2 * n;
        for (std::uint32_t i = 0; i < n; ++i) {
          const double cx = uy[i] * vz[i] - uz[i] * vy[i];
          const double cy = uz[i] * vx[i] - ux[i] * vz[i];
          const double cz = ux[i] * vy[i] - uy[i] * vx[i];
          const double len2 = cx * cx + cy * cy + cz * cz;
          const double tan2 = (ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i]) *
                              (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
          degenerate |= !(len2 > kDegenerateNormalSine * kDegenerateNormalSine * tan2) ||
                        len2 == 0.0;
          const double inv = flip / std::sqrt(len2);
          ox[i] = cx * inv;
          oy[i] = cy * inv;
          oz[i] = cz * inv;
        }
      }
      if (degenerate) {
        for (std::uint32_t i = 0; i < n; ++i) {
          const Vec3 du(dux[i], dux[n + i], dux[2 * n + i]), dv(dvx[i], dvx[n + i], dvx[2 * n + i]);
          const double len = du.cross(dv).norm();
          if (len > kDegenerateNormalSine * du.norm() * dv.norm() && len > 0.0) continue;
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

      // Store: interior points straight into the mesh, boundary points accumulate normals.
      float* pos = mesh.positions.data();
      float* nor = mesh.normals.data();
      const bool innerRow = j > 0 && j + 1 < n;
      if (innerRow && inner > 0) {
        const std::size_t base = std::size_t{patchBase + (j - 1) * inner} * 3;
        float* __restrict op = pos + base;
        float* __restrict on = nor + base;
        for (std::uint32_t i = 1; i + 1 < n; ++i) {
          const std::size_t o = std::size_t{i - 1} * 3;
          op[o] = static_cast<float>(px[i]);
          op[o + 1] = static_cast<float>(px[n + i]);
          op[o + 2] = static_cast<float>(px[2 * n + i]);
          on[o] = static_cast<float>(nx[i]);
          on[o + 1] = static_cast<float>(nx[n + i]);
          on[o + 2] = static_cast<float>(nx[2 * n + i]);
        }
      }
      for (std::uint32_t i = 0; i < n; ++i) {
        if (innerRow && i > 0 && i + 1 < n) {
          i = n - 2;  // skip to the last column
          continue;
        }
        const std::uint32_t id = idOf(i, j);
        const std::size_t o = std::size_t{id} * 3;
        pos[o] = static_cast<float>(px[i]);
        pos[o + 1] = static_cast<float>(px[n + i]);
        pos[o + 2] = static_cast<float>(px[2 * n + i]);
        accum[o] += nx[i];
        accum[o + 1] += nx[n + i];
        accum[o + 2] += nx[2 * n + i];
      }

      // Triangles between row j-1 and row j.
      std::swap(ids0, ids1);
      for (std::uint32_t i = 0; i < n; ++i) ids1[i] = idOf(i, j);
      if (j == 0) continue;
      for (std::uint32_t i = 0; i + 1 < n; ++i) {
        const std::uint32_t qa = ids0[i], qb = ids0[i + 1], qc = ids1[i + 1], qd = ids1[i];
        const std::uint32_t tris[2][3] = {{qa, qb, qc}, {qa, qc, qd}};
        for (const auto& t : tris) {
          if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
          if (flip > 0) {
            mesh.indices.insert(mesh.indices.end(), {t[0], t[1], t[2]});
          } else {
            mesh.indices.insert(mesh.indices.end(), {t[0], t[2], t[1]});
          }
          mesh.patchIds.push_back(k);
        }
      }
    }
  }

  for (std::uint32_t v = 0; v < boundaryCount; ++v) {
    const std::size_t o = std::size_t{v} * 3;
    const double len = std::sqrt(accum[o] * accum[o] + accum[o + 1] * accum[o + 1] +
                                 accum[o + 2] * accum[o + 2]);
    const double inv = len > 0.0 ? 1.0 / len : 0.0;
    for (int c = 0; c < 3; ++c) mesh.normals[o + c] = static_cast<float>(accum[o + c] * inv);
  }
  return mesh;
}

}  // namespace pdesurf
