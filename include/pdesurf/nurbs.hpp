// Every pdesurf patch as a bicubic B-spline surface, the form CAD kernels exchange (STEP,
// IGES): exact where the patch is polynomial, an interpolating approximation with a measured
// deviation otherwise (docs/nurbs-export.md). No Open CASCADE here: src/occt/ turns these
// surfaces into faces and files.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/spectral_model.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

// ---------------------------------------------------------------------------------------
// Tolerances.

/// The default export tolerance, relative to the model's bounding-box diagonal.
constexpr double kDefaultRelativeExportTolerance = 1e-4;

/// Relative deviation (to the model's extent) an exact conversion stays within: the Bézier
/// and knot-insertion arithmetic rounds, nothing else (the tests check exact faces with it).
constexpr double kExactNurbsTolerance = 1e-9;

// ---------------------------------------------------------------------------------------
// The surface.

/// A non-rational B-spline surface of degree ≤ 3 in each direction, clamped: each knot
/// vector starts and ends with degree + 1 equal knots, so its parameter domain is
/// [uKnots.front(), uKnots.back()] × [vKnots.front(), vKnots.back()] and its boundary curves
/// are the boundary rows of poles.
struct NurbsSurface {
  std::uint32_t uDegree = 3, vDegree = 3;
  std::vector<double> uKnots, vKnots;  ///< full knot vectors: poles + degree + 1 knots each
  std::uint32_t uCount = 0, vCount = 0;
  std::vector<Vec3> poles;  ///< P_{i,j} = poles[i * vCount + j], i along u

  const Vec3& pole(std::uint32_t i, std::uint32_t j) const { return poles[i * vCount + j]; }
  double uMin() const { return uKnots.front(); }
  double uMax() const { return uKnots.back(); }
  double vMin() const { return vKnots.front(); }
  double vMax() const { return vKnots.back(); }

  Vec3 position(double u, double v) const { return evaluate(u, v).p; }
  /// S, S_u, S_v by de Boor's basis recurrences (u, v clamped to the domain).
  SurfacePoint evaluate(double u, double v) const;
};

/// The polynomial part of a vertex-frame patch (its force terms left out) as a bicubic
/// Bézier patch on [0,1]²: P = M C Mᵀ with M(i,a) = binom(i,a)/binom(3,a) (monomial to
/// Bernstein). Equal to the patch wherever it has no forces.
NurbsSurface bezierPatch(const VertexFramePatch& patch);

/// A B-spline PDE surface exactly, on its domain [0,1]²: clamped knots are copied; uniform
/// knots are clamped at 0 and 1 by knot insertion (Boehm) and the poles outside dropped.
NurbsSurface toNurbs(const BSplineSurface& surface);

/// Force-free evaluation of a vertex-frame patch's polynomial part with unit normal: the
/// ten monomials by Horner in u with v-polynomial coefficients (what a CAD kernel's D1
/// computes, for the benchmark against Open CASCADE). Equals `evaluate` when there are no
/// forces.
struct PolynomialPatchPoint {
  Vec3 p, du, dv, normal;
};
PolynomialPatchPoint evaluatePolynomial(const VertexFramePatch& patch, double u, double v);

/// The same at many independent points at once (any (u, v), no grid), as structure of
/// arrays so that the loop runs in SIMD lanes, one point per lane.
struct PolynomialPatchPoints {
  std::vector<double> x, y, z;     ///< S
  std::vector<double> ux, uy, uz;  ///< S_u
  std::vector<double> vx, vy, vz;  ///< S_v
  std::vector<double> nx, ny, nz;  ///< unit normal S_u × S_v / |S_u × S_v| (0 where it is 0)
  void resize(std::size_t n);
  std::size_t size() const { return x.size(); }
};
/// Resizes `out` to u.size() (= v.size()) and fills point i with the patch at (u[i], v[i]).
void evaluatePolynomial(const VertexFramePatch& patch, std::span<const double> u,
                        std::span<const double> v, PolynomialPatchPoints& out);

// ---------------------------------------------------------------------------------------
// Approximation.

