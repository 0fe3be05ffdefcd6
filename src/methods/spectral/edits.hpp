// The shape edits of spectral models (ShapeEditsOf<SpectralModel>, shape_edits.hpp): their
// curves (the conditions), the operator and spine edits, the handles; private to src/methods/.
// What cross-section chains share with them (the operator's parse, a curve's reach points) is
// here too.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "methods/shape_edits/shape_edits.hpp"

namespace pdesurf::detail {

/// Parses set-operator: a spectral model's fields (`spectral`) or a chain's.
SetOperator parseSetOperator(const ModelReader& rd, const Json& doc, bool spectral);
/// Adds the points a drag moves of curve `c` to `out`: its points, or a Fourier curve's a0.
void addReachPoints(std::vector<Vec3>& out, const CurveInput& c);
/// The points of `c` when it is given as points, else nullptr.
const std::vector<Vec3>* curvePoints(const CurveInput& c);
/// A Fourier curve's a0, else zero.
Vec3 curveA0(const CurveInput& c);

template <>
struct ShapeEditsOf<SpectralModel> {
  static constexpr std::array<const char*, 3> kOps = {"set-operator", "set-spine",
                                                      "move-spine-point"};
  static CurveTarget curve(SpectralModel& m, const CurveRef& ref, const std::string& path);
  static ShapeEdit parseOwnEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                                const SpectralModel& m);
  static void applyOwnEdit(SpectralModel& m, const SolvedModel& solved, const ShapeEdit& edit);
  static void afterCurveEdit(const SpectralModel&, SpectralModel&) {}
  static std::vector<Vec3> reachPoints(const SpectralModel& m);
  static std::string dragAdvice(const SpectralModel& m);
  /// Its conditions' points, tangent tips (a derivative condition's vectors from the points
  /// of the position condition at its u; a Fourier one's a0 from that condition's centre) and
  /// spine points (spineHandles, kSpineHandles of them).
  static ModelHandles handles(const SpectralModel& m, const SolvedModel& solved);
  /// Its operator (kind, N, a, modes, remainder); its overlay: curves and spine.
  static ModelSettings settings(const SpectralModel& m);
};

}  // namespace pdesurf::detail
