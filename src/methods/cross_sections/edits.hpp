// The shape edits of cross-section chains (ShapeEditsOf<CrossSectionModel>, shape_edits.hpp):
// their curves (the sections), the chain's options, adding and removing sections, the
// handles; private to src/methods/.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "methods/shape_edits/shape_edits.hpp"

namespace pdesurf::detail {

template <>
struct ShapeEditsOf<CrossSectionModel> {
  static constexpr std::array<const char*, 3> kOps = {"set-operator", "add-section",
                                                      "remove-section"};
  static CurveTarget curve(CrossSectionModel& m, const CurveRef& ref, const std::string& path);
  static ShapeEdit parseOwnEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                                const CrossSectionModel& m);
  static void applyOwnEdit(CrossSectionModel& m, const SolvedModel& solved, const ShapeEdit& edit);
  static void afterCurveEdit(const CrossSectionModel&, CrossSectionModel&) {}
  static std::vector<Vec3> reachPoints(const CrossSectionModel& m);
  /// The seed's marching chains ("c2", "shared-curves") pass a moved point on.
  static std::string dragAdvice(const CrossSectionModel& m);
  /// Its sections' points.
  static ModelHandles handles(const CrossSectionModel& m, const SolvedModel& solved);
  /// Its chain's a, modes, remainder and method; its overlay: curves and spine.
  static ModelSettings settings(const CrossSectionModel& m);
};

}  // namespace pdesurf::detail
