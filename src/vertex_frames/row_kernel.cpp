// The tessellation's row kernel (row_kernel.hpp).
#include "vertex_frames/row_kernel.hpp"

#include <cmath>

#include "numerics/force_shape.hpp"
#include "runtime/simd.hpp"

namespace pdesurf::detail {

namespace {

/// Points per block of the row kernel on rows long enough (two AVX-512 registers of doubles
/// make one register of floats).
constexpr std::size_t kWideBlock = 16;

/// Where a folded line's values lie among its kFields (row_kernel.hpp).
constexpr std::size_t kFieldP = 0;     // p[k][i] at kFieldP + 4k + i
constexpr std::size_t kFieldDa = 12;   // da[k][i] at kFieldDa + 3k + i
constexpr std::size_t kFieldDc = 21;   // dc[k][i] at kFieldDc + 3k + i
constexpr std::size_t kFieldNrm = 30;  // nrm[k][i] at kFieldNrm + 5k + i

/// Calls block(i0) for the starts of whole blocks of B covering [0, count) (count ≥ B), the
/// last one shifted back to end at `count`: it overlaps the block before and rewrites the
/// same values, so that every block is one fixed-length vectorised loop.
template <std::size_t B, typename Block>
PDESURF_ALWAYS_INLINE void forEachBlock(std::size_t count, Block&& block) {
  for (std::size_t i0 = 0;; i0 += B) {
    if (i0 + B > count) i0 = count - B;
    block(i0);
    if (i0 + B >= count) break;
  }
}

/// S and the unit normal at the points x[0..count) (count ≥ B) of one folded line, plus force
/// terms (9 arrays at `forceStride`: position, along, across; x y z each) when Forces. Writes
/// positions and normals as interleaved floats and |Sa × Sc|² (scale-free: a sine²) for
/// degeneracy checks. Without forces the normal is the folded quartic; with them, the cross
/// product per point. The line's coefficients are read once; the points go in blocks of B
/// (forEachBlock). Returns whether some point is degenerate (|Sa × Sc|² not above kDegenerate2, or
/// NaN).
template <std::size_t B, bool Forces>
PDESURF_ALWAYS_INLINE bool evaluateSpan(const double* __restrict x, std::size_t count,
                                        const LinePolynomials& line, const double* __restrict force,
                                        std::size_t forceStride, float* __restrict pos,
                                        float* __restrict nor, double* __restrict cross2) {
  double p[3][4], da[3][3], dc[3][3], nrm[3][5];
  const double sign = line.sign;
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < 4; ++i) p[k][i] = line(kFieldP + 4 * k + i);
    for (std::size_t i = 0; i < 5; ++i) nrm[k][i] = Forces ? 0.0 : line(kFieldNrm + 5 * k + i);
    for (std::size_t i = 0; i < 3; ++i) {
      da[k][i] = Forces ? line(kFieldDa + 3 * k + i) : 0.0;
      dc[k][i] = Forces ? line(kFieldDc + 3 * k + i) : 0.0;
    }
  }
  // Positions, then normals: two loops over the line's blocks, each with fewer values live
  // (its coefficients stay in registers) than one would need.
  forEachBlock<B>(count, [&](std::size_t i0) PDESURF_ALWAYS_INLINE_LAMBDA {
    const double* __restrict t = x + i0;
    const double* __restrict f = Forces ? force + i0 : nullptr;
    float* __restrict po = pos + 3 * i0;
    for (std::size_t i = 0; i < B; ++i) {
      for (int k = 0; k < 3; ++k) {
        double v = p[k][0] + t[i] * (p[k][1] + t[i] * (p[k][2] + t[i] * p[k][3]));
        if constexpr (Forces) v += f[k * forceStride + i];
        po[3 * i + k] = static_cast<float>(v);
      }
    }
  });
  forEachBlock<B>(count, [&](std::size_t i0) PDESURF_ALWAYS_INLINE_LAMBDA {
    const double* __restrict t = x + i0;
    const double* __restrict f = Forces ? force + i0 : nullptr;
    float* __restrict no = nor + 3 * i0;
    double* __restrict c2 = cross2 + i0;
    for (std::size_t i = 0; i < B; ++i) {
      const double ti = t[i];
      double nv[3];
      if constexpr (Forces) {
        double a[3], c[3];
        for (int k = 0; k < 3; ++k) {
          a[k] = da[k][0] + ti * (da[k][1] + ti * da[k][2]) + f[(3 + k) * forceStride + i];
          c[k] = dc[k][0] + ti * (dc[k][1] + ti * dc[k][2]) + f[(6 + k) * forceStride + i];
        }
        nv[0] = sign * (a[1] * c[2] - a[2] * c[1]);
        nv[1] = sign * (a[2] * c[0] - a[0] * c[2]);
        nv[2] = sign * (a[0] * c[1] - a[1] * c[0]);
      } else {
        for (int k = 0; k < 3; ++k)
          nv[k] =
              nrm[k][0] + ti * (nrm[k][1] + ti * (nrm[k][2] + ti * (nrm[k][3] + ti * nrm[k][4])));
      }
      const double len2 = nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2];
      // The length in single precision, which the float normal needs (and where the square
      // root and division cost a fraction of double's). len2 is a sine², at most a few
      // units; where it underflows float the point is degenerate, and its normal is replaced.
      const float inv = 1.0f / std::sqrt(static_cast<float>(len2));
      c2[i] = len2;
      no[3 * i] = static_cast<float>(nv[0]) * inv;
      no[3 * i + 1] = static_cast<float>(nv[1]) * inv;
      no[3 * i + 2] = static_cast<float>(nv[2]) * inv;
    }
  });
  int degenerate = 0;
  for (std::size_t i = 0; i < count; ++i) degenerate |= !(cross2[i] > kDegenerate2);
  return degenerate != 0;
}

