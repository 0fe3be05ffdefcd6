// The tessellation's row kernel (tessellate.cpp): a line of a patch (a row, or a column as a
// row of the patch with u and v exchanged) folded into polynomials in its own parameter, and
// its positions and unit normals evaluated from them in vectorised blocks, compiled for each
// SIMD level (src/runtime/simd.hpp). Its sources build with tessellate.cpp's floating-point
// options (CMakeLists.txt): every level rounds the same operations.
#pragma once

#include <cstddef>
#include <vector>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::detail {

/// Doubles in one vector register (AVX-512 holds 8): buffers are padded to this.
constexpr std::size_t kLanes = 8;

/// A normal counts as degenerate (a pole, a cusp) when |Su × Sv| is below this fraction of
/// the patch's squared size: far below any real surface, far above rounding noise (1e-16).
constexpr double kDegenerateNormalSine = 1e-10;
constexpr double kDegenerate2 = kDegenerateNormalSine * kDegenerateNormalSine;

/// The force shape and its derivative sampled on the grid.
void shapeTable(const std::vector<double>& grid, double x0, double x1, std::vector<double>& s,
                std::vector<double>& ds);

/// Per-u and per-v tables of each force of a patch, on the padded grid.
struct ForceTables {
  std::vector<double> su, dsu, sv, dsv;
};

/// The summed force terms along a row (v = t[fixed]) or a column (u = t[fixed]), as 9 rows
/// of np values (position, derivative along the line, derivative across it; x y z each):
/// Σ k ⊙ (s s̃, s' s̃, s s̃'), s along the line and s̃ at the fixed parameter, the derivatives
/// divided by the patch's size bound as in foldLines. False when no force reaches the line.
/// Inline: called for every row and column, and for most of them (no force on the patch)
/// it returns at once.
inline bool lineForces(const VertexFramePatch& patch, const std::vector<ForceTables>& tables,
                       bool column, std::size_t fixed, std::size_t np, double invScale,
                       std::vector<double>& out) {
  bool any = false;
  for (std::size_t f = 0; f < patch.forces.size(); ++f) {
    const ForceTables& ft = tables[f];
    const double* s = column ? ft.sv.data() : ft.su.data();
    const double* ds = column ? ft.dsv.data() : ft.dsu.data();
    const double across = column ? ft.su[fixed] : ft.sv[fixed];
    const double dAcross = column ? ft.dsu[fixed] : ft.dsv[fixed];
    if (across == 0.0 && dAcross == 0.0) continue;
    if (!any) out.assign(9 * np, 0.0);
    any = true;
    for (int c = 0; c < 3; ++c) {
      const double kv = patch.forces[f].k[c] * across;
      const double kda = kv * invScale, kdc = patch.forces[f].k[c] * dAcross * invScale;
      double* p = out.data() + c * np;
      double* da = out.data() + (3 + c) * np;
      double* dc = out.data() + (6 + c) * np;
      for (std::size_t i = 0; i < np; ++i) {
        p[i] += kv * s[i];
        da[i] += kda * ds[i];
        dc[i] += kdc * s[i];
      }
    }
  }
  return any;
}

/// Values per folded line (row_kernel.cpp lays them out as kField*: its cubic, the
/// quadratics along and across it and the normal's quartic, per component).
constexpr std::size_t kFields = 45;

/// One folded line: its first field (the others at multiples of kLanes after it).
struct LinePolynomials {
  const double* field;
  double sign;  ///< ±1: orients Sa × Sc as the mesh's normals (nrm includes it)
  double operator()(std::size_t f) const { return field[f * kLanes]; }
};

/// Line j of folds stored as foldLines stores them.
inline LinePolynomials foldedLine(const double* folds, std::size_t j, double sign) {
  return {folds + (j / kLanes * kFields) * kLanes + j % kLanes, sign};
}

/// Lines of a patch folded over their fixed parameter, per component, in the line's own
/// parameter x: S = Σ p[i] x^i, the derivative along the line Sa = Σ da[i] x^i and across it
/// Sc = Σ dc[i] x^i (cubic, quadratic, quadratic); da and dc are divided by the patch's size
/// bound. The normal numerator sign·(Sa × Sc) = Σ nrm[i] x^i is a quartic. Stored in chunks
/// of kLanes lines, field by field: field f of line j at (j/kLanes·kFields + f)·kLanes +
/// j%kLanes. Folding a chunk is one vectorised loop over its lines, and a line's fields lie
/// at fixed offsets f·kLanes from its first, which the row kernel reads as broadcasts.
///
/// Folds lines y[0..count) of a patch; y is readable (padded) up to a whole chunk and `out`
/// holds whole chunks. `a` holds the coefficients (per component, monomials as in
/// VertexFramePatch) with its parameters ordered (along, across); y is the across one.
void foldLines(const double (&a)[3][10], const double* __restrict y, std::size_t count, double sign,
               double invScale, double* __restrict out);

/// The row kernel: S and the unit normal at the points x[0..count) (count ≥ kLanes) of one
/// folded line, plus force terms (9 arrays at `forceStride`: position, along, across; x y z
/// each) when `force` is not null. Writes positions and normals as interleaved floats and
/// |Sa × Sc|² (scale-free: a sine²) for degeneracy checks; returns whether some point is
/// degenerate (|Sa × Sc|² not above kDegenerate2, or NaN).
using EvaluateLine = bool (*)(const double*, std::size_t, const LinePolynomials&, const double*,
                              std::size_t, float*, float*, double*);

/// The row kernel compiled for the widest SIMD level this CPU has (simdChoose).
EvaluateLine rowKernel();

}  // namespace pdesurf::detail
