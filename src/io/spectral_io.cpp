// Parsing and validation of spectral and cross-section model files (docs/model-format.md),
// and the dispatch on "type" for every model file.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "io/model_reader.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

using detail::Json;
using detail::Reader;
using detail::typeName;

namespace {

/// The largest number of Fourier modes a model may ask for: the engine is checked up to
/// M = 32 (docs/spectral.md); beyond 64 the exponentials e^{-a n u} underflow for any a ≥ 1
/// over most of the patch and the modes carry nothing.
constexpr std::uint32_t kMaxModes = 64;
/// Ugail's N: order 2N up to 80 (the Klein bottle is order 40).
constexpr std::uint32_t kMaxUgailPower = 40;

/// The spectral types' readers: closed curves and the options both types share.
class SpectralReader : public detail::ModelReader {
 public:
  using ModelReader::ModelReader;

  /// A closed curve: points (with optional v) or Fourier coefficients. `modes` > 0: the
  /// points must be enough to fit that many modes.
  CurveInput curve(const Json& j, const std::string& path, std::uint32_t modes) const {
    expectObject(j, path);
    const bool hasPoints = j.contains("points"), hasFourier = j.contains("fourier");
    if (hasPoints == hasFourier)
      fail(path, "a curve has either \"points\" (with optional \"v\") or \"fourier\"");
    if (hasFourier) {
      onlyMembers(j, path, {"fourier"});
      const std::string fp = path + ".fourier";
      const Json& f = j["fourier"];
      expectObject(f, fp);
      onlyMembers(f, fp, {"a0", "a", "b"});
      FourierCurve c;
      c.a0 = vec3(member(f, fp, "a0"), fp + ".a0");
      for (const char* key : {"a", "b"}) {
        auto& out = key[0] == 'a' ? c.a : c.b;
        if (auto it = f.find(key); it != f.end()) {
          expectArray(*it, fmt::format("{}.{}", fp, key), 0);
          for (std::size_t n = 0; n < it->size(); ++n)
            out.push_back(vec3((*it)[n], fmt::format("{}.{}[{}]", fp, key, n)));
        }
      }
      const std::size_t terms = std::max(c.a.size(), c.b.size());
      c.a.resize(terms, Vec3::Zero());  // a missing "b" (or shorter list) is zeros
      c.b.resize(terms, Vec3::Zero());
      return c;
    }
    onlyMembers(j, path, {"points", "v"});
    SampledCurve c;
    const Json& pts = j["points"];
    const std::string pp = path + ".points";
    expectArray(pts, pp, 3);
    for (std::size_t i = 0; i < pts.size(); ++i)
      c.points.push_back(vec3(pts[i], fmt::format("{}[{}]", pp, i)));
    if (auto it = j.find("v"); it != j.end()) {
      const std::string vp = path + ".v";
      expectArray(*it, vp, 0);
      if (it->size() != pts.size())
        fail(vp, fmt::format("expected one v per point ({}), found {}", pts.size(), it->size()));
      for (std::size_t i = 0; i < it->size(); ++i) {
        const std::string ip = fmt::format("{}[{}]", vp, i);
        const double v = number((*it)[i], ip);
        if (v < 0.0 || v >= 2.0 * std::numbers::pi)
          fail(ip, fmt::format("v = {} lies outside [0, 2π)", v));
        if (i > 0 && !(v > c.v.back()))
          fail(ip, fmt::format("v values must increase: {} follows {}", v, c.v.back()));
        c.v.push_back(v);
      }
    }
    std::size_t distinct = c.points.size();
    if (c.v.empty() && c.points.size() > 1 && c.points.front() == c.points.back()) --distinct;
    if (modes > 0 && distinct < 2 * std::size_t{modes} + 1)
      fail(pp, fmt::format("{} points cannot determine {} Fourier modes: give at least {} "
                           "points or fewer \"modes\"",
                           distinct, modes, 2 * modes + 1));
    return c;
  }

