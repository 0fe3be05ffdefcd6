// The spectral and B-spline PDE methods' report() and info() (method.hpp), private to
// src/methods/.
#pragma once

#include <string>

#include "pdesurf/model.hpp"

namespace pdesurf::detail {

ModelReport spectralReport(const SolvedSpectral& solved);
std::string spectralInfo(const SolvedSpectral& solved, const std::string& path,
                         const std::string& name, bool json);

ModelReport bsplineReport(const SolvedBSplinePde& solved);
std::string bsplineInfo(const BSplinePdeModel& model, const SolvedBSplinePde& solved,
                        const std::string& path, bool json);

}  // namespace pdesurf::detail
