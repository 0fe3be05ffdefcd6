// The per-type parts of report() and infoText() (include/pdesurf/model.hpp), private to
// src/model/.
#pragma once

#include <string>

#include "pdesurf/model.hpp"

namespace pdesurf::detail {

ModelReport frameReport(const VertexFrameModel& model, const VertexFrameSurface& surface);
std::string frameInfo(const SolvedModel& solved, const VertexFrameModel& model,
                      const VertexFrameSurface& surface, bool json);

ModelReport spectralReport(const SolvedSpectral& solved);
std::string spectralInfo(const SolvedSpectral& solved, const std::string& path,
                         const std::string& name, bool json);

ModelReport bsplineReport(const SolvedBSplinePde& solved);
std::string bsplineInfo(const BSplinePdeModel& model, const SolvedBSplinePde& solved,
                        const std::string& path, bool json);

}  // namespace pdesurf::detail
