// Bicubic B-spline surfaces: evaluation from per-u and per-v basis rows, and tessellation.
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "bspline_pde/internal.hpp"

namespace pdesurf {

BSplineSurface::BSplineSurface(ControlNet net, KnotType uKnots, KnotType vKnots)
    : net_(std::move(net)), uType_(uKnots), vType_(vKnots) {
  bspline::validateNet(net_, false, "BSplineSurface");
  uKnots_ = cubicKnots(uType_, net_.nu);
  vKnots_ = cubicKnots(vType_, net_.nv);
}

CubicBasis BSplineSurface::uBasis(double u) const {
  return bspline::cubicBasis(uKnots_, net_.nu, u);
}
CubicBasis BSplineSurface::vBasis(double v) const {
  return bspline::cubicBasis(vKnots_, net_.nv, v);
}

namespace {

/// Σ_r Σ_q bu[r] bv[q] P_{su-3+r, sv-3+q}.
Vec3 contract(const ControlNet& net, const CubicBasis& bu, int a, const CubicBasis& bv, int b) {
  Vec3 sum = Vec3::Zero();
  for (std::uint32_t r = 0; r < 4; ++r) {
    Vec3 row = Vec3::Zero();
    for (std::uint32_t q = 0; q < 4; ++q) row += bv.d[b][q] * net(bu.span - 3 + r, bv.span - 3 + q);
    sum += bu.d[a][r] * row;
  }
  return sum;
}

}  // namespace

SurfacePoint BSplineSurface::evaluate(const CubicBasis& bu, const CubicBasis& bv) const {
  SurfacePoint out{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (std::uint32_t r = 0; r < 4; ++r) {
    Vec3 row = Vec3::Zero(), rowDv = Vec3::Zero();
    for (std::uint32_t q = 0; q < 4; ++q) {
      const Vec3& p = net_(bu.span - 3 + r, bv.span - 3 + q);
      row += bv.d[0][q] * p;
      rowDv += bv.d[1][q] * p;
    }
    out.p += bu.d[0][r] * row;
    out.du += bu.d[1][r] * row;
    out.dv += bu.d[0][r] * rowDv;
  }
  return out;
}

Vec3 BSplineSurface::position(double u, double v) const {
  return contract(net_, uBasis(u), 0, vBasis(v), 0);
}

SurfacePoint BSplineSurface::evaluate(double u, double v) const {
  return evaluate(uBasis(u), vBasis(v));
}

Vec3 BSplineSurface::derivative(double u, double v, int a, int b) const {
  if (a < 0 || a > 3 || b < 0 || b > 3)
    throw InvalidArgument("BSplineSurface::derivative: orders (" + std::to_string(a) + ", " +
                          std::to_string(b) + ") must be within 0..3");
  return contract(net_, uBasis(u), a, vBasis(v), b);
}

void BSplineSurface::evaluateGrid(std::span<const double> us, std::span<const double> vs,
                                  std::vector<SurfacePoint>& out) const {
  std::vector<CubicBasis> bu(us.size()), bv(vs.size());
  for (std::size_t a = 0; a < us.size(); ++a) bu[a] = uBasis(us[a]);
  for (std::size_t b = 0; b < vs.size(); ++b) bv[b] = vBasis(vs[b]);
  out.resize(us.size() * vs.size());
  for (std::size_t a = 0; a < us.size(); ++a)
    for (std::size_t b = 0; b < vs.size(); ++b) out[a * vs.size() + b] = evaluate(bu[a], bv[b]);
}

namespace bspline {

std::uint32_t segmentsPerSpan(const BSplineSurface& surface, std::uint32_t resolution) {
  const std::uint32_t spans = std::max(surface.uSpans(), surface.vSpans());
  return std::max(1u, (resolution - 1 + spans - 1) / spans);
}

Mesh tessellateSpans(const BSplineSurface& surface, std::uint32_t segments) {
  const std::uint32_t su = surface.uSpans(), sv = surface.vSpans();
  const std::uint32_t cu = su * segments, cv = sv * segments;
  if ((static_cast<std::uint64_t>(cu) + 1) * (cv + 1) > 0xffffffffull)
    throw InvalidArgument("tessellate: the grid has more vertices than 32-bit indices hold");
  std::vector<double> us(cu + 1), vs(cv + 1);
  for (std::uint32_t a = 0; a <= cu; ++a) us[a] = static_cast<double>(a) / cu;
  for (std::uint32_t b = 0; b <= cv; ++b) vs[b] = static_cast<double>(b) / cv;
  std::vector<SurfacePoint> grid;
  surface.evaluateGrid(us, vs, grid);

  Eigen::AlignedBox3d box;
  for (const Vec3& p : surface.net().points) box.extend(p);
  const double extent = std::max(box.diagonal().norm(), 1e-300);
  const double degenerate = kBSplineDegenerateNormalTolerance * extent * extent;

  Mesh mesh;
  const std::size_t count = grid.size();
  mesh.positions.resize(3 * count);
  mesh.normals.resize(3 * count);
  std::vector<std::uint8_t> unresolved(count, 0);
  for (std::uint32_t a = 0; a <= cu; ++a)
    for (std::uint32_t b = 0; b <= cv; ++b) {
      const std::size_t k = static_cast<std::size_t>(a) * (cv + 1) + b;
      const SurfacePoint& sp = grid[k];
      Vec3 n = sp.du.cross(sp.dv);
      // A pole or a collapsed row: the normal a little way into the domain (towards its
      // centre), at growing distances, else the mean of the adjacent faces below.
      for (double step : {1e-6, 1e-4, 1e-2}) {
        if (n.norm() > degenerate) break;
        const double u = us[a] + step * (0.5 - us[a]), v = vs[b] + step * (0.5 - vs[b]);
        const SurfacePoint inside = surface.evaluate(u, v);
        n = inside.du.cross(inside.dv);
      }
      if (n.norm() > degenerate)
        n.normalize();
      else
        unresolved[k] = 1;
      for (int c = 0; c < 3; ++c) {
        mesh.positions[3 * k + c] = static_cast<float>(sp.p[c]);
        mesh.normals[3 * k + c] = static_cast<float>(n[c]);
      }
    }
  mesh.indices.reserve(6 * static_cast<std::size_t>(cu) * cv);
  mesh.patchIds.reserve(2 * static_cast<std::size_t>(cu) * cv);
  for (std::uint32_t a = 0; a < cu; ++a)
    for (std::uint32_t b = 0; b < cv; ++b) {
      const std::uint32_t v00 = a * (cv + 1) + b, v10 = v00 + cv + 1;
      const std::uint32_t v01 = v00 + 1, v11 = v10 + 1;
      const std::uint32_t span = (a / segments) * sv + (b / segments);
      // Counter-clockwise in (u, v): the side x_u × x_v points to.
      mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
      mesh.patchIds.insert(mesh.patchIds.end(), {span, span});
    }
  if (std::find(unresolved.begin(), unresolved.end(), 1) != unresolved.end()) {
    std::vector<Vec3> sum(count, Vec3::Zero());
    const auto pos = [&](std::uint32_t v) { return grid[v].p; };
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const std::uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1],
                          i2 = mesh.indices[3 * t + 2];
      const Vec3 face = (pos(i1) - pos(i0)).cross(pos(i2) - pos(i0));
      for (std::uint32_t v : {i0, i1, i2}) sum[v] += face;
    }
    for (std::size_t k = 0; k < count; ++k) {
      if (!unresolved[k]) continue;
      const Vec3 n = sum[k].norm() > 0.0 ? sum[k].normalized() : Vec3::UnitZ().eval();
      for (int c = 0; c < 3; ++c) mesh.normals[3 * k + c] = static_cast<float>(n[c]);
    }
  }
  return mesh;
}

}  // namespace bspline

