// Spectral and cross-section models solved and tessellated (include/pdesurf/spectral_model.hpp).
#include <stdexcept>
#include <utility>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf {

SolvedSpectral solve(const SpectralModel& model, const std::string& source) {
  SolvedSpectral s;
  s.type = "spectral";
  try {
    SpectralPatch patch = solve(model.op, model.conditions, model.options);
    for (const SpineEdit& edit : model.spineEdits) patch = editSpine(patch, edit);
    s.patch = std::move(patch);
  } catch (const InvalidArgument& e) {
    throw ModelError(source, "$", e.what());
  }
  return s;
}

SolvedSpectral solve(const CrossSectionModel& model, const std::string& source) {
  SolvedSpectral s;
  s.type = "cross-sections";
  try {
    s.chain = solve(model.curves, model.options);
  } catch (const InvalidArgument& e) {
    throw ModelError(source, "$.curves", e.what());
  }
  return s;
}

Mesh tessellate(const SolvedSpectral& solved, const TessellateOptions& options) {
  return solved.chain ? tessellate(*solved.chain, options) : tessellate(*solved.patch, options);
}

}  // namespace pdesurf
