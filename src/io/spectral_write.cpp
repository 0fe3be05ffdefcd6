// Writing spectral and cross-section models (include/pdesurf/spectral_io.hpp): the format
// parseModel reads, laid out like the files in examples/ (one point per line).
#include <stdexcept>
#include <string>
#include <type_traits>

#include "io/json_writer.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

namespace {

using detail::jsonOf;
using detail::ModelJson;

ModelJson curve(const CurveInput& c) {
  if (const auto* s = std::get_if<SampledCurve>(&c)) {
    ModelJson out{{"points", jsonOf(s->points)}};
    if (!s->v.empty()) out["v"] = s->v;
    return out;
  }
  const FourierCurve& f = std::get<FourierCurve>(c);
  ModelJson fourier{{"a0", jsonOf(f.a0)}};
  if (!f.a.empty()) fourier["a"] = jsonOf(f.a);
  if (!f.b.empty()) fourier["b"] = jsonOf(f.b);
  return {{"fourier", std::move(fourier)}};
}

const char* parameterizationName(VParameterization p) {
  return p == VParameterization::Uniform ? "uniform" : "chord-length";
}

/// "type", "name", "description": the head of either document.
ModelJson head(const char* type, const std::string& name, const std::string& description) {
  ModelJson doc{{"type", type}};
  if (!name.empty()) doc["name"] = name;
  if (!description.empty()) doc["description"] = description;
  return doc;
}

}  // namespace

std::string serializeModel(const SpectralModel& m) {
  ModelJson doc = head("spectral", m.name, m.description);
  if (m.op.kind == OperatorKind::Ugail) {
    doc["operator"] = "ugail";
    doc["N"] = m.op.power;
  } else {
    doc["operator"] = "fu";
  }
  doc["a"] = m.op.a;
  doc["modes"] = m.options.modes;
  doc["placement"] = m.options.placement == UPlacement::Given     ? "given"
                     : m.options.placement == UPlacement::Uniform ? "uniform"
                                                                  : "chord-length";
  doc["parameterization"] = parameterizationName(m.options.parameterization);
  doc["remainder"] = m.options.remainder;
  doc["conditions"] = ModelJson::array();
  for (const SpectralCondition& c : m.conditions) {
    ModelJson condition;
    if (c.u) condition["u"] = *c.u;
    condition["derivative"] = c.derivative;
    condition["curve"] = curve(c.curve);
    doc["conditions"].push_back(std::move(condition));
  }
  for (const SpineEdit& e : m.spineEdits)
    doc["spine"].push_back({{"u", e.u}, {"moved", jsonOf(e.moved)}});
  return detail::writeModelJson(doc);
}

std::string serializeModel(const CrossSectionModel& m) {
  ModelJson doc = head("cross-sections", m.name, m.description);
  doc["a"] = m.options.a;
  doc["modes"] = m.options.modes;
  doc["method"] = chainMethodName(m.options.method);
  doc["parameterization"] = parameterizationName(m.options.parameterization);
  doc["remainder"] = m.options.remainder;
  if (m.options.method == ChainMethod::Global) {
    constexpr const char* kSpacing[] = {"centroids", "mean-distance", "uniform"};
    doc["spacing"] = kSpacing[static_cast<int>(m.options.spacing)];
    doc["ends"] = m.options.ends == ChainEnds::Natural ? "natural" : "estimated";
    if (!m.options.u.empty()) doc["u"] = m.options.u;
  }
  doc["curves"] = ModelJson::array();
  for (const CurveInput& c : m.curves) doc["curves"].push_back(curve(c));
  return detail::writeModelJson(doc);
}

}  // namespace pdesurf
