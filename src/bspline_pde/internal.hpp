// Private pieces of the B-spline PDE engine shared by its sources and tests: cubic basis
// evaluation, net validation (the banded LU is src/numerics/banded_lu.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "numerics/banded_lu.hpp"
#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/error.hpp"

namespace pdesurf::bspline {

/// The span s (3 ≤ s ≤ n) with knots[s] ≤ t < knots[s+1]; t at or past knots[n] gives n, t
/// below knots[4] gives 3 (the end polynomials extend beyond the domain).
std::uint32_t findSpan(std::span<const double> knots, std::uint32_t n, double t);

/// The 4 non-zero cubic basis functions at t and their derivatives up to the third
/// (Piegl & Tiller, The NURBS Book, A2.3, for degree 3).
CubicBasis cubicBasis(std::span<const double> knots, std::uint32_t n, double t);

/// The segments per knot span for a tessellation of `resolution` (≥ 2) samples per side: the
/// fewest that give at least resolution − 1 along the side with more spans.
std::uint32_t segmentsPerSpan(const BSplineSurface& surface, std::uint32_t resolution);

/// The grid mesh of tessellate(BSplineSurface) for `segments` (≥ 1) segments a knot span.
Mesh tessellateSpans(const BSplineSurface& surface, std::uint32_t segments);

/// Throws InvalidArgument unless nu, nv ≥ 3, the point count is (nu+1)(nv+1) and every
/// point (every given point when `innerExempt`) is finite. `where` starts each message.
void validateNet(const ControlNet& net, bool innerExempt, std::string_view where);

/// Least-squares control points 0..n on cubic knots of `knots` type for values at parameters
/// in [0, 1]; with `pinEnds`, the first and last control points are the first and last values
/// (clamped ends interpolate). Throws InvalidArgument, starting with `where`, when the
/// samples are too few or leave a control point undetermined.
std::vector<Vec3> fitControlPoints(const std::vector<Vec3>& values,
                                   const std::vector<double>& params, KnotType knots,
                                   std::uint32_t n, bool pinEnds, const std::string& where);

/// fitControlPoints of f sampled at kBoundaryResampleFactor (n + 1) + 1 uniform parameters;
/// throws InvalidArgument where f is not finite.
std::vector<Vec3> fitFunction(const std::function<Vec3(double)>& f, KnotType knots, std::uint32_t n,
                              bool pinEnds, const std::string& where);

using numerics::BandedLu;
using numerics::RowMatrix;

}  // namespace pdesurf::bspline
