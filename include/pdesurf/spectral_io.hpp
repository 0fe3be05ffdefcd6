// Model files of the spectral engine: `"type": "spectral"` and `"type": "cross-sections"`
// (spectral_model.hpp holds the models), and the Fourier curves files. docs/model-format.md
// describes both; docs/spectral.md the mathematics.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf {

/// The model as JSON text that parseModel reads back to the same model (numbers written
/// shortest round-trip, every option written out).
std::string serializeModel(const SpectralModel& model);
std::string serializeModel(const CrossSectionModel& model);

/// Parses one closed curve as written in model files: {"points": [[x,y,z], ...], "v": [...]}
/// or {"fourier": {"a0": [x,y,z], "a": [[...], ...], "b": [[...], ...]}}; `path` is its
/// JSON path in errors.
CurveInput parseCurve(std::string_view json, const std::string& source, const std::string& path);

/// The curves of a curves file: a cross-sections model, or {"curves": [curve, ...]}.
std::vector<CurveInput> loadCurves(const std::string& path);

}  // namespace pdesurf