  /// The options both model types share.
  void common(const Json& doc, std::uint32_t& modes, VParameterization& parameterization,
              bool& remainder) const {
    if (auto it = doc.find("modes"); it != doc.end()) modes = integer(*it, "$.modes", 0, kMaxModes);
    if (auto it = doc.find("parameterization"); it != doc.end())
      parameterization =
          choice<VParameterization>(*it, "$.parameterization",
                                    {{"chord-length", VParameterization::ChordLength},
                                     {"uniform", VParameterization::Uniform}});
    if (auto it = doc.find("remainder"); it != doc.end()) remainder = boolean(*it, "$.remainder");
  }
};

SpectralModel parseSpectral(const Json& doc, const SpectralReader& rd) {
  rd.onlyMembers(doc, "$",
                 {"type", "name", "description", "operator", "N", "a", "modes", "placement",
                  "parameterization", "remainder", "conditions", "spine"});
  SpectralModel m;
  rd.header(doc, m.name, m.description);
  rd.common(doc, m.options.modes, m.options.parameterization, m.options.remainder);

  const OperatorKind kind =
      rd.choice<OperatorKind>(rd.member(doc, "$", "operator"), "$.operator",
                              {{"ugail", OperatorKind::Ugail}, {"fu", OperatorKind::Fu}});
  if (kind == OperatorKind::Ugail) {
    const std::uint32_t n = rd.integer(rd.member(doc, "$", "N"), "$.N", 1, kMaxUgailPower);
    std::optional<double> a;
    if (auto it = doc.find("a"); it != doc.end()) {
      a = rd.number(*it, "$.a");
      if (!(*a > 0.0)) rd.fail("$.a", fmt::format("Ugail's a must be positive, found {}", *a));
    }
    m.op = SpectralOperator::ugail(n, a);
  } else {
    if (doc.contains("N"))
      rd.fail("$.N", "\"N\" belongs to the \"ugail\" operator (\"fu\" is sixth order)");
    const double a = rd.number(rd.member(doc, "$", "a"), "$.a");
    if (a == 0.0)
      rd.fail("$.a", "a = 0 leaves ∂⁶u X = 0, which does not couple v: use a > 0 or a < 0");
    m.op = SpectralOperator::fu(a);
  }

  const Json& list = rd.member(doc, "$", "conditions");
  const std::uint32_t order = m.op.order();
  rd.expectArray(list, "$.conditions", 1);
  if (list.size() != order)
    rd.fail("$.conditions",
            fmt::format("an order-{} operator takes exactly {} conditions, found {}", order, order,
                        list.size()));
  bool allHaveU = true;
  std::set<std::pair<double, std::uint32_t>> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("$.conditions[{}]", i);
    const Json& jc = list[i];
    rd.expectObject(jc, path);
    rd.onlyMembers(jc, path, {"u", "derivative", "curve"});
    SpectralCondition c;
    if (auto it = jc.find("derivative"); it != jc.end())
      c.derivative = rd.integer(*it, path + ".derivative", 0, order - 1);
    if (auto it = jc.find("u"); it != jc.end()) {
      c.u = rd.number(*it, path + ".u");
      if (!seen.insert({*c.u, c.derivative}).second)
        rd.fail(path, fmt::format("a second condition on the {} at u = {}",
                                  c.derivative == 0 ? std::string("position")
                                                    : fmt::format("derivative {}", c.derivative),
                                  *c.u));
    } else {
      allHaveU = false;
      if (c.derivative > 0 && i == 0)
        rd.fail(path,
                "a derivative condition without \"u\" takes the u of the position "
                "condition before it, and this one has none");
    }
    c.curve = rd.curve(rd.member(jc, path, "curve"), path + ".curve", m.options.modes);
    m.conditions.push_back(std::move(c));
  }
  m.options.placement = allHaveU ? UPlacement::Given : UPlacement::Uniform;
  if (auto it = doc.find("placement"); it != doc.end())
    m.options.placement = rd.choice<UPlacement>(*it, "$.placement",
                                                {{"given", UPlacement::Given},
                                                 {"uniform", UPlacement::Uniform},
                                                 {"chord-length", UPlacement::ChordLength}});
  if (m.options.placement == UPlacement::Given && !allHaveU)
    for (std::size_t i = 0; i < list.size(); ++i)
      if (!list[i].contains("u"))
        rd.fail(fmt::format("$.conditions[{}]", i),
                "\"placement\": \"given\" needs a \"u\" on every condition");

  if (auto it = doc.find("spine"); it != doc.end()) {
    rd.expectArray(*it, "$.spine", 0);
    for (std::size_t e = 0; e < it->size(); ++e) {
      const std::string path = fmt::format("$.spine[{}]", e);
      const Json& je = (*it)[e];
      rd.expectObject(je, path);
      rd.onlyMembers(je, path, {"u", "moved"});
      const Json& us = rd.member(je, path, "u");
      const Json& moved = rd.member(je, path, "moved");
      rd.expectArray(us, path + ".u", 1);
      rd.expectArray(moved, path + ".moved", 1);
      if (us.size() != moved.size())
        rd.fail(path, fmt::format("\"u\" has {} values and \"moved\" {} points: one point per u",
                                  us.size(), moved.size()));
      SpineEdit edit;
      for (std::size_t j = 0; j < us.size(); ++j) {
        const std::string up = fmt::format("{}.u[{}]", path, j);
        edit.u.push_back(rd.number(us[j], up));
        if (j > 0 && !(edit.u[j] > edit.u[j - 1]))
          rd.fail(up,
                  fmt::format("u values must increase: {} follows {}", edit.u[j], edit.u[j - 1]));
        edit.moved.push_back(rd.vec3(moved[j], fmt::format("{}.moved[{}]", path, j)));
      }
      m.spineEdits.push_back(std::move(edit));
    }
  }
  return m;
}

