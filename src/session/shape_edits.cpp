// Shape edits of spectral, cross-section and B-spline PDE models (include/pdesurf/session.hpp),
// as src/io/shape_edit_io.cpp parses them: applied to a copy of the model, and checked as its
// file would be before the session takes it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "io/model_reader.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"
#include "session/curve_target.hpp"

namespace pdesurf {

namespace {

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

/// The number of points a curve holds (Fourier curves: 0).
std::size_t pointCount(const CurveInput& c) {
  const auto* s = std::get_if<SampledCurve>(&c);
  return s ? s->points.size() : 0;
}

}  // namespace

bool takesShapeEdits(const AnyModel& model) {
  return !std::holds_alternative<VertexFrameModel>(model);
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
