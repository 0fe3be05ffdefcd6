// What `info` tells of a solved model, as values (ModelInfo): every method lists its own
// (SurfaceMethod::info) and the front ends write them, the CLI's `pdesurf info` as a listing or
// as JSON (apps/cli/info_command.cpp), the Python package's Surface.info() as a dict. The
// library lays out no text and writes no JSON document here.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/geometry.hpp"

namespace pdesurf {

class SolvedModel;

/// One value `info` reports, with its label for a listing and its key for JSON. A plain value
/// (a count, a name, a number, a flag, a box) leaves `text` empty and is written as it is; a
/// value a listing words with more ("3 (1 pinned to 0)") gives that wording in `text`.
struct InfoFact {
  std::string label;  ///< the listing's label ("strips", "C0 gap"); empty: in JSON only
  std::string key;    ///< the JSON member ("strips", "c0_gap"); empty: in the listing only
  /// A number, a string, a flag, a point [x, y, z], a box {"min": point, "max": point}, or a
  /// list or record of such values.
  nlohmann::ordered_json value;
  std::string text;  ///< the listing's wording of the value; empty: the value as it is
};

/// What `info` tells of a solved model: the model's file and name, and its method's values
/// in the order a listing shows them (SurfaceMethod::info; the default: type, patch count,
/// largest C0 gap, bounding box).
struct ModelInfo {
  std::string source;  ///< the model's file (SolvedModel::source)
  std::string name;    ///< the model's own name; empty when it has none
  std::vector<InfoFact> facts;
  /// JSON lists the members by key, not in the facts' order (vertex frames' `info --json`
  /// always has).
  bool keysSorted = false;

  /// The fact of JSON member `key`, else nullptr.
  const InfoFact* find(std::string_view key) const;
};

/// The model's info: its source and name, and its method's facts (SurfaceMethod::info).
ModelInfo modelInfo(const SolvedModel& solved);

/// The fact "bbox": the box from `min` to `max` ([x, y, z] to [x, y, z] in a listing).
InfoFact boxFact(const Vec3& min, const Vec3& max);

}  // namespace pdesurf
