// Shape edits of spectral, cross-section and B-spline PDE models parsed from the studio's
// JSON, with the paths of what is wrong (parseShapeEdit, edit_io.hpp); the session applies
// them (src/session/shape_edits.cpp).
#include <algorithm>
#include <array>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "io/json_reader.hpp"
#include "io/model_reader.hpp"
#include "methods/curve_target.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

namespace {

using detail::curveTarget;
using detail::CurveTarget;
using detail::Json;
using detail::ModelReader;

/// {"curve": index or name}.
CurveRef curveRef(const ModelReader& rd, const Json& doc) {
  const Json& j = rd.member(doc, "$", "curve");
  CurveRef ref;
  if (j.is_string())
    ref.name = j.get<std::string>();
  else
    ref.index = rd.integer(j, "$.curve", 0, std::numeric_limits<std::uint32_t>::max());
  return ref;
}

/// "positions": one point per listed item.
std::vector<Vec3> positions(const ModelReader& rd, const Json& doc, std::size_t count) {
  const Json& list = rd.member(doc, "$", "positions");
  rd.expectArray(list, "$.positions", count);
  if (list.size() != count)
    rd.fail("$.positions",
            fmt::format("expected {} positions (one per point), found {}", count, list.size()));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(rd.vec3(list[i], fmt::format("$.positions[{}]", i)));
  return out;
}

/// Only the listed members besides "op" and "group".
void onlyMembers(const ModelReader& rd, const Json& doc, std::initializer_list<const char*> keys) {
  for (const auto& [key, value] : doc.items())
    if (key != "op" && key != "group" &&
        std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; })) {
      std::string known;
      for (const char* k : keys) known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", k);
      rd.fail("$", fmt::format("unknown field \"{}\" (expected {})", key, known));
    }
}

/// Parses a transform given inline (parseTransform's fields beside "op" and "curve"), its
/// errors at the same paths of this edit.
AffineMap inlineTransform(const Json& doc) {
  Json t = Json::object();
  for (const char* key : {"translate", "rotate", "scale", "center"})
    if (doc.contains(key)) t[key] = doc.at(key);
  try {
    return parseTransform(t.dump());
  } catch (const ModelError& e) {
    throw ModelError("edit", e.jsonPath(), e.problem());
  }
}

ShapeEdit parseSetOperator(const ModelReader& rd, const Json& doc, const AnyModel& model) {
  const bool spectral = model.is<SpectralModel>();
  if (spectral)
    onlyMembers(rd, doc, {"operator", "N", "a", "modes", "remainder"});
  else
    onlyMembers(rd, doc, {"a", "modes", "remainder", "method"});
  SetOperator e;
  if (auto it = doc.find("operator"); it != doc.end())
    e.kind = rd.choice<OperatorKind>(*it, "$.operator",
                                     {{"ugail", OperatorKind::Ugail}, {"fu", OperatorKind::Fu}});
  if (auto it = doc.find("N"); it != doc.end())
    e.power = rd.integer(*it, "$.N", 1, std::numeric_limits<std::uint32_t>::max());
  if (auto it = doc.find("a"); it != doc.end()) e.a = rd.number(*it, "$.a");
  if (auto it = doc.find("modes"); it != doc.end())
    e.modes = rd.integer(*it, "$.modes", 0, std::numeric_limits<std::uint32_t>::max());
  if (auto it = doc.find("remainder"); it != doc.end())
    e.remainder = rd.boolean(*it, "$.remainder");
  if (auto it = doc.find("method"); it != doc.end())
    e.method = rd.choice<ChainMethod>(*it, "$.method",
                                      {{"global", ChainMethod::Global},
                                       {"c2", ChainMethod::ExactC2},
                                       {"shared-curves", ChainMethod::SharedCurves}});
  if (!e.kind && !e.power && !e.a && !e.modes && !e.remainder && !e.method)
    rd.fail("$", spectral ? "set-operator needs \"operator\", \"N\", \"a\", \"modes\" or "
                            "\"remainder\""
                          : "set-operator needs \"a\", \"modes\", \"remainder\" or "
                            "\"method\"");
  return e;
}

}  // namespace

