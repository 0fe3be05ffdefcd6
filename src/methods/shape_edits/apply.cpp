// Shape edits of spectral, cross-section and B-spline PDE models (include/pdesurf/session.hpp),
// as parse.cpp parses them: applied to a copy of the model, checked as its file would be and
// solved before the session takes it (shape_edits.hpp: those methods' applyEdit). The curve
// edits every such method takes are here; each method's own edits are in its folder.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "methods/shape_edits/shape_edits.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf {

namespace {

using detail::curveTarget;
using detail::CurveTarget;
using detail::ModelReader;
using detail::shapeEditor;

/// Moves `points[moved[k]]` to `positions[k]` and, with falloff > 0, the points round each
/// by the compact bump of MoveCurvePoints::falloff (the polygon closed).
void movePoints(std::vector<Vec3>& points, const std::vector<std::uint32_t>& moved,
                const std::vector<Vec3>& positions, double falloff) {
  const std::size_t n = points.size();
  std::vector<Vec3> offset(n, Vec3::Zero());
  if (falloff > 0.0 && n > 1) {
    std::vector<double> at(n, 0.0);  // arc length from point 0
    for (std::size_t j = 1; j < n; ++j) at[j] = at[j - 1] + (points[j] - points[j - 1]).norm();
    const double length = at[n - 1] + (points[0] - points[n - 1]).norm();
    const double radius = falloff * length;
    for (std::size_t k = 0; k < moved.size(); ++k) {
      const Vec3 d = positions[k] - points[moved[k]];
      for (std::size_t j = 0; j < n; ++j) {
        const double along = std::abs(at[j] - at[moved[k]]);
        const double t = std::min(along, length - along) / radius;
        if (t < 1.0) offset[j] += std::pow(1.0 - t * t, 3) * d;
      }
    }
  }
  for (std::size_t j = 0; j < n; ++j) points[j] += offset[j];
  for (std::size_t k = 0; k < moved.size(); ++k) points[moved[k]] = positions[k];
}

/// A solved model's surface box, from a mesh of kReachSamples a patch side.
Bounds surfaceBox(const SolvedModel& solved) {
  Bounds box;
  const Mesh mesh = tessellate(solved, TessellateOptions{.resolution = kReachSamples});
  for (std::size_t k = 0; k + 2 < mesh.positions.size(); k += 3)
    box.add(Vec3(mesh.positions[k], mesh.positions[k + 1], mesh.positions[k + 2]));
  return box;
}

}  // namespace

void checkReach(const AnyModel& before, const SolvedModel& solvedBefore, const AnyModel& after,
                const SolvedModel& solvedAfter) {
  // How far the handles moved: the largest offset of a corresponding point.
  const detail::ShapeEditor* editor = shapeEditor(before);
  if (!editor) return;  // a method without shape edits: no drag
  const std::vector<Vec3> was = editor->reachPoints(before), now = editor->reachPoints(after);
  if (was.size() != now.size()) return;  // a section added or removed: no drag
  double moved = 0.0;
  for (std::size_t k = 0; k < was.size(); ++k) moved = std::max(moved, (now[k] - was[k]).norm());
  // Operators, spines, tangents and modes move no position: their effect is the edit's intent.
  if (moved == 0.0) return;
  const Bounds from = surfaceBox(solvedBefore), to = surfaceBox(solvedAfter);
  // How far the surface reached out of its box.
  const double reach = std::max((to.max - from.max).cwiseMax(0.0).maxCoeff(),
                                (from.min - to.min).cwiseMax(0.0).maxCoeff());
  if (reach <= kMaxReach * moved + kReachRounding * from.diagonal()) return;
  const std::string advice = dragAdvice(before);
  throw ModelError(
      "edit", "",
      fmt::format("this edit would move the surface {:.3g} out of its box ({:.3g} across), {:.3g} "
                  "times as far as the points moved ({:.3g}); kept as it was. {}",
                  reach, from.diagonal(), moved > 0.0 ? reach / moved : reach, moved,
                  advice.empty() ? "Move whole curves instead" : advice));
}

