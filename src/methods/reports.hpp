// The spectral and B-spline PDE methods' report() and info() (method.hpp: what `build`
// reports, the values `info` tells), private to src/methods/.
#pragma once

#include <string>

#include "pdesurf/model.hpp"
#include "pdesurf/model_info.hpp"

namespace pdesurf::detail {

ModelReport spectralReport(const SolvedSpectral& solved);
ModelInfo spectralInfo(const SolvedSpectral& solved);

ModelReport bsplineReport(const SolvedBSplinePde& solved);
ModelInfo bsplineInfo(const BSplinePdeModel& model, const SolvedBSplinePde& solved);

}  // namespace pdesurf::detail
