// The one writer of model files (vertex-frames, spectral, cross-sections, bspline-pde): a
// document is built as JSON values, and this lays it out the way the files in examples/ read.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::detail {

/// A model document: keys in the order they are added ("type" first).
using ModelJson = nlohmann::ordered_json;

/// [x, y, z].
ModelJson jsonOf(const Vec3& v);

/// [[x, y, z], ...].
ModelJson jsonOf(const std::vector<Vec3>& points);

/// `doc` as text, indented by two spaces: an array of numbers (a point, indices) on one line;
/// an array of points or objects one element per line; an object on one line when it fits
/// 100 columns (the document itself never); numbers in the shortest form that reads back to
/// the same double; a newline at the end.
std::string writeModelJson(const ModelJson& doc);

}  // namespace pdesurf::detail
