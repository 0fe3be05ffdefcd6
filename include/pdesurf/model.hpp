// The model layer: a model of any type, parsed (AnyModel) or solved (SolvedModel), and what
// every front end (the CLI, the studio, the session) does with one, written once. Front ends
// never branch on the model's type; a new method is one more alternative of AnyModel and of
// SolvedModel's variant, and one more case in src/model/. docs/architecture.md draws where
// this layer sits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/geometry.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/spectral_model.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// Any model as a file describes it (docs/model-format.md). Parsed and written by io
/// (model_io.hpp: parseModel, loadModel, serializeModel).
using AnyModel = std::variant<VertexFrameModel, SpectralModel, CrossSectionModel, BSplinePdeModel>;

/// The "type" of a model file: "vertex-frames", "spectral", "cross-sections", "bspline-pde".
const char* modelTypeName(const AnyModel& model);
/// The "name" a model file gives (empty when it gives none).
const std::string& modelNameOf(const AnyModel& model);

/// A spectral or cross-section model, solved; nothing for the other types.
std::optional<SolvedSpectral> solveIfSpectral(const AnyModel& model, const std::string& source);

/// Any model, solved. Alternatives in the order of AnyModel's: a vertex-frame surface, a
/// spectral patch or cross-section chain (SolvedSpectral), a B-spline PDE surface or blend.
using SolvedAlternative = std::variant<VertexFrameSurface, SolvedSpectral, SolvedBSplinePde>;

/// A parsed model with its solved surface, the name it goes by in messages (`source`, a
/// file path) and the options it was solved with.
class SolvedModel {
 public:
  SolvedModel(std::shared_ptr<const AnyModel> model, SolvedAlternative solved, std::string source,
              SolveOptions options);

  const AnyModel& model() const { return *model_; }
  const SolvedAlternative& solved() const { return solved_; }
  const std::string& source() const { return source_; }
  const SolveOptions& options() const { return options_; }
  /// The model's "type": "vertex-frames", "spectral", "cross-sections", "bspline-pde".
  const char* type() const { return modelTypeName(*model_); }
  /// The model's own name, else the file name of its source (modelDisplayName).
  std::string displayName() const;
  /// The solver's notes (vertex frames: strips pinned, …); empty for the other types.
  const std::vector<std::string>& notes() const;
  /// The solved spectral or cross-section model, else nullptr (the spine and fit commands).
  const SolvedSpectral* spectral() const { return std::get_if<SolvedSpectral>(&solved_); }
  /// The solved vertex-frame surface, else nullptr (the Coons baselines).
  const VertexFrameSurface* frames() const { return std::get_if<VertexFrameSurface>(&solved_); }

 private:
  std::shared_ptr<const AnyModel> model_;  // shared with a session's undo steps
  SolvedAlternative solved_;
  std::string source_;
  SolveOptions options_;
};

/// Solves a model of any type. Vertex frames use `options` (and `topology` when given: one
/// built by buildTopology for this model's frames, shared by every solve of a session);
/// the other types' solver refusals become ModelError naming `source`.
SolvedModel solveModel(std::shared_ptr<const AnyModel> model, const std::string& source,
                       const SolveOptions& options = {},
                       std::shared_ptr<const FrameTopology> topology = nullptr);
SolvedModel solveModel(AnyModel model, const std::string& source, const SolveOptions& options = {});

/// Throws std::out_of_range when `options` do not fit `model` (vertex frames: a seed frame
/// the model does not have), with what is wrong: "out of range, the model has 3 frames
/// (indices 0 to 2)".
void checkSolveOptions(const AnyModel& model, const SolveOptions& options);

/// The mesh for options.resolution samples per patch side, for every type (the resolution of
/// the CLI's --resolution and the studio's meshes): watertight where patches share edges,
/// with normals and patch ids.
Mesh tessellate(const SolvedModel& solved, const TessellateOptions& options = {});

/// Tessellates again and again into one mesh (the studio's page): a vertex-frame model keeps
/// its layout while only positions and normals change (a drag).
class ModelTessellator {
 public:
  const Mesh& tessellate(const SolvedModel& solved, const TessellateOptions& options);
  /// Changes whenever a call lays the mesh out afresh: while it stays the same, the indices,
  /// patch ids and vertex count of the mesh stay the same.
  std::uint64_t layoutVersion() const { return layoutVersion_; }

 private:
  Tessellator frames_;
  std::uint64_t framesLayout_ = 0;
  bool lastWasFrames_ = false;
  Mesh mesh_;
  std::uint64_t layoutVersion_ = 0;
};

/// One patch sampled on a grid × grid lattice: points[j*grid+i] = S(u_i, v_j).
struct PatchSamples {
  const char* label = "patch";  ///< the JSON key of `index`: "frame" for vertex frames
  std::size_t index = 0;
  std::uint32_t grid = 0;
  std::optional<std::pair<double, double>> u;          ///< spectral: the patch's u range
  std::optional<std::array<std::uint32_t, 2>> origin;  ///< B-spline pieces: origin in the blend
  std::vector<Vec3> points;
};
/// Every patch sampled: vertex frames and B-spline pieces on the unit square, spectral
/// patches over their u range and v ∈ [0, 2π].
std::vector<PatchSamples> sample(const SolvedModel& solved, std::uint32_t grid);

/// What `build` and `info` report of a solved model.
struct ModelReport {
  std::string summary;  ///< "3 frames, 2 strips" / "spectral, order 12, …" / "bspline-pde, …"
  std::string quality;  ///< "C0 gap 0" / "condition error 1e-15" / "PDE residual 3e-16"
};
ModelReport report(const SolvedModel& solved);
/// `info`: counts, quality figures, bounding box and storage, as text or as JSON.
std::string infoText(const SolvedModel& solved, bool json);
/// The largest distance between two patches where they should meet (absolute), 0 for a
/// single patch: the studio's X-C0-Gap.
double largestC0Gap(const SolvedModel& solved);

/// The patches as NURBS faces (docs/nurbs-export.md).
NurbsModel toNurbs(const SolvedModel& solved, const NurbsExportOptions& options = {});

/// What the studio's frame view draws of a model it does not edit: polylines of the
/// defining curves (spectral position curves, B-spline control polygons) and spines.
/// Empty for vertex frames (the page draws their frames from the model itself).
struct ModelOverlay {
  std::vector<std::vector<Vec3>> curves, spines;
};
ModelOverlay overlay(const SolvedModel& solved);

/// `name` when it is not empty, else the file name of `path`: how output names a model.
std::string modelDisplayName(const std::string& name, const std::string& path);

/// "1 frame", "2 frames", "1 vertex", "3 vertices", "2 patches": a count and its noun.
std::string countText(std::size_t n, const std::string& noun);

/// Whether a session edits the model's parts (vertex frames) or only transforms it whole.
bool hasEditableParts(const AnyModel& model);

}  // namespace pdesurf
