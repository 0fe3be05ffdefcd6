// Shape edits of spectral, cross-section and B-spline PDE models (include/pdesurf/session.hpp),
// as shape_edit_io.cpp parses them: applied to a copy of the model, checked as its file would
// be and solved before the session takes it (shape_edits.hpp: those methods' applyEdit).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "io/model_reader.hpp"
#include "methods/curve_target.hpp"
#include "methods/shape_edits.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

namespace {

/// dragAdvice's probe of a spectral patch: point 0 of each position condition given as points
/// moved by this fraction of the surface's size, the patch solved again.
constexpr double kProbeFraction = 1e-3;
/// dragAdvice advises on a spectral patch whose probe moved the surface by more than this many
/// times the probe's offset (twice the aim of locality_test.cpp for a point).
constexpr double kAdviseRatio = 4.0;

using detail::curveTarget;
using detail::CurveTarget;
using detail::ModelReader;

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

/// The points of every curve and net of a model that holds positions, in a fixed order (two
/// models of one structure list corresponding points).
std::vector<Vec3> handlePoints(const AnyModel& model) {
  std::vector<Vec3> out;
  const auto add = [&](const std::vector<Vec3>& points) {
    out.insert(out.end(), points.begin(), points.end());
  };
  const auto addCurve = [&](const CurveInput& c) {
    if (const auto* s = std::get_if<SampledCurve>(&c)) add(s->points);
    if (const auto* f = std::get_if<FourierCurve>(&c)) out.push_back(f->a0);
  };
  if (const auto* m = model.as<SpectralModel>()) {
    for (const SpectralCondition& c : m->conditions)
      if (c.derivative == 0) addCurve(c.curve);
  } else if (const auto* m = model.as<CrossSectionModel>()) {
    for (const CurveInput& c : m->curves) addCurve(c);
  } else if (const auto* m = model.as<BSplinePdeModel>()) {
    for (const Vec3& p : m->net.points)
      if (p.allFinite()) out.push_back(p);  // the inner points are NaN: solved
    for (std::vector<Vec3>* c : cornerCurves(const_cast<BSplinePdeModel&>(*m))) add(*c);
  }
  return out;
}

/// The number of points a curve holds (Fourier curves: 0).
std::size_t pointCount(const CurveInput& c) {
  const auto* s = std::get_if<SampledCurve>(&c);
  return s ? s->points.size() : 0;
}

}  // namespace

void checkReach(const AnyModel& before, const SolvedModel& solvedBefore, const AnyModel& after,
                const SolvedModel& solvedAfter) {
  // How far the handles moved: the largest offset of a corresponding point.
  const std::vector<Vec3> was = handlePoints(before), now = handlePoints(after);
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
AnyModel shapeEdited(const AnyModel& model, const SolvedModel& solved, const ShapeEdit& edit) {
  const ModelReader rd("edit");
  AnyModel next = model;
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, MoveCurvePoints>) {
          const CurveTarget target = curveTarget(next, e.curve, "$.curve");
          std::vector<Vec3>& points =
              target.input ? std::get<SampledCurve>(*target.input).points : *target.points;
          movePoints(points, e.points, e.positions, e.falloff);
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
          if (auto* m = next.as<SpectralModel>()) {
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
            auto& options = next.get<CrossSectionModel>().options;
            if (e.a) options.a = *e.a;
            if (e.modes) options.modes = *e.modes;
            if (e.remainder) options.remainder = *e.remainder;
            if (e.method) options.method = *e.method;
          }
        } else if constexpr (std::is_same_v<T, SetSpine>) {
          next.get<SpectralModel>().spineEdits = e.edits;
        } else if constexpr (std::is_same_v<T, AddSection>) {
          auto& m = next.get<CrossSectionModel>();
          const std::size_t i = e.index;
          CurveInput curve;
          if (e.curve) {
            curve = *e.curve;
          } else {
            const CrossSectionChain& chain = *solved.surface().get<SolvedSpectral>().chain;
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
          auto& m = next.get<CrossSectionModel>();
          m.curves.erase(m.curves.begin() + e.index);
          if (!m.options.u.empty()) m.options.u.erase(m.options.u.begin() + e.index);
        } else {
          static_assert(std::is_same_v<T, MoveControlPoints>);
          ControlNet& net = next.get<BSplinePdeModel>().net;
          for (std::size_t k = 0; k < e.points.size(); ++k)
            net(e.points[k][0], e.points[k][1]) = e.positions[k];
        }
      },
      edit);
  if (auto* m = next.as<BSplinePdeModel>(); m && (std::holds_alternative<MoveCurvePoints>(edit) ||
                                                  std::holds_alternative<TransformCurve>(edit))) {
    BSplinePdeModel before = model.get<BSplinePdeModel>();
    keepCornersShared(before, *m);
  }
  // What the file parser checks of the result (counts, orders, spine u order, modes against
  // points), with the model file's paths; the solver's refusals come when the session solves.
  parseModel(serializeModel(next), "edit");
  return next;
}

}  // namespace

