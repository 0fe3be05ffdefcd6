// The model layer: a model of any method, parsed (AnyModel) or solved (SolvedModel, over
// the SolvedSurface interface), and what every front end (the CLI, the studio, the session)
// does with one, written once. Each surface method is one description (SurfaceMethod,
// method.hpp) in the registry; AnyModel and SolvedModel hold a method's own values behind
// that description, so front ends never branch on the model's type. docs/architecture.md
// draws where this layer sits and where the descriptions live.
#pragma once

#include <any>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/geometry.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/spectral_model.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

class SurfaceMethod;

/// The description registered for models of C++ type `type` (method.hpp: the built-in
/// methods and those given to registerMethod). Throws InvalidArgument when none is.
const SurfaceMethod& methodForModelType(const std::type_info& type);

/// Any model as a file describes it (docs/model-format.md): one method's own model value
/// (VertexFrameModel, SpectralModel, CrossSectionModel, BSplinePdeModel, or a registered
/// method's) with its method's description. A value: copies copy the model. Parsed and
/// written by io (model_io.hpp: parseModel, loadModel, serializeModel).
class AnyModel {
 public:
  /// Any registered method's model (implicit, as the variant it replaces was).
  template <class T>
  requires(!std::same_as<std::remove_cvref_t<T>, AnyModel>)
      AnyModel(T model)  // NOLINT(google-explicit-constructor)
      : value_(std::move(model)), method_(&methodForModelType(typeid(T))) {}

  /// The description of the model's method (its type name, parse, solve, …).
  const SurfaceMethod& method() const { return *method_; }
  /// The model as its method's own type, else nullptr: for the few places that work on one
  /// method's data (a method's own edits, the vertex-frame structure edits).
  template <class T>
  const T* as() const {
    return std::any_cast<T>(&value_);
  }
  template <class T>
  T* as() {
    return std::any_cast<T>(&value_);
  }
  template <class T>
  bool is() const {
    return as<T>() != nullptr;
  }
  /// The model as T; throws std::bad_any_cast when it is another method's.
  template <class T>
  const T& get() const {
    return std::any_cast<const T&>(value_);
  }
  template <class T>
  T& get() {
    return std::any_cast<T&>(value_);
  }

 private:
  std::any value_;
  const SurfaceMethod* method_;
};

/// The "type" of a model file: "vertex-frames", "spectral", "cross-sections", "bspline-pde",
/// or a registered method's.
const char* modelTypeName(const AnyModel& model);
/// The "name" a model file gives (empty when it gives none).
const std::string& modelNameOf(const AnyModel& model);

/// One patch sampled on a grid × grid lattice: points[j*grid+i] = S(u_i, v_j).
struct PatchSamples {
  std::size_t index = 0;  ///< the patch (SurfaceMethod::patchName: what its method calls it)
  std::uint32_t grid = 0;
  std::optional<std::pair<double, double>> u;          ///< spectral: the patch's u range
  std::optional<std::array<std::uint32_t, 2>> origin;  ///< B-spline pieces: origin in the blend
  std::vector<Vec3> points;
};

/// A model's defining curves as polylines: spectral position curves and B-spline control
/// polygons (`curves`), and spectral patches' spines (`spines`). Empty for vertex frames,
/// whose frames are the model itself. Geometry a viewer may draw over the surface to show
/// what defines it (the studio does).
struct ModelOverlay {
  std::vector<std::vector<Vec3>> curves, spines;
};

/// How `solve` solves a model of any method: one member for each method that takes options,
/// read by that method alone; a model of another method ignores it (a spectral model has no
/// seed frame), so solve(AnyModel) never reads an option meant for another method, and
/// checkSolveOptions checks only the member of the model's own method.
struct SolveOptions {
  VertexFrameSolveOptions vertexFrames;  ///< vertex-frame models: the solver, the seed frame

  bool operator==(const SolveOptions&) const = default;
};

/// How `sample` samples every patch of a model.
struct SampleOptions {
  /// Points per patch side (≥ 2): each patch a grid × grid lattice over its domain.
  std::uint32_t grid = 17;
};

/// What `build` reports of a solved model (`info`'s values: model_info.hpp).
struct ModelReport {
  std::string summary;  ///< "3 frames, 2 strips" / "spectral, order 12, …" / "bspline-pde, …"
  std::string quality;  ///< "C0 gap 0" / "condition error 1e-15" / "PDE residual 3e-16"
};

/// A patch's parameter rectangle [u0, u1] × [v0, v1] (u1 < u0 where a patch runs backwards).
struct PatchDomain {
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
};

/// A solved model of any method: what sampling, continuity checks, overlays, export,
/// compare and rebuild use without knowing the method. Each method's solve returns one
/// (a SolvedSurfaceOf its own solved value).
class SolvedSurface {
 public:
  virtual ~SolvedSurface() = default;

