// The shape edits of spectral models (ShapeEditsOf<SpectralModel>, shape_edits.hpp): their
// curves (the conditions), the operator and spine edits, the handles (the conditions' points,
// tangent tips and spine points); private to src/methods/.
// What cross-section chains share with them (the operator's parse, a curve's reach points) is
// here too.
#pragma once

#include <string>
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

/// The spectral method's shape edits (spectral/edits.cpp).
extern const ShapeEditsOf<SpectralModel> kSpectralEdits;

}  // namespace pdesurf::detail
