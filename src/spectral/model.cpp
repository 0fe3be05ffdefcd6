// Spectral and cross-section models solved and tessellated (include/pdesurf/spectral_model.hpp).
#include <algorithm>
#include <stdexcept>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf {

SpectralPatch solveModel(const SpectralModel& model, const std::string& source) {
  try {
    SpectralPatch patch = solveSpectral(model.op, model.conditions, model.options);
    for (const SpineEdit& edit : model.spineEdits) patch = editSpine(patch, edit);
    return patch;
  } catch (const InvalidArgument& e) {
    throw ModelError(source, "$", e.what());
  }
}

CrossSectionChain solveModel(const CrossSectionModel& model, const std::string& source) {
  try {
    return buildCrossSectionChain(model.curves, model.options);
  } catch (const InvalidArgument& e) {
    throw ModelError(source, "$.curves", e.what());
  }
}

SolvedSpectral solveSpectralModel(const SpectralModel& model, const std::string& source) {
  SolvedSpectral s;
  s.type = "spectral";
  s.patch = solveModel(model, source);
  return s;
}

SolvedSpectral solveSpectralModel(const CrossSectionModel& model, const std::string& source) {
  SolvedSpectral s;
  s.type = "cross-sections";
  s.chain = solveModel(model, source);
  return s;
}

SpectralTessellateOptions spectralMeshOptions(std::uint32_t samples) {
  SpectralTessellateOptions o;
  o.uResolution = std::max(samples, 2u);
  o.vResolution = std::max(4 * (o.uResolution - 1), 8u);
  return o;
}

Mesh tessellate(const SolvedSpectral& solved, std::uint32_t samples) {
  const SpectralTessellateOptions options = spectralMeshOptions(samples);
  return solved.chain ? tessellate(*solved.chain, options) : tessellate(*solved.patch, options);
}

}  // namespace pdesurf