  virtual std::size_t patchCount() const = 0;
  /// Patch k's parameter domain: the rectangle `sample` spans.
  virtual PatchDomain domain(std::size_t patch) const = 0;
  /// S, S_u, S_v of patch k at (u, v) in its domain.
  virtual SurfacePoint evaluate(std::size_t patch, double u, double v) const = 0;
  /// The mesh for options.resolution samples per patch side. The default: each patch its
  /// own resolution × resolution grid over its domain (patches not welded), normals
  /// S_u × S_v.
  virtual Mesh tessellate(const TessellateOptions& options) const;
  /// Every patch on an options.grid × options.grid lattice over its domain (the default:
  /// through evaluate).
  virtual std::vector<PatchSamples> sample(const SampleOptions& options) const;
  /// The patches as NURBS faces (docs/nurbs-export.md).
  virtual NurbsModel toNurbs(const NurbsExportOptions& options) const = 0;
  /// The largest distance between two patches where they should meet (absolute), 0 for a
  /// single patch: the studio's X-C0-Gap.
  virtual double largestC0Gap() const = 0;
  /// The model's defining curves as polylines (ModelOverlay; the default: none).
  virtual ModelOverlay overlay() const { return {}; }
  /// The solver's notes (vertex frames: strips pinned, …); the default: none.
  virtual const std::vector<std::string>& notes() const;

  /// The method's own solved value, else nullptr (see SolvedSurfaceOf).
  template <class T>
  const T* as() const;
  /// The method's own solved value; throws std::bad_cast when it is another method's.
  template <class T>
  const T& get() const;
};

/// A SolvedSurface over a method's own solved value `T` (VertexFrameSurface,
/// SolvedSpectral, SolvedBSplinePde, …), reachable with as<T>().
template <class T>
class SolvedSurfaceOf : public SolvedSurface {
 public:
  explicit SolvedSurfaceOf(T value) : value_(std::move(value)) {}
  const T& value() const { return value_; }

 protected:
  T value_;
};

template <class T>
const T* SolvedSurface::as() const {
  const auto* typed = dynamic_cast<const SolvedSurfaceOf<T>*>(this);
  return typed ? &typed->value() : nullptr;
}

template <class T>
const T& SolvedSurface::get() const {
  return dynamic_cast<const SolvedSurfaceOf<T>&>(*this).value();
}

/// A parsed model with its solved surface, the name it goes by in messages (`source`, a
/// file path) and the options it was solved with.
class SolvedModel {
 public:
  SolvedModel(std::shared_ptr<const AnyModel> model, std::shared_ptr<const SolvedSurface> surface,
              std::string source, SolveOptions options);

  const AnyModel& model() const { return *model_; }
  /// The solved surface: patches, evaluation, tessellation, NURBS faces.
  const SolvedSurface& surface() const { return *surface_; }
  const std::string& source() const { return source_; }
  const SolveOptions& options() const { return options_; }
  /// The model's "type": "vertex-frames", "spectral", "cross-sections", "bspline-pde".
  const char* type() const { return modelTypeName(*model_); }
  /// The model's own name, else the file name of its source (modelDisplayName).
  std::string displayName() const;
  /// The solver's notes (vertex frames: strips pinned, …); empty for the other types.
  const std::vector<std::string>& notes() const { return surface_->notes(); }
  /// The solved spectral or cross-section model, else nullptr (the spine and fit commands).
  const SolvedSpectral* spectral() const { return surface_->as<SolvedSpectral>(); }
  /// The solved vertex-frame surface, else nullptr (the Coons baselines).
  const VertexFrameSurface* frames() const { return surface_->as<VertexFrameSurface>(); }

 private:
  std::shared_ptr<const AnyModel> model_;  // shared with a session's undo steps
  std::shared_ptr<const SolvedSurface> surface_;
  std::string source_;
  SolveOptions options_;
};

/// Solves a model of any method (its description's solve); the overloads on one method's
/// own model type (solve(SpectralModel), …) return that method's solved value instead. The
/// method reads its member of `options` (SolveOptions) and, for vertex frames, `topology`
/// when given (one built by buildTopology for this model's frames, shared by every solve of
/// a session); solver refusals become ModelError naming `source`. A model file:
/// `solve(loadModel(path), path)`.
SolvedModel solve(std::shared_ptr<const AnyModel> model, const std::string& source,
                  const SolveOptions& options = {},
                  std::shared_ptr<const FrameTopology> topology = nullptr);
SolvedModel solve(AnyModel model, const std::string& source, const SolveOptions& options = {});

/// Throws InvalidArgument when the member of `options` for the model's method does not fit
/// `model` (vertex frames: a seed frame the model does not have), with what is wrong: "out of
/// range, the model has 3 frames (indices 0 to 2)".
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

/// Every patch sampled: vertex frames and B-spline pieces on the unit square, spectral
/// patches over their u range and v ∈ [0, 2π].
std::vector<PatchSamples> sample(const SolvedModel& solved, const SampleOptions& options = {});

ModelReport report(const SolvedModel& solved);
/// The largest distance between two patches where they should meet (absolute), 0 for a
/// single patch: the studio's X-C0-Gap.
double largestC0Gap(const SolvedModel& solved);

/// The patches as NURBS faces (docs/nurbs-export.md).
NurbsModel toNurbs(const SolvedModel& solved, const NurbsExportOptions& options = {});

/// The model's defining curves as polylines (ModelOverlay).
ModelOverlay overlay(const SolvedModel& solved);

/// `name` when it is not empty, else the file name of `path`: how output names a model.
std::string modelDisplayName(const std::string& name, const std::string& path);

/// "1 frame", "2 frames", "1 vertex", "3 vertices", "2 patches": a count and its noun.
std::string countText(std::size_t n, const std::string& noun);

/// Whether the model has editable parts (SurfaceMethod::hasEditableParts: vertex frames).
bool hasEditableParts(const AnyModel& model);

}  // namespace pdesurf
