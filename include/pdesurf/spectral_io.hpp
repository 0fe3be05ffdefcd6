// Model files of the spectral engine: `"type": "spectral"` (one patch of Ugail's or Fu's
// operator through position and derivative curves) and `"type": "cross-sections"` (a chain
// of sixth-order patches through ordered closed curves). docs/model-format.md describes
// both; docs/spectral.md the mathematics.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "pdesurf/bspline_pde_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral.hpp"
#include "pdesurf/vertex_frames.hpp"

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

/// Any model file.
using AnyModel = std::variant<VertexFrameModel, SpectralModel, CrossSectionModel, BSplinePdeModel>;

/// The "type" of a model file: "vertex-frames", "spectral", "cross-sections", "bspline-pde".
const char* modelTypeName(const AnyModel& model);
/// The "name" a model file gives (empty when it gives none).
const std::string& modelNameOf(const AnyModel& model);

/// Parses and validates a model of any type (by its "type"); `source` names it in errors.
AnyModel parseModel(std::string_view text, const std::string& source);
/// Reads and parses a model file of any type (errors name the path).
AnyModel loadModel(const std::string& path);

/// The model as JSON text that parseModel reads back to the same model (numbers written
/// shortest round-trip, every option written out). The AnyModel overload throws
/// std::invalid_argument for a type it cannot write yet.
std::string serializeModel(const SpectralModel& model);
std::string serializeModel(const CrossSectionModel& model);
std::string serializeModel(const AnyModel& model);

/// Parses one closed curve as written in model files: {"points": [[x,y,z], ...], "v": [...]}
/// or {"fourier": {"a0": [x,y,z], "a": [[...], ...], "b": [[...], ...]}}; `path` is its
/// JSON path in errors.
CurveInput parseCurve(std::string_view json, const std::string& source, const std::string& path);

/// The curves of a curves file: a cross-sections model, or {"curves": [curve, ...]}.
std::vector<CurveInput> loadCurves(const std::string& path);

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
/// A spectral or cross-section model, solved; nothing for the other types.
std::optional<SolvedSpectral> solveIfSpectral(const AnyModel& model, const std::string& source);

/// The tessellation for `samples` points per patch side, the resolution of the CLI and the
/// studio: `samples` rows along u and 4(samples − 1) columns around the closed direction v
/// (a turn is about 2π times longer than a patch is long), at least 8.
SpectralTessellateOptions spectralMeshOptions(std::uint32_t samples);
Mesh tessellate(const SolvedSpectral& solved, std::uint32_t samples);

}  // namespace pdesurf
