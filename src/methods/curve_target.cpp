// The curve a shape edit names in a model (curve_target.hpp).
#include "methods/curve_target.hpp"

#include <fmt/format.h>

#include "io/model_reader.hpp"

namespace pdesurf::detail {

namespace {

/// The B-spline PDE curves by their file names, per form.
constexpr const char* kSideNames[] = {"uMin", "uMax", "vMin", "vMax"};
constexpr const char* kClosedNames[] = {"start", "end"};

}  // namespace

/// The curve `ref` names in `model` (a copy the edit changes); throws ModelError (source
/// "edit", at `path`) when the model has no such curve.
CurveTarget curveTarget(AnyModel& model, const CurveRef& ref, const std::string& path) {
  const ModelReader rd("edit");
  if (auto* m = model.as<SpectralModel>()) {
    if (!ref.name.empty()) rd.fail(path, "a spectral model's curves are numbered (its conditions)");
    const std::uint32_t i = ref.index;
    if (i >= m->conditions.size())
      rd.fail(path, fmt::format("condition {} is out of range (the model has {}, indices 0 to {})",
                                i, m->conditions.size(), m->conditions.size() - 1));
    return {&m->conditions[i].curve, nullptr, m->conditions[i].derivative > 0,
            fmt::format("$.conditions[{}].curve", i)};
  }
  if (auto* m = model.as<CrossSectionModel>()) {
    if (!ref.name.empty()) rd.fail(path, "a chain's sections are numbered");
    if (ref.index >= m->curves.size())
      rd.fail(path, fmt::format("section {} is out of range (the chain has {}, indices 0 to {})",
                                ref.index, m->curves.size(), m->curves.size() - 1));
    return {&m->curves[ref.index], nullptr, false, fmt::format("$.curves[{}]", ref.index)};
  }
  auto& m = model.get<BSplinePdeModel>();
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

}  // namespace pdesurf::detail
