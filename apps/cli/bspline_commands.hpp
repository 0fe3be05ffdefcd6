// The CLI's side of the B-spline PDE engine: build summaries, sample and info of
// "bspline-pde" models (docs/bspline-pde.md).
#pragma once

#include <cstdint>
#include <string>

#include "pdesurf/bspline_pde_io.hpp"

namespace pdesurf::cli {

/// "bspline-pde, 1 piece, 6 x 6 control points, clamped knots" for `build`.
std::string bsplineSummary(const SolvedBSplinePde& solved);
/// "PDE residual 3e-16" (+ ", C1 gap 1e-14" for blends) for `build`.
std::string bsplineQuality(const SolvedBSplinePde& solved);

/// `sample`: {"patches": [{"patch": k, "grid": N, "origin": [p, q], "points": [...]}]} with
/// points[j*N+i] = x(i/(N−1), j/(N−1)) of piece k (local parameters).
std::string bsplineSampleJson(const SolvedBSplinePde& solved, std::uint32_t grid);

/// `info` for B-spline PDE models (text or JSON).
std::string bsplineInfoText(const BSplinePdeModel& model, const SolvedBSplinePde& solved,
                            const std::string& path, bool json);

}  // namespace pdesurf::cli
