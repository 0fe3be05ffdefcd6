// Parsing, validation and solving of "bspline-pde" model files (docs/model-format.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_writer.hpp"
#include "io/model_reader.hpp"
#include "pdesurf/bspline_pde_io.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf {

using detail::Json;
using detail::ModelReader;

namespace {

/// The largest last control index a file may ask for: the Kronecker solve handles far more,
/// but cond(M) ≈ 0.2 n³ (docs/bspline-pde.md §Accuracy) makes n > 1000 lose 9 digits.
constexpr std::uint32_t kMaxNetIndex = 1000;
/// The blends' dense constraint solve is O(n⁶) (docs/bspline-pde.md): n = 24 takes seconds.
constexpr std::uint32_t kMaxBlendIndex = 24;

class BSplineReader : public ModelReader {
 public:
  using ModelReader::ModelReader;

  KnotType knotType(const Json& j, const std::string& path) const {
    return choice<KnotType>(j, path,
                            {{"clamped", KnotType::Clamped}, {"uniform", KnotType::Uniform}});
  }

  std::vector<Vec3> points(const Json& j, const std::string& path, std::size_t minSize) const {
    expectArray(j, path, minSize);
    std::vector<Vec3> out;
    for (std::size_t k = 0; k < j.size(); ++k)
      out.push_back(vec3(j[k], fmt::format("{}[{}]", path, k)));
    return out;
  }

  /// {"bspline": [...], "knots": ...}: a cubic B-spline curve (at least 4 points).
  BSplineCurve bsplineCurve(const Json& j, const std::string& path) const {
    BSplineCurve c;
    c.points = points(member(j, path, "bspline"), path + ".bspline", 4);
    if (auto it = j.find("knots"); it != j.end()) c.knots = knotType(*it, path + ".knots");
    return c;
  }

  /// A curve: {"bspline": points, "knots": ...} or {"points": samples, "t": parameters}.
  BoundaryCurve curve(const Json& j, const std::string& path) const {
    expectObject(j, path);
    const bool spline = j.contains("bspline"), samples = j.contains("points");
    if (spline == samples)
      fail(path,
           "a curve has either \"bspline\" (control points, optional \"knots\") or \"points\" "
           "(samples, optional \"t\")");
    if (spline) {
      onlyMembers(j, path, {"bspline", "knots"});
      return bsplineCurve(j, path);
    }
    onlyMembers(j, path, {"points", "t"});
    CurveSamples s;
    s.points = points(j["points"], path + ".points", 2);
    if (auto it = j.find("t"); it != j.end()) {
      const std::string tp = path + ".t";
      expectArray(*it, tp, 0);
      if (it->size() != s.points.size())
        fail(tp,
             fmt::format("expected one t per point ({}), found {}", s.points.size(), it->size()));
      for (std::size_t k = 0; k < it->size(); ++k) {
        const std::string kp = fmt::format("{}[{}]", tp, k);
        s.t.push_back(number((*it)[k], kp));
        if (k == 0 && s.t[0] != 0.0) fail(kp, fmt::format("t starts at 0, found {}", s.t[0]));
        if (k > 0 && !(s.t[k] > s.t[k - 1]))
          fail(kp, fmt::format("t values must increase: {} follows {}", s.t[k], s.t[k - 1]));
      }
      if (s.t.back() != 1.0) fail(tp, fmt::format("t ends at 1, found {}", s.t.back()));
    }
    return s;
  }

  /// A curve of the blends: B-spline curves only (the blend refits them).
  BSplineCurve blendCurve(const Json& j, const std::string& path) const {
    expectObject(j, path);
    if (!j.contains("bspline"))
      fail(path, "blend curves are B-spline curves: give \"bspline\" control points");
    onlyMembers(j, path, {"bspline", "knots"});
    BSplineCurve c = bsplineCurve(j, path);
    if (c.knots != KnotType::Clamped)
      fail(path + ".knots", "blend curves need clamped knots (they must interpolate their ends)");
    return c;
  }