namespace detail {

EditResult applyShapeEdit(const EditContext& context, const ModelEdit& modelEdit) {
  const ShapeEdit& edit = modelEdit.as<ShapeEdit>(modelTypeName(*context.current.model));
  // A drag's absolute steps apply to the model as the drag began.
  const ModelState* base = &context.current;
  const auto* t = std::get_if<TransformCurve>(&edit);
  const auto* m = std::get_if<MoveCurvePoints>(&edit);
  if (((t && t->fromGroupStart) || (m && m->falloff > 0.0)) && context.groupStart)
    base = context.groupStart;
  auto next = std::make_shared<const AnyModel>(shapeEdited(*base->model, *base->solved, edit));
  auto solvedNext = std::make_shared<const SolvedModel>(solve(next, context.source));
  checkReach(*base->model, *base->solved, *next, *solvedNext);
  return {{std::move(next), std::move(solvedNext), nullptr}};
}

}  // namespace detail

std::string dragAdvice(const AnyModel& model) {
  if (const auto* m = model.as<CrossSectionModel>(); m && m->options.method != ChainMethod::Global)
    return fmt::format(
        "this chain is built by the seed's marching method \"{}\": a moved point is passed "
        "on from patch to patch and can move the surface far from it. The global chain keeps a "
        "drag local",
        m->options.method == ChainMethod::ExactC2 ? "c2" : "shared-curves");
  const auto* m = model.as<SpectralModel>();
  if (!m) return "";
  // A spectral patch: point 0 of each position condition given as points moved a little,
  // the surface's largest move measured (the probe's meshes correspond vertex by vertex).
  const auto positions = [](const SolvedModel& solved) {
    return tessellate(solved, TessellateOptions{.resolution = kReachSamples}).positions;
  };
  try {
    const SolvedModel base = solve(model, "probe");
    const auto was = positions(base);
    Bounds box;
    for (std::size_t k = 0; k + 2 < was.size(); k += 3)
      box.add(Vec3(was[k], was[k + 1], was[k + 2]));
    const double d = kProbeFraction * box.diagonal();
    double worst = 0.0;
    for (std::size_t i = 0; i < m->conditions.size(); ++i) {
      const auto* points = std::get_if<SampledCurve>(&m->conditions[i].curve);
      if (m->conditions[i].derivative != 0 || !points) continue;
      SpectralModel probe = *m;
      std::get<SampledCurve>(probe.conditions[i].curve).points[0] += d * Vec3(1, 2, 3).normalized();
      const auto now = positions(solve(AnyModel(std::move(probe)), "probe"));
      double moved = 0.0;
      for (std::size_t k = 0; k + 2 < was.size(); k += 3)
        moved = std::max(
            moved, Vec3(now[k] - was[k], now[k + 1] - was[k + 1], now[k + 2] - was[k + 2]).norm());
      worst = std::max(worst, moved / d);
    }
    if (worst <= kAdviseRatio) return "";
    return fmt::format(
        "this patch of order {} through {} curves is ill-conditioned between them: one point "
        "moved by d moves the surface by up to {:.2g} d. Move whole curves (their centre marks) "
        "or the spine",
        m->op.order(), m->conditions.size(), worst);
  } catch (const ModelError&) {
    return "";  // a model that does not solve has no drag to advise on
  }
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
