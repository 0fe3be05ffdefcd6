// A mesh rebuilt as a model in one call, as `pdesurf rebuild` and the Python package's
// pdesurf.rebuild do it: the options of the command checked, the layout (grid, tube, quad
// mesh, automatic, or the smallest automatic one that reaches a target RMS) fitted, or the
// mesh sliced and its sections joined by the C4 chain; then the model measured against the
// mesh both ways (distances, folds, normals) and its storage counted (docs/rebuild.md).
// Part of the CGAL module (pdesurf::cgal), since it fits and measures through CGAL's trees.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/sections.hpp"
#include "pdesurf/spectral.hpp"

namespace pdesurf {

enum class RebuildKind {
  VertexFrames,   ///< a layout of frames fitted to the mesh
  CrossSections,  ///< sections sliced off the mesh, fitted and joined by the global C4 chain
};

/// The automatic layout when neither `frames` nor `targetRms` is given.
inline constexpr std::uint32_t kDefaultAutoFrames = 200;

/// Everything `pdesurf rebuild` takes, with its defaults. Options of the other kind are
/// ignored (except fit.fitShape, refused for cross sections).
struct RebuildOptions {
  RebuildKind kind = RebuildKind::VertexFrames;
  /// The mesh's name: in error messages, the model's default name and its description.
  std::string source = "mesh";
  /// The model's name; empty: "STEM (vertex frames)" of `source`, or its file name for
  /// cross sections.
  std::string name;

  // Vertex frames: at most one layout; none of them is the automatic layout.
  std::optional<std::array<std::uint32_t, 2>> grid;  ///< U × V frames on a disk (1 to 1000)
  /// RINGS × SECTORS frames round the part `slice` chooses (rings 1 to 1000, sectors 3 to
  /// 1000); the model is fitted to, and measured against, that part.
  std::optional<std::array<std::uint32_t, 2>> tube;
  std::string quadsPath;  ///< a quad mesh file (OBJ, OFF, PLY) whose quads become the frames
  // The automatic layout (each unset: not given).
  std::uint32_t frames = 0;  ///< about this many frames (0: not given, kDefaultAutoFrames)
  /// The smallest automatic layout whose fitted model reaches this RMS both ways (a
  /// fraction of the diagonal in (0, 1); parseTargetRms reads "0.2%").
  std::optional<double> targetRms;
  std::optional<QuadConstruction> quads;  ///< default PairTriangles
  std::optional<double> creaseAngle;      ///< degrees in [0, 180], default 60
  /// With targetRms: the bound on the model's RMS normal deviation, degrees in [0, 180]
  /// (default kMaxNormalDeviation; 180: no bound).
  std::optional<double> maxNormalDeviation;
  /// The fit's normal-alignment weight ν (--normal-weight, [0, 1]; FitOptions::normalWeight).
  /// Unset: kNormalWeight with targetRms, where the search's fold and normal bounds judge
  /// every trial and the term lets a smaller layout meet them (docs/rebuild.md, "Normals"); 0
  /// for any other layout, where it costs time and, on some meshes, folded area.
  std::optional<double> normalWeight;
  /// The fit: maxIterations 0 to 100000, tolerance [0, 1], smoothness [0, 1e6],
  /// samplesPerSide 0 (automatic) or 3 to 65, conformalWeight (--fold-weight) [0, 1];
  /// preventFolds, fitShape. Its normalWeight is not read (normalWeight above sets it); its
  /// onIteration is RebuildProgress's.
  FitOptions fit;
  std::uint32_t resolution = 17;  ///< samples per patch side for the measure (2 to 4097)

  /// Slicing: the cross sections' planes and the tube's (`count`, 2 to 100000, is the
  /// tube's 2R + 1 there).
  SliceOptions slice = [] {
    SliceOptions cut;
    cut.count = 25;
    return cut;
  }();
  // Cross sections: the chain.
  std::uint32_t modes = 8;     ///< Fourier modes per section (1 to 256)
  std::uint32_t points = 128;  ///< points per section (8 to 100000, at least 2 modes + 1)
  double a = 1.0;              ///< finite, non-zero
  ChainEnds ends = ChainEnds::Natural;
  bool exact = false;

