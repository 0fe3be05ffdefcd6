// The shape edits (ShapeEdit, session.hpp) of the spectral, cross-section and B-spline PDE
// methods, private to src/methods/: the methods' parseEdit and applyEdit call these.
#pragma once

#include "pdesurf/method.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::detail {

/// Applies a shape edit (a ShapeEdit in `edit`) to the session's model (a drag's absolute
/// steps to the model as the group began): the result checked as its file would be, solved
/// and checked by checkReach. Throws ModelError (source "edit") naming what is wrong.
EditResult applyShapeEdit(const EditContext& context, const ModelEdit& edit);

}  // namespace pdesurf::detail
