// Model files of the B-spline PDE engine: `"type": "bspline-pde"` (bspline_pde_model.hpp
// holds the model). docs/model-format.md describes the file.
#pragma once

#include <string>

#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf {

/// The model as a file (docs/model-format.md): numbers in their shortest round-trip form;
/// parseModel of the text gives the same model.
std::string serializeModel(const BSplinePdeModel& model);

}  // namespace pdesurf
