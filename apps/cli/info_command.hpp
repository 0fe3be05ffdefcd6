// `pdesurf info`'s two layouts of a model's info (include/pdesurf/model_info.hpp: ModelInfo),
// one for every method: the listing (a label column, then each value) and the JSON document.
#pragma once

#include <string>

#include "pdesurf/model_info.hpp"

namespace pdesurf::cli {

/// The listing: "model" with the source (and the name in brackets), then each fact that has a
/// label, in order, its label padded to kInfoLabelWidth and its wording (InfoFact::text, else
/// infoValueText of its value).
std::string infoListing(const ModelInfo& info);
/// The JSON document: "model" (the source), "name", then each fact that has a key, in order
/// (in key order when info.keysSorted), indented by two, with a final newline.
std::string infoJson(const ModelInfo& info);
/// A value as a listing writes it: a string as it is, a number as fmt's "{}" writes it (the
/// shortest that reads back), a flag "yes" or "no", a list "[a, b, c]", a box
/// {"min", "max"} "[min] to [max]", any other record as JSON.
std::string infoValueText(const nlohmann::ordered_json& value);

/// A listing's labels are padded to this width, then a space: "model      path".
constexpr std::size_t kInfoLabelWidth = 10;

}  // namespace pdesurf::cli
