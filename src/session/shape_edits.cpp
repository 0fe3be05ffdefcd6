// Shape edits of spectral, cross-section and B-spline PDE models (include/pdesurf/session.hpp):
// parsed from the studio's JSON with the paths of what is wrong (parseShapeEdit, edit_io.hpp),
// applied to a copy of the model, and checked as its file would be before the session takes it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "io/model_reader.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

namespace {

using detail::Json;
using detail::ModelReader;

/// The B-spline PDE curves by their file names, per form.
constexpr const char* kSideNames[] = {"uMin", "uMax", "vMin", "vMax"};
constexpr const char* kClosedNames[] = {"start", "end"};

/// A curve of a model, to change: a spectral curve (points or Fourier) or a list of points,
/// with what its points are (positions, or vectors: a derivative condition, a tangent) and
/// its JSON path in the model file.
struct CurveTarget {
  CurveInput* input = nullptr;
  std::vector<Vec3>* points = nullptr;
  bool vectors = false;
  std::string path;
};

/// The curve `ref` names in `model` (a copy the edit changes); throws ModelError (source
/// "edit", at `path`) when the model has no such curve.
CurveTarget curveTarget(AnyModel& model, const CurveRef& ref, const std::string& path) {
  const ModelReader rd("edit");
  if (auto* m = std::get_if<SpectralModel>(&model)) {
    if (!ref.name.empty()) rd.fail(path, "a spectral model's curves are numbered (its conditions)");
    const std::uint32_t i = ref.index;
    if (i >= m->conditions.size())
      rd.fail(path, fmt::format("condition {} is out of range (the model has {}, indices 0 to {})",
                                i, m->conditions.size(), m->conditions.size() - 1));
    return {&m->conditions[i].curve, nullptr, m->conditions[i].derivative > 0,
            fmt::format("$.conditions[{}].curve", i)};
  }
  if (auto* m = std::get_if<CrossSectionModel>(&model)) {
    if (!ref.name.empty()) rd.fail(path, "a chain's sections are numbered");
    if (ref.index >= m->curves.size())
      rd.fail(path, fmt::format("section {} is out of range (the chain has {}, indices 0 to {})",
                                ref.index, m->curves.size(), m->curves.size() - 1));
    return {&m->curves[ref.index], nullptr, false, fmt::format("$.curves[{}]", ref.index)};
  }
  auto& m = std::get<BSplinePdeModel>(model);
  using Form = BSplinePdeModel::Form;
  const auto pointsOf = [](BoundaryCurve& c) -> std::vector<Vec3>& {
    return std::visit([](auto& x) -> std::vector<Vec3>& { return x.points; }, c);
  };
  if (m.form == Form::Boundary) {
    BoundaryInput& b = m.boundary;
    BoundaryCurve* sides[] = {&b.uMin, &b.uMax, &b.vMin, &b.vMax};
    for (int s = 0; s < 4; ++s)
      if (ref.name == kSideNames[s])
        return {nullptr, &pointsOf(*sides[s]), false, "$.boundary." + ref.name};
    for (auto [name, row] : {std::pair{"uMinSecond", &b.uMinSecond}, {"vMinSecond", &b.vMinSecond}})
      if (ref.name == name) {
        if (auto* points = std::get_if<std::vector<Vec3>>(row))
          return {nullptr, points, false, fmt::format("$.boundary.{}.points", name)};
        return {nullptr, &pointsOf(std::get<TangentCurve>(*row).vectors), true,
                fmt::format("$.boundary.{}.tangent", name)};
      }
    rd.fail(path, fmt::format("the boundary form has no curve \"{}\" (its curves: uMin, uMax, "
                              "vMin, vMax, uMinSecond, vMinSecond)",
                              ref.name));
  }
  if (m.form == Form::Blend || m.form == Form::ClosedBlend) {
    const bool closed = m.form == Form::ClosedBlend;
    const std::size_t count = closed ? 2 : 4;
    for (std::size_t k = 0; k < count; ++k)
      if (ref.name == (closed ? kClosedNames[k] : kSideNames[k]))
        return {nullptr, &m.curves[k].points, false,
                fmt::format("$.{}.{}.bspline", closed ? "closed-blend" : "blend", ref.name)};
    rd.fail(path, closed ? fmt::format("the closed blend has no curve \"{}\" (its curves: start, "
                                       "end)",
                                       ref.name)
                         : fmt::format("the blend has no curve \"{}\" (its curves: uMin, uMax, "
                                       "vMin, vMax)",
                                       ref.name));
  }
  rd.fail(path, "the net form has no curves: move its control points (move-control-points)");
}

/// The curves of a B-spline PDE model whose ends may be shared corners (the boundary form's
/// four sides, a blend's four curves, a closed blend's two closed curves), as point lists.
std::vector<std::vector<Vec3>*> cornerCurves(BSplinePdeModel& m) {
  std::vector<std::vector<Vec3>*> out;
  const auto pointsOf = [](BoundaryCurve& c) -> std::vector<Vec3>* {
    return std::visit([](auto& x) { return &x.points; }, c);
  };
  if (m.form == BSplinePdeModel::Form::Boundary)
    for (BoundaryCurve* c :
         {&m.boundary.uMin, &m.boundary.uMax, &m.boundary.vMin, &m.boundary.vMax})
      out.push_back(pointsOf(*c));
  if (m.form == BSplinePdeModel::Form::Blend || m.form == BSplinePdeModel::Form::ClosedBlend)
    for (BSplineCurve& c : m.curves) out.push_back(&c.points);
  return out;
}

/// Corners stay shared: every curve end that sat where a moved end of a curve sat (another
/// curve's corner, a closed curve's other end) moves with it. `before` is the model before
/// the edit, `after` the edited one (the same curves, the same counts).
void keepCornersShared(BSplinePdeModel& before, BSplinePdeModel& after) {
  const auto was = cornerCurves(before), now = cornerCurves(after);
  std::vector<std::pair<Vec3, Vec3>> moves;  // (where an end was, where it is)
  for (std::size_t c = 0; c < was.size(); ++c)
    for (const bool last : {false, true}) {
      const Vec3& from = last ? was[c]->back() : was[c]->front();
      const Vec3& to = last ? now[c]->back() : now[c]->front();
      if (from != to) moves.emplace_back(from, to);
    }
  for (const auto& [from, to] : moves)
    for (std::size_t c = 0; c < was.size(); ++c)
      for (const bool last : {false, true})
        if ((last ? was[c]->back() : was[c]->front()) == from)
          (last ? now[c]->back() : now[c]->front()) = to;
}

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
  const bool spectral = std::holds_alternative<SpectralModel>(model);
  if (spectral)
    onlyMembers(rd, doc, {"operator", "N", "a", "modes", "remainder"});
  else
    onlyMembers(rd, doc, {"a", "modes", "remainder"});
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
  if (!e.kind && !e.power && !e.a && !e.modes && !e.remainder)
    rd.fail("$", spectral ? "set-operator needs \"operator\", \"N\", \"a\", \"modes\" or "
                            "\"remainder\""
                          : "set-operator needs \"a\", \"modes\" or \"remainder\"");
  return e;
}

