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

/// Solves a parsed model: one patch (`patch`) or a chain (`chain`). The solver's own
/// refusals (singular conditions, collapsed curves) become ModelError naming `source`.
SolvedSpectral solve(const SpectralModel& model, const std::string& source);
SolvedSpectral solve(const CrossSectionModel& model, const std::string& source);

/// The patch's or the chain's mesh (tessellate(SpectralPatch) and
/// tessellate(CrossSectionChain), spectral.hpp).
Mesh tessellate(const SolvedSpectral& solved, const TessellateOptions& options = {});

}  // namespace pdesurf
