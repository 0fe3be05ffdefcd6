// Vertex-frame patches evaluated as the polynomials they are (nurbs.hpp: evaluatePolynomial):
// one point, or many at once in a loop compiled for each SIMD level (src/runtime/simd.hpp),
// built with the same floating-point options as the tessellation's kernels (CMakeLists.txt).
// The reference the NURBS evaluation is measured against (bench/bench_nurbs_eval.cpp).
#include <cassert>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "pdesurf/nurbs.hpp"
#include "runtime/simd.hpp"

namespace pdesurf {

PolynomialPatchPoint evaluatePolynomial(const VertexFramePatch& patch, double u, double v) {
  const auto& c = patch.c;
  // S = A0(v) + u (A1(v) + u (A2(v) + u A3)), each A a polynomial in v.
  const Vec3 a0 = c[0] + v * (c[4] + v * (c[5] + v * c[6]));
  const Vec3 a1 = c[1] + v * (c[7] + v * c[9]);
  const Vec3 a2 = c[2] + v * c[8];
  const Vec3 a0v = c[4] + v * (2.0 * c[5] + (3.0 * v) * c[6]);
  const Vec3 a1v = c[7] + (2.0 * v) * c[9];
  PolynomialPatchPoint r;
  r.p = a0 + u * (a1 + u * (a2 + u * c[3]));
  r.du = a1 + u * (2.0 * a2 + (3.0 * u) * c[3]);
  r.dv = a0v + u * (a1v + u * c[8]);
  const Vec3 n = r.du.cross(r.dv);
  const double len = n.norm();
  r.normal = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
  return r;
}

void PolynomialPatchPoints::resize(std::size_t n) {
  for (std::vector<double>* a : {&x, &y, &z, &ux, &uy, &uz, &vx, &vy, &vz, &nx, &ny, &nz})
    a->resize(n);
}

namespace {

/// One component of the Horner form: S = a0 + u (a1 + u (a2 + u c3)) with a0..a2 in v.
struct HornerComponent {
  double c0, c1, c2, c3, c4, c5, c6, c7, c8, c9;
};

/// By value, so that after inlining the coefficients are registers, not loads the
/// vectoriser cannot place.
[[gnu::always_inline]] inline void hornerAt(const HornerComponent c, double u, double v, double& s,
                                            double& su, double& sv) {
  const double a0 = c.c0 + v * (c.c4 + v * (c.c5 + v * c.c6));
  const double a1 = c.c1 + v * (c.c7 + v * c.c9);
  const double a2 = c.c2 + v * c.c8;
  s = a0 + u * (a1 + u * (a2 + u * c.c3));
  su = a1 + u * (2.0 * a2 + (3.0 * u) * c.c3);
  sv = (c.c4 + v * (2.0 * c.c5 + (3.0 * v) * c.c6)) + u * ((c.c7 + (2.0 * v) * c.c9) + u * c.c8);
}

HornerComponent hornerComponent(const VertexFramePatch& patch, int axis) {
  const auto& c = patch.c;
  return {c[0][axis], c[1][axis], c[2][axis], c[3][axis], c[4][axis],
          c[5][axis], c[6][axis], c[7][axis], c[8][axis], c[9][axis]};
}

}  // namespace

namespace {

/// The SIMD loop of evaluatePolynomial, on raw arrays that do not alias: inlined into one
/// wrapper per SIMD level (src/runtime/simd.hpp), whose own __restrict parameters let GCC
/// vectorise it (inlined into evaluatePolynomial, GCC 12 does not).
PDESURF_ALWAYS_INLINE void hornerLoop(
    HornerComponent cx, HornerComponent cy, HornerComponent cz, std::size_t n,
    const double* __restrict pu, const double* __restrict pv, double* __restrict x,
    double* __restrict y, double* __restrict z, double* __restrict ux, double* __restrict uy,
    double* __restrict uz, double* __restrict vx, double* __restrict vy, double* __restrict vz,
    double* __restrict nx, double* __restrict ny, double* __restrict nz) {
  for (std::size_t i = 0; i < n; ++i) {
    double sx, sy, sz, sux, suy, suz, svx, svy, svz;
    const double ui = pu[i], vi = pv[i];
    hornerAt(cx, ui, vi, sx, sux, svx);
    hornerAt(cy, ui, vi, sy, suy, svy);
    hornerAt(cz, ui, vi, sz, suz, svz);
    const double mx = suy * svz - suz * svy, my = suz * svx - sux * svz, mz = sux * svy - suy * svx;
    const double len = std::sqrt(mx * mx + my * my + mz * mz);
    const double inv = len > 0.0 ? 1.0 / len : 0.0;
    x[i] = sx, y[i] = sy, z[i] = sz;
    ux[i] = sux, uy[i] = suy, uz[i] = suz;
    vx[i] = svx, vy[i] = svy, vz[i] = svz;
    nx[i] = mx * inv, ny[i] = my * inv, nz[i] = mz * inv;
  }
}

using HornerLoop = void (*)(HornerComponent, HornerComponent, HornerComponent, std::size_t,
                            const double*, const double*, double*, double*, double*, double*,
                            double*, double*, double*, double*, double*, double*, double*, double*);
#define PDESURF_HORNER_LOOP(name, target)                                                         \
  [[gnu::noinline]] target void name(                                                             \
      HornerComponent cx, HornerComponent cy, HornerComponent cz, std::size_t n,                  \
      const double* __restrict pu, const double* __restrict pv, double* __restrict x,             \
      double* __restrict y, double* __restrict z, double* __restrict ux, double* __restrict uy,   \
      double* __restrict uz, double* __restrict vx, double* __restrict vy, double* __restrict vz, \
      double* __restrict nx, double* __restrict ny, double* __restrict nz) {                      \
    hornerLoop(cx, cy, cz, n, pu, pv, x, y, z, ux, uy, uz, vx, vy, vz, nx, ny, nz);               \
  }
PDESURF_HORNER_LOOP(hornerLoopV2, )
PDESURF_HORNER_LOOP(hornerLoopV3, PDESURF_TARGET_V3)
PDESURF_HORNER_LOOP(hornerLoopV4, PDESURF_TARGET_V4)
#undef PDESURF_HORNER_LOOP

/// Points per parallel task of the batched evaluation (a few microseconds of work).
constexpr std::size_t kHornerPointsPerTask = 2048;

}  // namespace

void evaluatePolynomial(const VertexFramePatch& patch, std::span<const double> u,
                        std::span<const double> v, PolynomialPatchPoints& out) {
  assert(u.size() == v.size());
  out.resize(u.size());
  const HornerLoop loop = detail::simdChoose<HornerLoop>(hornerLoopV2, hornerLoopV3, hornerLoopV4);
  const HornerComponent cx = hornerComponent(patch, 0), cy = hornerComponent(patch, 1),
                        cz = hornerComponent(patch, 2);
  // Every point is independent: blocks in parallel give the same values for any thread count.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, u.size(), kHornerPointsPerTask),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      const std::size_t i = r.begin();
                      loop(cx, cy, cz, r.size(), u.data() + i, v.data() + i, out.x.data() + i,
                           out.y.data() + i, out.z.data() + i, out.ux.data() + i, out.uy.data() + i,
                           out.uz.data() + i, out.vx.data() + i, out.vy.data() + i,
                           out.vz.data() + i, out.nx.data() + i, out.ny.data() + i,
                           out.nz.data() + i);
                    });
}

}  // namespace pdesurf