/// The points of a closed curve of a chain, sampled on its solved surface at chain parameter
/// `s`: `count` points at uniform v, with their v.
SampledCurve sectionAt(const CrossSectionChain& chain, double s, std::uint32_t count) {
  const ChainPatch* at = &chain.patches.front();
  for (const ChainPatch& p : chain.patches)
    if (chain.curveU[p.shownFirstCurve] <= s && s <= chain.curveU[p.shownLastCurve]) {
      at = &p;
      break;
    }
  const double t = (s - chain.curveU[at->firstCurve]) / at->length;
  SampledCurve out;
  for (std::uint32_t j = 0; j < count; ++j) {
    const double v = 2.0 * std::numbers::pi * j / count;
    out.points.push_back(at->patch.position(t, v));
    out.v.push_back(v);
  }
  return out;
}

/// The number of points a curve holds (Fourier curves: 0).
std::size_t pointCount(const CurveInput& c) {
  const auto* s = std::get_if<SampledCurve>(&c);
  return s ? s->points.size() : 0;
}

}  // namespace

bool takesShapeEdits(const AnyModel& model) {
  return !std::holds_alternative<VertexFrameModel>(model);
}

GroupedShapeEdit parseShapeEdit(std::string_view json, const AnyModel& model) {
  const ModelReader rd("edit");
  const Json doc = rd.parseDocument(json);
  rd.expectObject(doc, "$");
  GroupedShapeEdit out;
  if (auto it = doc.find("group"); it != doc.end()) out.group = rd.string(*it, "$.group");
  const std::string name = rd.string(rd.member(doc, "$", "op"), "$.op");
  const bool spectral = std::holds_alternative<SpectralModel>(model);
  const bool sections = std::holds_alternative<CrossSectionModel>(model);
  const bool bspline = std::holds_alternative<BSplinePdeModel>(model);
  const auto only = [&](bool allowed, const char* types) {
    if (!allowed)
      rd.fail("$.op", fmt::format("\"{}\" edits {} models, not {} models", name, types,
                                  modelTypeName(model)));
  };
  AnyModel copy = model;  // the edit's targets are checked on a copy of the model
  if (name == "move-curve-points") {
    onlyMembers(rd, doc, {"curve", "points", "positions"});
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
    const std::size_t count = std::get<CrossSectionModel>(model).curves.size();
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
    const auto& m = std::get<BSplinePdeModel>(model);
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

AnyModel applyShapeEdit(const AnyModel& model, const SolvedModel& solved, const ShapeEdit& edit) {
  const ModelReader rd("edit");
  AnyModel next = model;
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, MoveCurvePoints>) {
          const CurveTarget target = curveTarget(next, e.curve, "$.curve");
          std::vector<Vec3>& points =
              target.input ? std::get<SampledCurve>(*target.input).points : *target.points;
          for (std::size_t k = 0; k < e.points.size(); ++k) points.at(e.points[k]) = e.positions[k];
        } else if constexpr (std::is_same_v<T, TransformCurve>) {
          const CurveTarget target = curveTarget(next, e.curve, "$.curve");
          if (target.input) {
            *target.input = transformCurve(*target.input, e.map, target.vectors);
          } else {
            for (Vec3& p : *target.points) p = target.vectors ? e.map.vector(p) : e.map.point(p);
          }
        } else if constexpr (std::is_same_v<T, SetFourier>) {
          auto& c = std::get<FourierCurve>(*curveTarget(next, e.curve, "$.curve").input);
          if (e.a0) c.a0 = *e.a0;
          if (e.a) c.a = *e.a;
          if (e.b) c.b = *e.b;
          // As the file reads them: the shorter list is the longer one's zeros.
          const std::size_t terms = std::max(c.a.size(), c.b.size());
          c.a.resize(terms, Vec3::Zero());
          c.b.resize(terms, Vec3::Zero());
        } else if constexpr (std::is_same_v<T, SetOperator>) {
          if (auto* m = std::get_if<SpectralModel>(&next)) {
            SpectralOperator& op = m->op;
            if (e.kind && *e.kind != op.kind) {
              op.kind = *e.kind;
              op.power = op.kind == OperatorKind::Fu ? 3u : op.order() / 2;
            }
            if (e.power) {
              if (op.kind == OperatorKind::Fu)
                rd.fail("$.N", "the Fu operator is of order 6 (N is Ugail's)");
              op.power = *e.power;
            }
            if (e.a) op.a = *e.a;
            if (e.modes) m->options.modes = *e.modes;
            if (e.remainder) m->options.remainder = *e.remainder;
          } else {
            auto& options = std::get<CrossSectionModel>(next).options;
            if (e.a) options.a = *e.a;
            if (e.modes) options.modes = *e.modes;
            if (e.remainder) options.remainder = *e.remainder;
          }
        } else if constexpr (std::is_same_v<T, SetSpine>) {
          std::get<SpectralModel>(next).spineEdits = e.edits;
        } else if constexpr (std::is_same_v<T, AddSection>) {
          auto& m = std::get<CrossSectionModel>(next);
          const std::size_t i = e.index;
          CurveInput curve;
          if (e.curve) {
            curve = *e.curve;
          } else {
            const CrossSectionChain& chain = *std::get<SolvedSpectral>(solved.solved()).chain;
            const std::size_t count = std::max<std::size_t>(
                {2 * std::size_t{m.options.modes} + 1, pointCount(m.curves[i - 1]),
                 pointCount(m.curves[i]), kMinSampledSection});
            curve = sectionAt(chain, 0.5 * (chain.curveU[i - 1] + chain.curveU[i]),
                              static_cast<std::uint32_t>(count));
          }
          m.curves.insert(m.curves.begin() + static_cast<std::ptrdiff_t>(i), std::move(curve));
          if (std::vector<double>& u = m.options.u; !u.empty()) {
            const double at = i == 0          ? u[0] - (u[1] - u[0])
                              : i == u.size() ? u.back() + (u.back() - u[u.size() - 2])
                                              : 0.5 * (u[i - 1] + u[i]);
            u.insert(u.begin() + static_cast<std::ptrdiff_t>(i), at);
          }
        } else if constexpr (std::is_same_v<T, RemoveSection>) {
          auto& m = std::get<CrossSectionModel>(next);
          m.curves.erase(m.curves.begin() + e.index);
          if (!m.options.u.empty()) m.options.u.erase(m.options.u.begin() + e.index);
        } else {
          static_assert(std::is_same_v<T, MoveControlPoints>);
          ControlNet& net = std::get<BSplinePdeModel>(next).net;
          for (std::size_t k = 0; k < e.points.size(); ++k)
            net(e.points[k][0], e.points[k][1]) = e.positions[k];
        }
      },
      edit);
  if (auto* m = std::get_if<BSplinePdeModel>(&next);
      m && (std::holds_alternative<MoveCurvePoints>(edit) ||
            std::holds_alternative<TransformCurve>(edit))) {
    BSplinePdeModel before = std::get<BSplinePdeModel>(model);
    keepCornersShared(before, *m);
  }
  // What the file parser checks of the result (counts, orders, spine u order, modes against
  // points), with the model file's paths; the solver's refusals come when the session solves.
  parseModel(serializeModel(next), "edit");
  return next;
}