CrossSectionModel parseCrossSections(const Json& doc, const SpectralReader& rd) {
  rd.onlyMembers(doc, "$",
                 {"type", "name", "description", "a", "modes", "method", "parameterization",
                  "remainder", "spacing", "u", "ends", "curves"});
  CrossSectionModel m;
  rd.header(doc, m.name, m.description);
  rd.common(doc, m.options.modes, m.options.parameterization, m.options.remainder);
  if (auto it = doc.find("a"); it != doc.end()) {
    m.options.a = rd.number(*it, "$.a");
    if (m.options.a == 0.0)
      rd.fail("$.a", "a = 0 leaves ∂⁶u X = 0, which does not couple v: use a > 0 or a < 0");
  }
  if (auto it = doc.find("method"); it != doc.end())
    m.options.method = rd.choice<ChainMethod>(*it, "$.method",
                                              {{"global", ChainMethod::Global},
                                               {"c2", ChainMethod::ExactC2},
                                               {"shared-curves", ChainMethod::SharedCurves}});
  const bool global = m.options.method == ChainMethod::Global;
  for (const char* key : {"spacing", "u", "ends"})
    if (!global && doc.contains(key))
      rd.fail(fmt::format("$.{}", key),
              fmt::format("\"{}\" belongs to the \"global\" method, not \"{}\"", key,
                          chainMethodName(m.options.method)));
  if (auto it = doc.find("spacing"); it != doc.end())
    m.options.spacing = rd.choice<ChainSpacing>(*it, "$.spacing",
                                                {{"centroids", ChainSpacing::Centroids},
                                                 {"mean-distance", ChainSpacing::MeanDistance},
                                                 {"uniform", ChainSpacing::Uniform}});
  if (auto it = doc.find("ends"); it != doc.end())
    m.options.ends = rd.choice<ChainEnds>(
        *it, "$.ends", {{"natural", ChainEnds::Natural}, {"estimated", ChainEnds::Estimated}});
  const std::size_t minCurves = global ? 2 : m.options.method == ChainMethod::ExactC2 ? 4 : 6;
  const Json& list = rd.member(doc, "$", "curves");
  rd.expectArray(list, "$.curves", 0);
  if (list.size() < minCurves)
    rd.fail("$.curves", fmt::format("the \"{}\" method needs at least {} curves, found {}",
                                    chainMethodName(m.options.method), minCurves, list.size()));
  if (auto it = doc.find("u"); it != doc.end()) {
    rd.expectArray(*it, "$.u", 0);
    if (it->size() != list.size())
      rd.fail("$.u",
              fmt::format("expected one u per curve ({}), found {}", list.size(), it->size()));
    for (std::size_t i = 0; i < it->size(); ++i) {
      const std::string ip = fmt::format("$.u[{}]", i);
      const double x = rd.number((*it)[i], ip);
      if (i > 0 && !(x > m.options.u.back()))
        rd.fail(ip, fmt::format("u values must increase: {} follows {}", x, m.options.u.back()));
      m.options.u.push_back(x);
    }
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    m.curves.push_back(rd.curve(list[i], fmt::format("$.curves[{}]", i), m.options.modes));
  return m;
}

}  // namespace

namespace detail {

SpectralModel parseSpectralDocument(const Json& doc, const std::string& source) {
  return parseSpectral(doc, SpectralReader(source));
}

CrossSectionModel parseCrossSectionsDocument(const Json& doc, const std::string& source) {
  return parseCrossSections(doc, SpectralReader(source));
}

}  // namespace detail

CurveInput parseCurve(std::string_view json, const std::string& source, const std::string& path) {
  SpectralReader rd(source);
  return rd.curve(rd.parseDocument(json), path, 0);
}

std::vector<CurveInput> loadCurves(const std::string& path) {
  SpectralReader rd(path);
  const Json doc = rd.parseDocument(detail::readModelFile(path));
  rd.expectObject(doc, "$");
  const Json& list = rd.member(doc, "$", "curves");
  rd.expectArray(list, "$.curves", 1);
  std::vector<CurveInput> curves;
  for (std::size_t i = 0; i < list.size(); ++i)
    curves.push_back(rd.curve(list[i], fmt::format("$.curves[{}]", i), 0));
  return curves;
}

}  // namespace pdesurf