  /// {"points": row} or {"tangent": curve of vectors}.
  SecondRowInput secondRow(const Json& j, const std::string& path) const {
    expectObject(j, path);
    if (j.contains("points") == j.contains("tangent"))
      fail(path, "a second row has either \"points\" (its control points) or \"tangent\"");
    if (j.contains("points")) {
      onlyMembers(j, path, {"points"});
      return points(j["points"], path + ".points", 1);
    }
    onlyMembers(j, path, {"tangent"});
    return TangentCurve{curve(j["tangent"], path + ".tangent")};
  }
};

void parseNet(const Json& j, const BSplineReader& rd, BSplinePdeModel& m) {
  const std::string path = "$.net";
  rd.expectArray(j, path, 4);
  if (j.size() > kMaxNetIndex + 1)
    rd.fail(path, fmt::format("{} rows: at most {}", j.size(), kMaxNetIndex + 1));
  const auto nu = static_cast<std::uint32_t>(j.size() - 1);
  std::uint32_t nv = 0;
  for (std::size_t i = 0; i <= nu; ++i) {
    const std::string rp = fmt::format("{}[{}]", path, i);
    rd.expectArray(j[i], rp, 4);
    if (i == 0) {
      if (j[0].size() > kMaxNetIndex + 1)
        rd.fail(rp, fmt::format("{} points: at most {}", j[0].size(), kMaxNetIndex + 1));
      nv = static_cast<std::uint32_t>(j[0].size() - 1);
      m.net = ControlNet(nu, nv, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    } else if (j[i].size() != nv + 1) {
      rd.fail(rp, fmt::format("row {} has {} points, row 0 has {}: a net is rectangular", i,
                              j[i].size(), nv + 1));
    }
    for (std::uint32_t k = 0; k <= nv; ++k) {
      const Json& p = j[i][k];
      const std::string pp = fmt::format("{}[{}]", rp, k);
      if (!m.net.given(static_cast<std::uint32_t>(i), k)) {
        if (!p.is_null()) rd.vec3(p, pp);  // checked, then ignored: the PDE decides it
        continue;
      }
      if (p.is_null())
        rd.fail(pp, fmt::format("P[{}][{}] is in row 0, 1, {} or column 0, 1, {}: the PDE needs "
                                "it given (only inner points may be null)",
                                i, k, nu, nv));
      m.net(static_cast<std::uint32_t>(i), k) = rd.vec3(p, pp);
    }
  }
}

void parseBoundary(const Json& j, const BSplineReader& rd, BSplinePdeModel& m) {
  const std::string path = "$.boundary";
  rd.expectObject(j, path);
  rd.onlyMembers(j, path, {"nu", "nv", "uMin", "uMax", "vMin", "vMax", "uMinSecond", "vMinSecond"});
  BoundaryInput& b = m.boundary;
  b.nu = rd.integer(rd.member(j, path, "nu"), path + ".nu", 3, kMaxNetIndex);
  b.nv = rd.integer(rd.member(j, path, "nv"), path + ".nv", 3, kMaxNetIndex);
  b.uMin = rd.curve(rd.member(j, path, "uMin"), path + ".uMin");
  b.uMax = rd.curve(rd.member(j, path, "uMax"), path + ".uMax");
  b.vMin = rd.curve(rd.member(j, path, "vMin"), path + ".vMin");
  b.vMax = rd.curve(rd.member(j, path, "vMax"), path + ".vMax");
  b.uMinSecond = rd.secondRow(rd.member(j, path, "uMinSecond"), path + ".uMinSecond");
  b.vMinSecond = rd.secondRow(rd.member(j, path, "vMinSecond"), path + ".vMinSecond");
}

void parseBlend(const Json& j, const BSplineReader& rd, BSplinePdeModel& m, bool closed) {
  const std::string path = closed ? "$[\"closed-blend\"]" : "$.blend";
  rd.expectObject(j, path);
  const std::initializer_list<const char*> names = {"uMin", "uMax", "vMin", "vMax"};
  const std::initializer_list<const char*> closedNames = {"start", "end"};
  if (closed)
    rd.onlyMembers(j, path, {"n", "start", "end"});
  else
    rd.onlyMembers(j, path, {"n", "uMin", "uMax", "vMin", "vMax"});
  m.blendN = rd.integer(rd.member(j, path, "n"), path + ".n", 3, kMaxBlendIndex);
  for (const char* name : closed ? closedNames : names)
    m.curves.push_back(rd.blendCurve(rd.member(j, path, name), path + "." + name));
}

}  // namespace

namespace detail {

BSplinePdeModel parseBSplinePdeDocument(const Json& doc, const std::string& source) {
  const BSplineReader rd(source);
  rd.onlyMembers(
      doc, "$",
      {"type", "name", "description", "knots", "net", "boundary", "blend", "closed-blend"});
  BSplinePdeModel m;
  rd.header(doc, m.name, m.description);
  int forms = 0;
  for (const char* f : {"net", "boundary", "blend", "closed-blend"}) forms += doc.contains(f);
  if (forms != 1)
    rd.fail("$", forms == 0
                     ? "a bspline-pde model needs one of \"net\", \"boundary\", \"blend\" or "
                       "\"closed-blend\""
                     : "a bspline-pde model has only one of \"net\", \"boundary\", \"blend\" and "
                       "\"closed-blend\"");
  if (auto it = doc.find("knots"); it != doc.end()) {
    if (it->is_object()) {
      rd.onlyMembers(*it, "$.knots", {"u", "v"});
      if (auto u = it->find("u"); u != it->end()) m.knots.uKnots = rd.knotType(*u, "$.knots.u");
      if (auto v = it->find("v"); v != it->end()) m.knots.vKnots = rd.knotType(*v, "$.knots.v");
    } else {
      m.knots.uKnots = m.knots.vKnots = rd.knotType(*it, "$.knots");
    }
    if ((doc.contains("blend") || doc.contains("closed-blend")) &&
        (m.knots.uKnots != KnotType::Clamped || m.knots.vKnots != KnotType::Clamped))
      rd.fail("$.knots", "blends are made of clamped pieces (they interpolate their curves)");
  }
  if (auto it = doc.find("net"); it != doc.end()) {
    m.form = BSplinePdeModel::Form::Net;
    parseNet(*it, rd, m);
  } else if (auto b = doc.find("boundary"); b != doc.end()) {
    m.form = BSplinePdeModel::Form::Boundary;
    parseBoundary(*b, rd, m);
  } else if (auto bl = doc.find("blend"); bl != doc.end()) {
    m.form = BSplinePdeModel::Form::Blend;
    parseBlend(*bl, rd, m, false);
  } else {
    m.form = BSplinePdeModel::Form::ClosedBlend;
    parseBlend(doc["closed-blend"], rd, m, true);
  }
  return m;
}

}  // namespace detail

namespace {

using detail::jsonOf;
using detail::ModelJson;

const char* knotName(KnotType k) { return k == KnotType::Clamped ? "clamped" : "uniform"; }

ModelJson curveJson(const BoundaryCurve& c) {
  if (const auto* s = std::get_if<BSplineCurve>(&c))
    return {{"bspline", jsonOf(s->points)}, {"knots", knotName(s->knots)}};
  const auto& samples = std::get<CurveSamples>(c);
  ModelJson out{{"points", jsonOf(samples.points)}};
  if (!samples.t.empty()) out["t"] = samples.t;
  return out;
}

ModelJson secondJson(const SecondRowInput& row) {
  if (const auto* given = std::get_if<std::vector<Vec3>>(&row)) return {{"points", jsonOf(*given)}};
  return {{"tangent", curveJson(std::get<TangentCurve>(row).vectors)}};
}

}  // namespace

std::string serializeModel(const BSplinePdeModel& m) {
  ModelJson doc{{"type", "bspline-pde"}};
  if (!m.name.empty()) doc["name"] = m.name;
  if (!m.description.empty()) doc["description"] = m.description;
  using Form = BSplinePdeModel::Form;
  if (m.form == Form::Net || m.form == Form::Boundary)
    doc["knots"] = m.knots.uKnots == m.knots.vKnots ? ModelJson(knotName(m.knots.uKnots))
                                                    : ModelJson{{"u", knotName(m.knots.uKnots)},
                                                                {"v", knotName(m.knots.vKnots)}};
  switch (m.form) {
    case Form::Net: {
      ModelJson& net = doc["net"] = ModelJson::array();
      for (std::uint32_t i = 0; i <= m.net.nu; ++i) {
        ModelJson row = ModelJson::array();
        for (std::uint32_t j = 0; j <= m.net.nv; ++j)
          row.push_back(m.net.given(i, j) ? jsonOf(m.net(i, j)) : ModelJson(nullptr));
        net.push_back(std::move(row));
      }
      break;
    }
    case Form::Boundary: {
      const BoundaryInput& b = m.boundary;
      doc["boundary"] = {{"nu", b.nu},
                         {"nv", b.nv},
                         {"uMin", curveJson(b.uMin)},
                         {"uMax", curveJson(b.uMax)},
                         {"vMin", curveJson(b.vMin)},
                         {"vMax", curveJson(b.vMax)},
                         {"uMinSecond", secondJson(b.uMinSecond)},
                         {"vMinSecond", secondJson(b.vMinSecond)}};
      break;
    }
    case Form::Blend:
    case Form::ClosedBlend: {
      const bool closed = m.form == Form::ClosedBlend;
      const char* names[] = {"uMin", "uMax", "vMin", "vMax"};
      const char* closedNames[] = {"start", "end"};
      ModelJson blend{{"n", m.blendN}};
      for (std::size_t k = 0; k < m.curves.size(); ++k)
        blend[closed ? closedNames[k] : names[k]] = curveJson(m.curves[k]);
      doc[closed ? "closed-blend" : "blend"] = std::move(blend);
      break;
    }
  }
  return detail::writeModelJson(doc);
}

}  // namespace pdesurf