void ModelSession::apply(const ShapeEdit& edit, std::string_view group) {
  if (!takesShapeEdits(model()))
    throw std::logic_error("ModelSession::apply: vertex-frame models take Edit, not ShapeEdit");
  const State* base = &current_;
  if (const auto* t = std::get_if<TransformCurve>(&edit); t && t->fromGroupStart)
    if (const State* start = history_.groupStart(group)) base = start;
  auto next = std::make_shared<const AnyModel>(applyShapeEdit(*base->model, *base->solved, edit));
  auto solvedNext = solveIfFixed(next);  // may throw: nothing changed yet
  change(std::move(next), std::move(solvedNext), group);
}

SpineHandles spineHandles(const SolvedModel& solved, std::uint32_t count) {
  SpineHandles out;
  const SolvedSpectral* spectral = solved.spectral();
  if (!spectral || !spectral->patch || count < 2) return out;
  const auto [u0, u1] = spectral->range(0);
  for (std::uint32_t i = 0; i < count; ++i) {
    // As `pdesurf spine` places its points (apps/cli/spectral_commands.cpp: spineJson).
    const double u = u0 + (u1 - u0) * static_cast<double>(i) / (count - 1);
    out.u.push_back(u);
    out.points.push_back(spectral->patch->spine(u));
  }
  return out;
}

}  // namespace pdesurf
