// Shape edits of spectral, cross-section and B-spline PDE models parsed from the studio's
// JSON, with the paths of what is wrong (parseShapeEdit, edit_io.hpp): the curve edits every
// such method takes here, each method's own (its ShapeEditor's ownOps) in its folder; the
// session applies them (apply.cpp).
#include <algorithm>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "methods/shape_edits/shape_edits.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/session.hpp"

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

/// The methods that take edit `op` as one of their own, by type name ("spectral and
/// cross-sections"), or "" when none does.
std::string methodsTaking(std::string_view op) {
  std::string out;
  for (const SurfaceMethod* method : surfaceMethods())
    if (const auto* editor = dynamic_cast<const detail::ShapeEditor*>(method))
      for (const char* own : editor->ownOps())
        if (op == own) out += fmt::format("{}{}", out.empty() ? "" : " and ", method->typeName());
  return out;
}

/// Every shape edit's op: the curve edits, then each method's own, once each.
std::string knownOps() {
  std::vector<std::string_view> ops(detail::kCurveOps.begin(), detail::kCurveOps.end());
  for (const SurfaceMethod* method : surfaceMethods())
    if (const auto* editor = dynamic_cast<const detail::ShapeEditor*>(method))
      for (const char* own : editor->ownOps())
        if (std::find(ops.begin(), ops.end(), own) == ops.end()) ops.emplace_back(own);
  return fmt::format("{}", fmt::join(ops, ", "));
}

}  // namespace

GroupedShapeEdit parseShapeEdit(std::string_view json, const AnyModel& model) {
  const detail::ShapeEditor* editor = detail::shapeEditor(model);
  if (!editor)
    throw ModelError("edit", "$.op",
                     fmt::format("{} models take no shape edits", modelTypeName(model)));
  return detail::parseShapeEdit(*editor, json, model);
}

namespace detail {

GroupedShapeEdit parseShapeEdit(const ShapeEditor& editor, std::string_view json,
                                const AnyModel& model) {
  const ModelReader rd("edit");
  const auto [doc, group, name] = rd.edit(json);
  GroupedShapeEdit out;
  out.group = group;
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
    e.positions = positionsField(rd, doc, e.points.size());
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
  } else if (const auto own = editor.ownOps();
             std::find(own.begin(), own.end(), name) != own.end()) {
    out.edit = editor.parseOwnEdit(name, rd, doc, model);
  } else if (const std::string types = methodsTaking(name); !types.empty()) {
    rd.fail("$.op", fmt::format("\"{}\" edits {} models, not {} models", name, types,
                                modelTypeName(model)));
  } else if (name == "move-vertex" || name == "move-vertices" || name == "set-parameters" ||
             name == "set-forces" || name == "set-shared-forces") {
    rd.fail("$.op", fmt::format("\"{}\" edits vertex-frame models; a {} model takes {}", name,
                                modelTypeName(model), knownOps()));
  } else {
    rd.fail("$.op", fmt::format("unknown edit \"{}\" for a {} model (known: {})", name,
                                modelTypeName(model), knownOps()));
  }
  return out;
}

}  // namespace detail

}  // namespace pdesurf