GroupedShapeEdit parseShapeEdit(std::string_view json, const AnyModel& model) {
  const ModelReader rd("edit");
  const auto [doc, group, name] = rd.edit(json);
  GroupedShapeEdit out;
  out.group = group;
  const bool spectral = model.is<SpectralModel>();
  const bool sections = model.is<CrossSectionModel>();
  const bool bspline = model.is<BSplinePdeModel>();
  const auto only = [&](bool allowed, const char* types) {
    if (!allowed)
      rd.fail("$.op", fmt::format("\"{}\" edits {} models, not {} models", name, types,
                                  modelTypeName(model)));
  };
  AnyModel copy = model;  // the edit's targets are checked on a copy of the model
  if (name == "move-curve-points") {
    onlyMembers(rd, doc, {"curve", "points", "positions", "falloff"});
    MoveCurvePoints e;
    e.curve = curveRef(rd, doc);
    const CurveTarget target = curveTarget(copy, e.curve, "$.curve");
    const std::vector<Vec3>* points = target.points;
    if (target.input) {
      auto* sampled = std::get_if<SampledCurve>(target.input);
      if (!sampled)
        rd.fail("$.curve", fmt::format("{} is given by Fourier coefficients, not points: move it "
                                       "whole (transform-curve)",
                                       target.path));
      points = &sampled->points;
    }
    const Json& list = rd.member(doc, "$", "points");
    rd.expectArray(list, "$.points", 1);
    std::set<std::uint32_t> seen;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = fmt::format("$.points[{}]", i);
      const std::uint32_t k = rd.index(list[i], path, points->size(), "point", "points");
      if (!seen.insert(k).second) rd.fail(path, fmt::format("point {} is listed twice", k));
      e.points.push_back(k);
    }
    e.positions = positions(rd, doc, e.points.size());
    if (auto it = doc.find("falloff"); it != doc.end()) {
      e.falloff = rd.number(*it, "$.falloff");
      if (!(e.falloff >= 0.0 && e.falloff <= kMaxFalloff))
        rd.fail("$.falloff", fmt::format("{} is not between 0 and {} (a fraction of the "
                                         "curve's length)",
                                         e.falloff, kMaxFalloff));
      if (e.falloff > 0.0 && !target.input)
        rd.fail("$.falloff", fmt::format("{} is not a closed curve: a falloff bends closed "
                                         "curves given as points",
                                         target.path));
    }
    out.edit = std::move(e);
  } else if (name == "transform-curve") {
    onlyMembers(rd, doc, {"curve", "translate", "rotate", "scale", "center", "from"});
    TransformCurve e;
    e.curve = curveRef(rd, doc);
    curveTarget(copy, e.curve, "$.curve");
    e.map = inlineTransform(doc);
    if (auto it = doc.find("from"); it != doc.end()) {
      e.fromGroupStart = rd.choice<bool>(*it, "$.from", {{"group-start", true}});
      if (out.group.empty())
        rd.fail("$.from",
                "\"from\": \"group-start\" needs the edit's \"group\" (the drag "
                "whose start it names)");
    }
    out.edit = std::move(e);
  } else if (name == "set-fourier") {
    onlyMembers(rd, doc, {"curve", "a0", "a", "b"});
    SetFourier e;
    e.curve = curveRef(rd, doc);
    const CurveTarget target = curveTarget(copy, e.curve, "$.curve");
    if (!target.input || !std::holds_alternative<FourierCurve>(*target.input))
      rd.fail("$.curve", fmt::format("{} is not given by Fourier coefficients: move its points "
                                     "(move-curve-points)",
                                     target.path));
    if (auto it = doc.find("a0"); it != doc.end()) e.a0 = rd.vec3(*it, "$.a0");
    for (auto [key, list] : {std::pair{"a", &e.a}, {"b", &e.b}})
      if (auto it = doc.find(key); it != doc.end()) {
        const std::string path = fmt::format("$.{}", key);
        rd.expectArray(*it, path, 0);
        list->emplace();
        for (std::size_t n = 0; n < it->size(); ++n)
          (*list)->push_back(rd.vec3((*it)[n], fmt::format("{}[{}]", path, n)));
      }
    if (!e.a0 && !e.a && !e.b) rd.fail("$", "set-fourier needs \"a0\", \"a\" or \"b\"");
    out.edit = std::move(e);
  } else if (name == "set-operator") {
    only(spectral || sections, "spectral and cross-sections");
    out.edit = parseSetOperator(rd, doc, model);
  } else if (name == "set-spine") {
    only(spectral, "spectral");
    onlyMembers(rd, doc, {"spine"});
    // The file's own field: its order and counts are checked with the model (the same paths).
    const Json& list = rd.member(doc, "$", "spine");
    rd.expectArray(list, "$.spine", 0);
    SetSpine e;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string path = fmt::format("$.spine[{}]", k);
      rd.expectObject(list[k], path);
      SpineEdit edit;
      const Json& us = rd.member(list[k], path, "u");
      const Json& moved = rd.member(list[k], path, "moved");
      rd.expectArray(us, path + ".u", 1);
      rd.expectArray(moved, path + ".moved", 1);
      for (std::size_t j = 0; j < us.size(); ++j)
        edit.u.push_back(rd.number(us[j], fmt::format("{}.u[{}]", path, j)));
      for (std::size_t j = 0; j < moved.size(); ++j)
        edit.moved.push_back(rd.vec3(moved[j], fmt::format("{}.moved[{}]", path, j)));
      e.edits.push_back(std::move(edit));
    }
    out.edit = std::move(e);
  } else if (name == "add-section" || name == "remove-section") {
    only(sections, "cross-sections");
    const std::size_t count = model.get<CrossSectionModel>().curves.size();
    if (name == "remove-section") {
      onlyMembers(rd, doc, {"index"});
      out.edit = RemoveSection{
          rd.index(rd.member(doc, "$", "index"), "$.index", count, "section", "sections")};
    } else {
      onlyMembers(rd, doc, {"index", "curve"});
      AddSection e;
      e.index =
          rd.integer(rd.member(doc, "$", "index"), "$.index", 0, static_cast<std::uint32_t>(count));
      if (auto it = doc.find("curve"); it != doc.end())
        e.curve = parseCurve(it->dump(), "edit", "$.curve");
      else if (e.index == 0 || e.index == count)
        rd.fail("$.curve",
                "a section before the first or after the last needs its \"curve\" "
                "(between two sections it is sampled from the surface)");
      out.edit = std::move(e);
    }
  } else if (name == "move-control-points") {
    only(bspline, "bspline-pde");
    onlyMembers(rd, doc, {"points", "positions"});
    const auto& m = model.get<BSplinePdeModel>();
    if (m.form != BSplinePdeModel::Form::Net)
      rd.fail("$.op", fmt::format("the {} form has no net of its own: move the points of its "
                                  "curves (move-curve-points)",
                                  formName(m.form)));
    const Json& list = rd.member(doc, "$", "points");
    rd.expectArray(list, "$.points", 1);
    MoveControlPoints e;
    std::set<std::array<std::uint32_t, 2>> seen;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string path = fmt::format("$.points[{}]", k);
      rd.expectArray(list[k], path, 2);
      if (list[k].size() != 2) rd.fail(path, "expected [i, j]: a row and a column");
      const std::uint32_t i = rd.index(list[k][0], path + "[0]", m.net.nu + 1, "row", "rows");
      const std::uint32_t j = rd.index(list[k][1], path + "[1]", m.net.nv + 1, "column", "columns");
      if (!m.net.given(i, j))
        rd.fail(path, fmt::format("P[{}][{}] is an inner point, solved by the PDE (the given "
                                  "points: rows 0, 1, {} and columns 0, 1, {})",
                                  i, j, m.net.nu, m.net.nv));
      if (!seen.insert({i, j}).second)
        rd.fail(path, fmt::format("P[{}][{}] is listed twice", i, j));
      e.points.push_back({i, j});
    }
    e.positions = positions(rd, doc, e.points.size());
    out.edit = std::move(e);
  } else if (name == "move-vertex" || name == "move-vertices" || name == "set-parameters" ||
             name == "set-forces" || name == "set-shared-forces") {
    rd.fail("$.op", fmt::format("\"{}\" edits vertex-frame models; a {} model takes "
                                "move-curve-points, transform-curve, set-fourier, set-operator, "
                                "set-spine, add-section, remove-section, move-control-points",
                                name, modelTypeName(model)));
  } else {
    rd.fail("$.op", fmt::format("unknown edit \"{}\" for a {} model (known: move-curve-points, "
                                "transform-curve, set-fourier, set-operator, set-spine, "
                                "add-section, remove-section, move-control-points)",
                                name, modelTypeName(model)));
  }
  return out;
}

}  // namespace pdesurf
