// The models of the spectral engine as files describe them (docs/model-format.md):
// `"type": "spectral"` (one patch of Ugail's or Fu's operator through position and
// derivative curves) and `"type": "cross-sections"` (a chain of sixth-order patches through
// ordered closed curves), and their solutions. Parsing and writing: spectral_io.hpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/spectral.hpp"

namespace pdesurf {

/// What a `"type": "spectral"` file says: the operator, the options and the conditions,
/// then the spine edits applied in order (seed 003 §4.2).
struct SpectralModel {
  std::string name, description;
  SpectralOperator op;
  SpectralOptions options;
  std::vector<SpectralCondition> conditions;
  std::vector<SpineEdit> spineEdits;
};

/// What a `"type": "cross-sections"` file says: K ≥ 4 ordered closed curves and the options.
struct CrossSectionModel {
  std::string name, description;
  CrossSectionOptions options;
  std::vector<CurveInput> curves;
};

/// Solves a parsed model. The solver's own refusals (singular conditions, collapsed
/// curves) become ModelError naming `source`.
SpectralPatch solveModel(const SpectralModel& model, const std::string& source);
CrossSectionChain solveModel(const CrossSectionModel& model, const std::string& source);

/// A spectral or cross-section model, solved: one patch or a chain of patches.
struct SolvedSpectral {
  std::string type;  ///< "spectral" or "cross-sections"
  std::optional<SpectralPatch> patch;
  std::optional<CrossSectionChain> chain;

  std::size_t patchCount() const { return chain ? chain->patches.size() : 1; }
  const SpectralPatch& patchAt(std::size_t k) const {
    return chain ? chain->patches[k].patch : *patch;
  }
  /// The shown u range of patch k.
  std::pair<double, double> range(std::size_t k) const {
    return chain ? std::pair{chain->patches[k].tStart, chain->patches[k].tEnd}
                 : std::pair{patch->uStart(), patch->uEnd()};
  }
};
SolvedSpectral solveSpectralModel(const SpectralModel& model, const std::string& source);
SolvedSpectral solveSpectralModel(const CrossSectionModel& model, const std::string& source);

/// The tessellation for `samples` points per patch side, the resolution of the CLI and the
/// studio: `samples` rows along u and 4(samples − 1) columns around the closed direction v
/// (a turn is about 2π times longer than a patch is long), at least 8.
SpectralTessellateOptions spectralMeshOptions(std::uint32_t samples);
Mesh tessellate(const SolvedSpectral& solved, std::uint32_t samples);

}  // namespace pdesurf
