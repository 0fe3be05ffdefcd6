// The shape edits of B-spline PDE models (ShapeEditsOf<BSplinePdeModel>, shape_edits.hpp):
// their curves by file name, the shared corners, a net's given control points, the handles;
// private to src/methods/.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "methods/shape_edits/shape_edits.hpp"

namespace pdesurf::detail {

template <>
struct ShapeEditsOf<BSplinePdeModel> {
  static constexpr std::array<const char*, 1> kOps = {"move-control-points"};
  static CurveTarget curve(BSplinePdeModel& m, const CurveRef& ref, const std::string& path);
  static ShapeEdit parseOwnEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                                const BSplinePdeModel& m);
  static void applyOwnEdit(BSplinePdeModel& m, const SolvedModel& solved, const ShapeEdit& edit);
  /// Corners stay shared: every curve end that sat where a moved end of a curve sat (another
  /// curve's corner, a closed curve's other end) moves with it.
  static void afterCurveEdit(const BSplinePdeModel& before, BSplinePdeModel& after);
  static std::vector<Vec3> reachPoints(const BSplinePdeModel& m);
  static std::string dragAdvice(const BSplinePdeModel&) { return ""; }
  /// Its curves' points (the boundary's sides and second rows, a blend's curves), a tangent
  /// row's tips (drawn from the side they leave, at their parameters on it) and a net's given
  /// control points (rows 0, 1, n_u and columns 0, 1, n_v).
  static ModelHandles handles(const BSplinePdeModel& m, const SolvedModel& solved);
  /// No operator to set; its overlay: control nets.
  static ModelSettings settings(const BSplinePdeModel&) { return {{}, {}, "Control nets"}; }
};

}  // namespace pdesurf::detail
