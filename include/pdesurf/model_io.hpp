// Model files: JSON documents with a "type" (docs/model-format.md), read into the model
// layer's AnyModel and written back; the vertex-frame type's own reader and writer.
// spectral_io.hpp and bspline_pde_io.hpp write the other types.
#pragma once

#include <string>
#include <string_view>

#include "pdesurf/error.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// Parses and validates a model of any type (by its "type"); `source` names it in errors.
AnyModel parseModel(std::string_view text, const std::string& source);
/// Reads and parses a model file of any type (errors name the path).
AnyModel loadModel(const std::string& path);

/// The model as JSON text that parseModel reads back to the same model (numbers written
/// shortest round-trip).
std::string serializeModel(const AnyModel& model);

/// A force has no particular solution when a1/Lu² + a2/Lv² vanishes; it counts as vanishing
/// when it is below this fraction of |a1|/Lu² + |a2|/Lv². Rounding in Lu = u1 - u0 and the
/// divisions leaves a few 1e-16 of that sum where the exact value is 0; a real value this
/// small would displace the surface by 1e12 × f0, which no model means.
constexpr double kForceSolvabilityTolerance = 1e-12;

/// Parses and validates a `"type": "vertex-frames"` model; `source` names it in errors.
/// Everything a solver assumes is checked here: counts, types, finite numbers, indices,
/// shared edges that agree, force regions, and forces whose PDE has a solution.
VertexFrameModel parseVertexFrameModel(std::string_view text, const std::string& source);

/// Reads and parses a model file (errors name the path).
VertexFrameModel loadVertexFrameModel(const std::string& path);

/// The model as JSON text that parseVertexFrameModel reads back to the same model
/// (numbers written shortest round-trip; defaults omitted).
std::string serializeVertexFrameModel(const VertexFrameModel& model);

/// `written` (serializeModel's text of a model of any type read from `original`, then perhaps
/// edited) with the fields of `original` that the model's method does not hold (what its
/// writer does not write for the original's model: "description", a frame's or a tool's own
/// fields), matched by identity: the same key path, and in an array the element the writer
/// wrote unchanged (wherever it moved; else the one at its index while both arrays are as
/// long); in the original's key order. `written` unchanged when it has no such field to
/// keep, when `original` is not a model file, or when the kept fields would change the model.
std::string keepUnknownFields(const std::string& written, std::string_view original);

}  // namespace pdesurf