/// A patch given only by its evaluation, on a parameter rectangle.
struct PatchFunction {
  std::function<Vec3(double, double)> position;
  /// Optional, the same on a tensor grid: out[i * vs.size() + j] = S(us[i], vs[j]). Faster
  /// where per-u and per-v tables are shared (spectral patches); used for every sample.
  std::function<void(std::span<const double> us, std::span<const double> vs,
                     std::vector<Vec3>& out)>
      grid;
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
  /// S(u, v0) = S(u, v1) (a spectral patch around its closed direction): the fit then uses
  /// the same samples on both rows, so its two boundary rows of poles are bit-identical.
  bool vClosed = false;
  /// Parameters inside the rectangle where the patch is only C0 (a force region's border):
  /// the fit puts a triple knot there, so the crease costs no refinement.
  std::vector<double> uCreases, vCreases;
};

struct ApproximationOptions {
  double tolerance = 1e-4;          ///< absolute: the largest deviation accepted
  std::uint32_t initialUSpans = 4;  ///< uniform knot spans to start with, per direction
  std::uint32_t initialVSpans = 4;
  std::uint32_t maxSpans = 512;    ///< refinement stops (and fails) past this, per direction
  std::uint32_t checkPerSpan = 4;  ///< deviation samples per span and direction (≥ 2)
};

/// A bicubic fit and the largest deviation from the patch measured on its check grid.
struct Approximation {
  NurbsSurface surface;
  double deviation = 0.0;
  bool withinTolerance = false;  ///< false: maxSpans reached first (surface: the last try)
};

/// The measured deviation an approximation must reach, as a fraction of the tolerance: the
/// check grid samples each span at a few points, the margin covers the error between them.
constexpr double kApproximationSafety = 0.5;

/// Interpolates the patch at the Greville points of clamped cubic knots, uniform between
/// creases (so the fit reproduces cubics, and each boundary curve is the interpolant of the
/// patch's boundary), then measures |fit - patch| on checkPerSpan + 1 points per span in
/// both directions, and doubles the spans of the direction(s) whose error is too large until
/// the deviation is ≤ kApproximationSafety × tolerance.
Approximation approximate(const PatchFunction& patch, const ApproximationOptions& options);

/// max |surface(u,v) - patch(u,v)| on a uniform grid of `samples` × `samples` points over
/// the patch's rectangle (mapped affinely onto the surface's domain).
double measureDeviation(const NurbsSurface& surface, const PatchFunction& patch,
                        std::uint32_t samples);

// ---------------------------------------------------------------------------------------
// Whole models.

struct NurbsExportOptions {
  /// Absolute tolerance of approximated faces; ≤ 0: kDefaultRelativeExportTolerance × the
  /// model's bounding-box diagonal.
  double tolerance = 0.0;
  /// Refinement cap of approximated faces, spans per direction (ApproximationOptions).
  std::uint32_t maxSpans = 512;
  /// A face whose fit misses the tolerance at maxSpans: false throws NurbsToleranceError;
  /// true keeps the finest fit tried, its measured deviation in NurbsFace::deviation and
  /// NurbsFace::withinTolerance false (the CLI does this under its default tolerance).
  bool keepBest = false;
};

/// One patch as one face.
struct NurbsFace {
  NurbsSurface surface;
  std::uint32_t patch = 0;      ///< the patch (frame, chain patch) it comes from
  bool exact = false;           ///< polynomial patch: no approximation
  double deviation = 0.0;       ///< measured max |face - patch| (rounding only when exact)
  bool withinTolerance = true;  ///< false: the finest fit tried missed it (keepBest)
};

struct NurbsModel {
  std::vector<NurbsFace> faces;
  double diagonal = 0.0;   ///< bounding-box diagonal of the model (sampled)
  double tolerance = 0.0;  ///< the absolute tolerance used for approximations
  double maxDeviation() const;
  std::size_t exactCount() const;
  std::size_t overToleranceCount() const;  ///< faces kept with withinTolerance false
};

/// Vertex-frame patches: force-free ones exactly (bezierPatch), the others approximated.
NurbsModel toNurbs(const VertexFrameSurface& surface, const NurbsExportOptions& options = {});
/// Spectral and cross-section patches (on their shown u range, v ∈ [0, 2π]): approximated.
NurbsModel toNurbs(const SolvedSpectral& solved, const NurbsExportOptions& options = {});
/// B-spline PDE surfaces: exactly (toNurbs of each).
NurbsModel toNurbs(std::span<const BSplineSurface> surfaces,
                   const NurbsExportOptions& options = {});

}  // namespace pdesurf