  /// Face samples on each mesh for the distances (1 to 1e8).
  std::size_t samples = 100000;
  /// Measure the model against the mesh (RebuildReport::distance, normals); off: only the
  /// fit's own measures.
  bool measure = true;
};

/// An option that cannot be used (a value out of its range, options that exclude each other);
/// what() names the option as the front end spells it (RebuildOptionStyle).
class RebuildOptionError : public InvalidArgument {
 public:
  RebuildOptionError(std::string option, const std::string& message)
      : InvalidArgument(message), option_(std::move(option)) {}
  /// The option's key: its Python keyword ("target_rms", "grid", ...).
  const std::string& option() const { return option_; }

 private:
  std::string option_;
};

/// How messages spell the options: as the CLI's flags (`--target-rms`, `--grid U V`) or as
/// the Python package's keywords (`target_rms`, `grid=(U, V)`).
enum class RebuildOptionStyle { Cli, Python };

/// Checks the options before any work: every value in its range and no two options that
/// exclude each other. Throws RebuildOptionError.
void checkRebuildOptions(const RebuildOptions& options,
                         RebuildOptionStyle style = RebuildOptionStyle::Cli);

/// A target RMS as written, "0.002" or "0.2%", as a fraction of the diagonal; throws
/// RebuildOptionError unless it is a number in (0, 1) (a percentage in (0 %, 100 %)).
double parseTargetRms(const std::string& text, RebuildOptionStyle style = RebuildOptionStyle::Cli);

/// The target search that `options` ask for (RebuildOptions::targetRms, read as 0 where it is
/// not set; maxNormalDeviation; the automatic layout's shape; the fit without its
/// onIteration; the resolution); its onTrial is empty.
TargetSearchOptions targetSearchOptions(const RebuildOptions& options);

/// "vertex-frames" or "cross-sections"; "pair" or "split"; "natural" or "estimated"; else none.
std::optional<RebuildKind> parseRebuildKind(std::string_view name);
std::optional<QuadConstruction> parseQuadConstruction(std::string_view name);
std::optional<ChainEnds> parseChainEnds(std::string_view name);
const char* rebuildKindName(RebuildKind kind);
const char* chainEndsName(ChainEnds ends);

/// What the automatic layout made (AutoLayout without its meshes).
struct AutoLayoutReport {
  std::uint32_t requested = 0;  ///< frames asked for
  std::size_t frames = 0, baseTriangles = 0, components = 0, creaseEdges = 0, skippedTriangles = 0;
  /// n where the target search answered with the disk's n × n grid (AutoFit::grid; then
  /// baseTriangles and creaseEdges are 0); 0: the automatic layout.
  std::uint32_t grid = 0;
};

/// How the target-RMS search ended (TargetSearch).
struct TargetSearchReport {
  double targetRms = 0.0, maxFoldedArea = 0.0, maxNormalDeviation = 0.0;
  bool reached = false;
  TargetCheck met;  ///< the criteria the answer meets
  TargetSearch::Stop stop = TargetSearch::Stop::Reached;
  std::uint32_t trials = 0;
  bool foldsPrevented = false;   ///< the answer was fitted with steps that fold more refused
  double worseRms = 0.0;         ///< the answer's larger one-way RMS (of the diagonal)
  double foldedArea = 0.0;       ///< the answer's folded share of its area
  double normalDeviation = 0.0;  ///< the answer's RMS normal deviation (degrees)
};

/// The distances of a peer (Open CASCADE's loft through the same sections), measured by the
/// caller that made it (pdesurf::occt): the report's JSON shows them.
struct PeerMeasure {
  std::optional<MeshDistance> distance;
  std::string failure;  ///< why it failed, where it did
};

struct RebuildReport {
  RebuildKind kind = RebuildKind::VertexFrames;
  std::string name;  ///< the model's
  /// The model's tessellation against the mesh (or the part: cross sections, tubes), both
  /// ways, and its normals against the mesh's (with RebuildOptions::measure).
  bool measured = false;
  MeshDistance distance;
  NormalDeviation normals;
  std::size_t storageBytes = 0;           ///< the model's (the seed's Table 1 convention)
  std::size_t referenceStorageBytes = 0;  ///< the mesh's, or the part's
  std::size_t referenceTriangles = 0, referenceVertices = 0;
  // Vertex frames.
  std::size_t frames = 0, vertices = 0;
  std::vector<FitIteration> iterations;  ///< [0] is the start
  std::string stopReason;
  std::optional<AutoLayoutReport> automatic;  ///< the automatic layout (the search's answer)
  std::optional<TargetSearchReport> search;   ///< with RebuildOptions::targetRms
  // Cross sections.
  std::size_t sections = 0;
  double from = 0.0, to = 0.0;  ///< the first and last plane's coordinates
  std::optional<PeerMeasure> loft;
  /// Milliseconds: `read` is the caller's (reading the mesh), the rest rebuild's (`layout`
  /// for vertex frames; `fit` the fit, or the slicing, preparing, fitting and solving).
  struct Timings {
    double read = 0.0, layout = 0.0, fit = 0.0, measure = 0.0;
  } ms;
};

struct RebuildResult {
  AnyModel model;
  RebuildReport report;
  /// The part of the mesh the model rebuilds and was measured against (cross sections, tubes).
  std::optional<Mesh> part;
  std::vector<MeshSection> sections;   ///< cross sections: as the slicer kept them
  std::vector<SampledCurve> prepared;  ///< cross sections: aligned and resampled
};

/// Called while rebuilding, for progress reports (each may be empty).
struct RebuildProgress {
  /// The automatic layout made (not the search's: see onTrial), before its fit.
  std::function<void(const AutoLayoutReport&)> onLayout;
  /// The fit's start and each accepted iteration (not during the target search).
  std::function<void(const FitIteration&)> onIteration;
  /// Each trial of the target search: the frames asked for and the fitted, measured layout.
  std::function<void(std::uint32_t requested, const AutoFit&)> onTrial;
};

/// Rebuilds `mesh` as `options` say (checked first: RebuildOptionError). Throws LayoutError
/// for a mesh or quad file that cannot give the layout, MeshSliceError and
/// InvalidArgument for sections that cannot be used (naming the plane), and
/// InvalidArgument for a mesh the fit or the measure cannot use ("the rebuilt part:
/// ..." where the sections' part is empty).
RebuildResult rebuild(const Mesh& mesh, const RebuildOptions& options,
                      const RebuildProgress& progress = {});

/// The report as `pdesurf rebuild --as cross-sections --json` prints it (two-space indents,
/// keys in a fixed order; `mesh` is options.source, `output` the model file written or empty).
std::string rebuildReportJson(const RebuildReport& report, const RebuildOptions& options,
                              const std::string& output);

/// What a one-way distance's JSON holds (oneWayDistanceJson).
enum class DistanceFields {
  Figures,  ///< rms, mean and max, absolute and relative: the rebuild's report
  All,      ///< the samples first, then the figures, where the max is and the cover radius
};

/// One direction of a MeshDistance as JSON, its keys in a fixed order ("rms",
/// "rms_relative", ...): the writer of `pdesurf compare --json` (`All`) and of the rebuild's
/// report (`Figures`).
nlohmann::ordered_json oneWayDistanceJson(const OneWayDistance& d, DistanceFields fields);
/// A NormalDeviation as JSON: "folded_area", "rms_degrees", "reversed".
nlohmann::ordered_json normalDeviationJson(const NormalDeviation& n);

}  // namespace pdesurf
