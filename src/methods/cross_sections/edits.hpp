// The shape edits of cross-section chains (ShapeEditsOf<CrossSectionModel>, shape_edits.hpp):
// their curves (the sections), the chain's options ("set-operator"), adding and removing
// sections, the handles (its sections' points); private to src/methods/.
#pragma once

#include "methods/shape_edits/shape_edits.hpp"

namespace pdesurf::detail {

/// The cross-sections method's shape edits (cross_sections/edits.cpp).
extern const ShapeEditsOf<CrossSectionModel> kCrossSectionEdits;

}  // namespace pdesurf::detail