namespace {

/// The model after a shape edit (parsed against it by parseShapeEdit), checked as its file
/// would be (parseModel of its text). `solved` is `model` solved (AddSection samples it).
/// Throws ModelError (source "edit") naming what is wrong.
AnyModel shapeEdited(const detail::ShapeEditor& editor, const AnyModel& model,
                     const SolvedModel& solved, const ShapeEdit& edit) {
  AnyModel next = model;
  if (const auto* move = std::get_if<MoveCurvePoints>(&edit)) {
    const CurveTarget target = curveTarget(next, move->curve, "$.curve");
    std::vector<Vec3>& points =
        target.input ? std::get<SampledCurve>(*target.input).points : *target.points;
    movePoints(points, move->points, move->positions, move->falloff);
    editor.afterCurveEdit(model, next);
  } else if (const auto* transform = std::get_if<TransformCurve>(&edit)) {
    const CurveTarget target = curveTarget(next, transform->curve, "$.curve");
    if (target.input) {
      *target.input = transformCurve(*target.input, transform->map, target.vectors);
    } else {
      for (Vec3& p : *target.points)
        p = target.vectors ? transform->map.vector(p) : transform->map.point(p);
    }
    editor.afterCurveEdit(model, next);
  } else if (const auto* fourier = std::get_if<SetFourier>(&edit)) {
    auto& c = std::get<FourierCurve>(*curveTarget(next, fourier->curve, "$.curve").input);
    if (fourier->a0) c.a0 = *fourier->a0;
    if (fourier->a) c.a = *fourier->a;
    if (fourier->b) c.b = *fourier->b;
    // As the file reads them: the shorter list is the longer one's zeros.
    const std::size_t terms = std::max(c.a.size(), c.b.size());
    c.a.resize(terms, Vec3::Zero());
    c.b.resize(terms, Vec3::Zero());
  } else {
    editor.applyOwnEdit(next, solved, edit);  // the method's own edits
  }
  // What the file parser checks of the result (counts, orders, spine u order, modes against
  // points), with the model file's paths; the solver's refusals come when the session solves.
  parseModel(serializeModel(next), "edit");
  return next;
}

}  // namespace

namespace detail {

CurveTarget curveTarget(AnyModel& model, const CurveRef& ref, const std::string& path) {
  const ShapeEditor* editor = shapeEditor(model);
  if (!editor)
    ModelReader("edit").fail(path, fmt::format("a {} model has no curves", modelTypeName(model)));
  return editor->curve(model, ref, path);
}

EditResult applyShapeEdit(const ShapeEditor& editor, const EditContext& context,
                          const ModelEdit& modelEdit) {
  const ShapeEdit& edit = modelEdit.as<ShapeEdit>(modelTypeName(*context.current.model));
  // A drag's absolute steps apply to the model as the drag began.
  const ModelState* base = &context.current;
  const auto* t = std::get_if<TransformCurve>(&edit);
  const auto* m = std::get_if<MoveCurvePoints>(&edit);
  const bool spine = std::holds_alternative<MoveSpinePoint>(edit);
  if (((t && t->fromGroupStart) || (m && m->falloff > 0.0) || spine) && context.groupStart)
    base = context.groupStart;
  auto next =
      std::make_shared<const AnyModel>(shapeEdited(editor, *base->model, *base->solved, edit));
  auto solvedNext = std::make_shared<const SolvedModel>(solve(next, context.source));
  checkReach(*base->model, *base->solved, *next, *solvedNext);
  return {{std::move(next), std::move(solvedNext), nullptr}};
}

}  // namespace detail

std::string dragAdvice(const AnyModel& model) {
  const detail::ShapeEditor* editor = shapeEditor(model);
  return editor ? editor->dragAdvice(model) : "";
}

namespace detail {

void onlyMembers(const ModelReader& rd, const Json& doc, std::initializer_list<const char*> keys) {
  for (const auto& [key, value] : doc.items())
    if (key != "op" && key != "group" &&
        std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; })) {
      std::string known;
      for (const char* k : keys) known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", k);
      rd.fail("$", fmt::format("unknown field \"{}\" (expected {})", key, known));
    }
}

std::vector<Vec3> positionsField(const ModelReader& rd, const Json& doc, std::size_t count) {
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

Vec3 meanOf(const std::vector<Vec3>& points) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

void addCurve(ModelHandles& out, const CurveRef& ref, std::string label,
              const std::vector<Vec3>* points, const Vec3& a0, bool vectors) {
  if (points)
    for (std::uint32_t k = 0; k < points->size(); ++k) {
      ModelHandle& h = out.points.emplace_back();
      h.kind = ModelHandle::Kind::CurvePoint;
      h.curve = ref;
      h.index = k;
      h.position = (*points)[k];
    }
  const Vec3 centre = points && !points->empty() ? meanOf(*points) : a0;
  out.curves.push_back({ref, std::move(label), centre, vectors});
}

void addTangents(ModelHandles& out, const CurveRef& ref, const std::vector<Vec3>& at,
                 const std::vector<Vec3>& base, bool mean) {
  for (std::uint32_t k = 0; k < at.size(); ++k) {
    ModelHandle& h = out.points.emplace_back();
    h.kind = ModelHandle::Kind::Tangent;
    h.curve = ref;
    h.index = k;
    h.position = base[k] + kTangentDraw * at[k];
    h.base = base[k];
    h.mean = mean;
  }
}

}  // namespace detail

}  // namespace pdesurf