/// evaluateSpan with or without forces, in the widest blocks that fit (count ≥ kLanes).
PDESURF_ALWAYS_INLINE bool evaluateLineBody(const double* x, std::size_t count,
                                            const LinePolynomials& r, const double* force,
                                            std::size_t forceStride, float* pos, float* nor,
                                            double* cross2) {
  if (count >= kWideBlock)
    return force ? evaluateSpan<kWideBlock, true>(x, count, r, force, forceStride, pos, nor, cross2)
                 : evaluateSpan<kWideBlock, false>(x, count, r, nullptr, 0, pos, nor, cross2);
  return force ? evaluateSpan<kLanes, true>(x, count, r, force, forceStride, pos, nor, cross2)
               : evaluateSpan<kLanes, false>(x, count, r, nullptr, 0, pos, nor, cross2);
}

/// The row kernel for each SIMD level (src/runtime/simd.hpp).
#define PDESURF_EVALUATE_LINE(name, target)                                              \
  target bool name(const double* x, std::size_t count, const LinePolynomials& r,         \
                   const double* force, std::size_t forceStride, float* pos, float* nor, \
                   double* cross2) {                                                     \
    return evaluateLineBody(x, count, r, force, forceStride, pos, nor, cross2);          \
  }
PDESURF_EVALUATE_LINE(evaluateLineV2, )
PDESURF_EVALUATE_LINE(evaluateLineV3, PDESURF_TARGET_V3)
PDESURF_EVALUATE_LINE(evaluateLineV4, PDESURF_TARGET_V4)
#undef PDESURF_EVALUATE_LINE

}  // namespace

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

/// Folds lines y[0..count) of a patch; y is readable (padded) up to a whole chunk and `out`
/// holds whole chunks. `a` holds the coefficients (per component, monomials as in
/// VertexFramePatch) with its parameters ordered (along, across); y is the across one.
void foldLines(const double (&a)[3][10], const double* __restrict y, std::size_t count, double sign,
               double invScale, double* __restrict out) {
  for (std::size_t chunk = 0; chunk < count; chunk += kLanes) {
    double* __restrict o = out + chunk * kFields;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double y1 = y[chunk + l], y2 = y1 * y1, y3 = y2 * y1;
      double da[3][3], dc[3][3];
      for (int k = 0; k < 3; ++k) {
        const double* c = a[k];
        const double p1 = c[1] + y1 * c[7] + y2 * c[9], p2 = c[2] + y1 * c[8];
        o[(kFieldP + 4 * k) * kLanes + l] = c[0] + y1 * c[4] + y2 * c[5] + y3 * c[6];
        o[(kFieldP + 4 * k + 1) * kLanes + l] = p1;
        o[(kFieldP + 4 * k + 2) * kLanes + l] = p2;
        o[(kFieldP + 4 * k + 3) * kLanes + l] = c[3];
        da[k][0] = p1 * invScale;
        da[k][1] = 2.0 * p2 * invScale;
        da[k][2] = 3.0 * c[3] * invScale;
        dc[k][0] = (c[4] + 2.0 * y1 * c[5] + 3.0 * y2 * c[6]) * invScale;
        dc[k][1] = (c[7] + 2.0 * y1 * c[9]) * invScale;
        dc[k][2] = c[8] * invScale;
        for (int i = 0; i < 3; ++i) {
          o[(kFieldDa + 3 * k + i) * kLanes + l] = da[k][i];
          o[(kFieldDc + 3 * k + i) * kLanes + l] = dc[k][i];
        }
      }
      // nrm = sign · Σ_{i+l=m} da_i × dc_l, the coefficients of the product of the quadratics.
      double m[3][5] = {};
      for (int i = 0; i < 3; ++i)
        for (int q = 0; q < 3; ++q) {
          m[0][i + q] += da[1][i] * dc[2][q] - da[2][i] * dc[1][q];
          m[1][i + q] += da[2][i] * dc[0][q] - da[0][i] * dc[2][q];
          m[2][i + q] += da[0][i] * dc[1][q] - da[1][i] * dc[0][q];
        }
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 5; ++i) o[(kFieldNrm + 5 * k + i) * kLanes + l] = sign * m[k][i];
    }
  }
}

EvaluateLine rowKernel() {
  return simdChoose<EvaluateLine>(evaluateLineV2, evaluateLineV3, evaluateLineV4);
}

}  // namespace pdesurf::detail
