// The model-file writer (src/io/json_writer.hpp).
#include "io/json_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include <fmt/format.h>

namespace pdesurf::detail {
namespace {

constexpr std::size_t kLineWidth = 100;

/// `value` on one line: ", " between elements, ": " after keys.
std::string inlineText(const ModelJson& value) {
  if (value.is_number_float()) {
    // The shortest text that reads back to the same double; -0 as "-0.0", since "-0" reads
    // back as the integer 0.
    const double x = value.get<double>();
    return x == 0 && std::signbit(x) ? "-0.0" : fmt::format("{}", x);
  }
  if (value.is_object()) {
    std::string out = "{";
    for (auto it = value.begin(); it != value.end(); ++it)
      out += (it == value.begin() ? "" : ", ") + ModelJson(it.key()).dump() + ": " +
             inlineText(it.value());
    return out + "}";
  }
  if (value.is_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + inlineText(value[i]);
    return out + "]";
  }
  return value.dump();  // strings (escaped), integers, booleans, null
}

/// `value` starting at column `column` of a line indented by `indent`: an array of numbers
/// or strings on one line, an object on one line when it fits (and not `spread`), anything
/// else one member or element per line.
std::string layOut(const ModelJson& value, std::size_t indent, std::size_t column,
                   bool spread = false) {
  const auto primitive = [](const ModelJson& v) { return v.is_primitive(); };
  if (!value.is_structured() || value.empty() ||
      (value.is_array() && std::all_of(value.begin(), value.end(), primitive)))
    return inlineText(value);
  if (value.is_object() && !spread) {
    std::string line = inlineText(value);
    if (column + line.size() <= kLineWidth) return line;
  }
  const std::string inner(indent + 2, ' ');
  std::string out = value.is_object() ? "{\n" : "[\n";
  std::size_t i = 0;
  for (auto it = value.begin(); it != value.end(); ++it, ++i) {
    std::string head = inner;
    if (value.is_object()) head += ModelJson(it.key()).dump() + ": ";
    out +=
        head + layOut(it.value(), indent + 2, head.size()) + (i + 1 < value.size() ? ",\n" : "\n");
  }
  return out + std::string(indent, ' ') + (value.is_object() ? "}" : "]");
}

}  // namespace

ModelJson jsonOf(const Vec3& v) { return ModelJson::array({v.x(), v.y(), v.z()}); }

ModelJson jsonOf(const std::vector<Vec3>& points) {
  ModelJson out = ModelJson::array();
  for (const Vec3& p : points) out.push_back(jsonOf(p));
  return out;
}

std::string writeModelJson(const ModelJson& doc) { return layOut(doc, 0, 0, true) + "\n"; }

}  // namespace pdesurf::detail
