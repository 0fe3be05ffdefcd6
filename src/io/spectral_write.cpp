// Writing spectral and cross-section models (include/pdesurf/spectral_io.hpp): the format
// parseModel reads, laid out like the files in examples/ (one point per line).
#include <stdexcept>
#include <string>
#include <type_traits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

namespace {

std::string vec(const Vec3& v) { return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z()); }

std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

/// Points, one per line at `indent`, as a JSON array.
std::string pointList(const std::vector<Vec3>& points, const std::string& indent) {
  std::string out = "[\n";
  for (std::size_t i = 0; i < points.size(); ++i)
    out += fmt::format("{}  {}{}\n", indent, vec(points[i]), i + 1 < points.size() ? "," : "");
  return out + indent + "]";
}

/// A curve object at `indent` (its first line is not indented).
std::string curve(const CurveInput& c, const std::string& indent) {
  if (const auto* s = std::get_if<SampledCurve>(&c)) {
    std::string out =
        fmt::format("{{\n{}  \"points\": {}", indent, pointList(s->points, indent + "  "));
    if (!s->v.empty()) out += fmt::format(",\n{}  \"v\": [{}]", indent, fmt::join(s->v, ", "));
    return out + fmt::format("\n{}}}", indent);
  }
  const FourierCurve& f = std::get<FourierCurve>(c);
  std::string out = fmt::format("{{\"fourier\": {{\"a0\": {}", vec(f.a0));
  for (const auto* list : {&f.a, &f.b}) {
    if (list->empty()) continue;
    std::vector<std::string> items;
    for (const Vec3& v : *list) items.push_back(vec(v));
    out += fmt::format(", \"{}\": [{}]", list == &f.a ? "a" : "b", fmt::join(items, ", "));
  }
  return out + "}}";
}

const char* parameterizationName(VParameterization p) {
  return p == VParameterization::Uniform ? "uniform" : "chord-length";
}

/// "type", "name", "description": the head of either document.
std::string head(const char* type, const std::string& name, const std::string& description) {
  std::string out = fmt::format("{{\n  \"type\": \"{}\",\n", type);
  if (!name.empty()) out += fmt::format("  \"name\": {},\n", quoted(name));
  if (!description.empty()) out += fmt::format("  \"description\": {},\n", quoted(description));
  return out;
}

}  // namespace

std::string serializeModel(const SpectralModel& m) {
  std::string out = head("spectral", m.name, m.description);
  if (m.op.kind == OperatorKind::Ugail)
    out +=
        fmt::format("  \"operator\": \"ugail\",\n  \"N\": {},\n  \"a\": {},\n", m.op.power, m.op.a);
  else
    out += fmt::format("  \"operator\": \"fu\",\n  \"a\": {},\n", m.op.a);
  const char* placement = m.options.placement == UPlacement::Given     ? "given"
                          : m.options.placement == UPlacement::Uniform ? "uniform"
                                                                       : "chord-length";
  out += fmt::format(
      "  \"modes\": {},\n  \"placement\": \"{}\",\n  \"parameterization\": \"{}\",\n"
      "  \"remainder\": {},\n  \"conditions\": [\n",
      m.options.modes, placement, parameterizationName(m.options.parameterization),
      m.options.remainder);
  for (std::size_t i = 0; i < m.conditions.size(); ++i) {
    const SpectralCondition& c = m.conditions[i];
    out += "    {";
    if (c.u) out += fmt::format("\"u\": {}, ", *c.u);
    out += fmt::format("\"derivative\": {}, \"curve\": {}}}{}\n", c.derivative,
                       curve(c.curve, "    "), i + 1 < m.conditions.size() ? "," : "");
  }
  out += "  ]";
  if (!m.spineEdits.empty()) {
    out += ",\n  \"spine\": [\n";
    for (std::size_t e = 0; e < m.spineEdits.size(); ++e) {
      std::vector<std::string> moved;
      for (const Vec3& p : m.spineEdits[e].moved) moved.push_back(vec(p));
      out += fmt::format("    {{\"u\": [{}], \"moved\": [{}]}}{}\n",
                         fmt::join(m.spineEdits[e].u, ", "), fmt::join(moved, ", "),
                         e + 1 < m.spineEdits.size() ? "," : "");
    }
    out += "  ]";
  }
  return out + "\n}\n";
}

std::string serializeModel(const CrossSectionModel& m) {
  std::string out = head("cross-sections", m.name, m.description);
  out += fmt::format(
      "  \"a\": {},\n  \"modes\": {},\n  \"method\": \"{}\",\n  \"parameterization\": \"{}\",\n"
      "  \"remainder\": {},\n",
      m.options.a, m.options.modes, chainMethodName(m.options.method),
      parameterizationName(m.options.parameterization), m.options.remainder);
  if (m.options.method == ChainMethod::Global) {
    constexpr const char* kSpacing[] = {"centroids", "mean-distance", "uniform"};
    out += fmt::format("  \"spacing\": \"{}\",\n  \"ends\": \"{}\",\n",
                       kSpacing[static_cast<int>(m.options.spacing)],
                       m.options.ends == ChainEnds::Natural ? "natural" : "estimated");
    if (!m.options.u.empty()) out += fmt::format("  \"u\": [{}],\n", fmt::join(m.options.u, ", "));
  }
  out += "  \"curves\": [\n";
  for (std::size_t i = 0; i < m.curves.size(); ++i)
    out +=
        fmt::format("    {}{}\n", curve(m.curves[i], "    "), i + 1 < m.curves.size() ? "," : "");
  return out + "  ]\n}\n";
}

std::string serializeModel(const AnyModel& model) {
  return std::visit(
      [](const auto& m) -> std::string {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, VertexFrameModel>)
          return serializeVertexFrameModel(m);
        else
          return serializeModel(m);
      },
      model);
}

}  // namespace pdesurf