Mesh tessellate(const BSplineSurface& surface, const TessellateOptions& options) {
  checkTessellateOptions(options);
  return bspline::tessellateSpans(surface, bspline::segmentsPerSpan(surface, options.resolution));
}

}  // namespace pdesurf

namespace pdesurf {

double pdeResidual(const BSplineSurface& surface) {
  const ControlNet& net = surface.net();
  std::vector<std::array<double, 4>> tu, tv;
  for (std::uint32_t s = 3; s <= net.nu; ++s)
    tu.push_back(thirdDerivativeMask(surface.uKnots(), s));
  for (std::uint32_t s = 3; s <= net.nv; ++s)
    tv.push_back(thirdDerivativeMask(surface.vKnots(), s));
  double worst = 0.0;
  for (std::uint32_t a = 0; a < surface.uSpans(); ++a)
    for (std::uint32_t b = 0; b < surface.vSpans(); ++b) {
      double scale = 0.0;
      for (std::uint32_t r = 0; r < 4; ++r)
        for (std::uint32_t q = 0; q < 4; ++q)
          scale += std::abs(tu[a][r] * tv[b][q]) * net(a + r, b + q).norm();
      const double u = (a + 0.5) / surface.uSpans(), v = (b + 0.5) / surface.vSpans();
      const double d = surface.derivative(u, v, 3, 3).norm();
      worst = std::max(worst, scale > 0.0 ? d / scale : d);
    }
  return worst;
}

}  // namespace pdesurf
