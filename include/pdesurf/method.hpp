// Surface methods: one description per method (vertex frames, spectral, cross-sections,
// B-spline PDE, or one a program registers) that holds everything pdesurf does with a model
// of that method: its type name, parse, serialise, solve, transform, report, info, edits.
// The registry finds a description by the "type" of a model file or by the C++ type of a model
// value.
// docs/architecture.md says where the descriptions live and how a method is added.
#pragma once

#include <any>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "pdesurf/model.hpp"
#include "pdesurf/spectral.hpp"  // OperatorKind, ChainMethod
#include "pdesurf/transform.hpp"

namespace pdesurf {

struct ModelInfo;  // model_info.hpp

/// A model as an editing session (session.hpp: ModelSession) holds it: the model, its
/// solution (null while it is not solved) and, for vertex frames, the frame topology its
/// solves share.
struct ModelState {
  std::shared_ptr<const AnyModel> model;
  std::shared_ptr<const SolvedModel> solved;
  std::shared_ptr<const FrameTopology> topology;
};

/// An edit of a model as its method parsed it (SurfaceMethod::parseEdit): the method's own
/// edit value, type-erased (vertex frames: Edit; spectral, cross-sections and B-spline PDE:
/// ShapeEdit, both in session.hpp; a registered method: a type of its own), with its undo
/// group: consecutive edits of one non-empty group (the steps of one drag) undo as one.
struct ModelEdit {
  std::any edit;
  std::string group;

  /// The edit's value as the method `type` takes it (its applyEdit); throws std::logic_error
  /// when it is of another type (another method's edit).
  template <class E>
  const E& as(std::string_view type) const {
    if (const E* e = std::any_cast<E>(&edit)) return *e;
    // Not a pdesurf::Error: the caller's slip (an edit parsed against another model), not input.
    throw std::logic_error(std::string("an edit of another method given to a ") +
                           std::string(type) + " model");
  }
};

/// What SurfaceMethod::applyEdit applies an edit to.
struct EditContext {
  /// The session's current state.
  const ModelState& current;
  /// The state before the first edit of the edit's group, while that group is open (null
  /// outside a group and at its first edit): a drag's absolute steps apply to it.
  const ModelState* groupStart = nullptr;
  /// `current` solved (solved on the first call when it is not yet).
  std::function<const SolvedModel&()> solved;
  /// The name solver refusals give (ModelError's source).
  const std::string& source;
};

/// What an edit makes (SurfaceMethod::applyEdit).
struct EditResult {
  /// The next state: its model; its solution when the method solved it (to check it; else
  /// the session solves it as every model without editable parts is solved); its topology
  /// when the edit changed the model's structure (null: the current one is kept).
  ModelState next;
  /// The edit is an undo step of its own whatever its group (a structure edit, a
  /// whole-model transform).
  bool ownStep = false;
};

/// A curve of a model: a spectral model's condition (`index`), a cross-section (`index`),
/// or a B-spline PDE model's curve by its file name (`name`: "uMin", "uMax", "vMin", "vMax",
/// "uMinSecond", "vMinSecond" of the boundary form; "uMin".."vMax" of the blend, "start",
/// "end" of the closed blend).
struct CurveRef {
  std::uint32_t index = 0;
  std::string name;  ///< B-spline PDE models only
};

/// A shape edit's tangent (a derivative condition's or a tangent row's vector) is drawn from
/// its base point on the position curve to its tip handle at base + kTangentDraw × vector: a
/// tangent is a derivative (a length per unit of u), often longer than the model; a quarter
/// keeps its tip near the surface and its direction plain.
constexpr double kTangentDraw = 0.25;

/// A point of a model that a user drags to edit it (SurfaceMethod::handles): what it is,
/// what it names in the model (the edit its drag makes) and where it is drawn.
struct ModelHandle {
  enum class Kind {
    CurvePoint,    ///< point `index` of `curve` (a curve given as points)
    Tangent,       ///< the tip of vector `index` of `curve` (`mean`: a Fourier curve's a0)
    ControlPoint,  ///< the given control point (`index`, `column`) = (i, j) of a net
    SpinePoint,    ///< spine point `index`, at `u`
  };
  Kind kind = Kind::CurvePoint;
  CurveRef curve;
  std::uint32_t index = 0;
  std::uint32_t column = 0;
  Vec3 position = Vec3::Zero();
  /// Tangent: the point its vector is drawn from (position = base + kTangentDraw × vector).
  Vec3 base = Vec3::Zero();
  bool mean = false;
  double u = 0.0;
};

/// A curve a model's shape edits move whole (SurfaceMethod::handles): the curve, its label,
/// the centre turns and scales pivot on (the mean of its points, or a Fourier curve's a0),
/// and whether it holds vectors (a derivative condition, a tangent row: no translation; turns
/// and scales through the map's linear part).
struct HandleCurve {
  CurveRef ref;
  std::string label;
  Vec3 centre = Vec3::Zero();
  bool vectors = false;
};

/// What a model offers to drag: its handles and its curves, in the order the method lists
/// them.
struct ModelHandles {
  std::vector<ModelHandle> points;
  std::vector<HandleCurve> curves;
};

/// What a model offers to set whole (SurfaceMethod::settings): the edits its method takes,
/// its operator's values and what the studio's frame view draws of it. The studio's panels
/// show these, so its page reads no model file.
struct ModelSettings {
  /// The ops of the edits parseEdit takes of the model (apps/studio/README.md), in the order
  /// the method lists them.
  std::vector<std::string> edits;
  /// The operator as set-operator's fields (session.hpp: SetOperator) at the model's values:
  /// the fields the model takes, each set.
  struct Operator {
    std::optional<OperatorKind> kind;    ///< Ugail's or Fu's (spectral)
    std::optional<std::uint32_t> power;  ///< N, the operator's order over 2 (spectral)
    double a = 0.0;
    std::uint32_t modes = 0;
    bool remainder = true;
    std::optional<ChainMethod> method;  ///< how a chain is solved (cross-sections)
  };
  /// None when the model takes no set-operator.
  std::optional<Operator> op;
  /// What its overlay (ModelOverlay) shows, as a caption names it ("Curves and spine");
  /// empty when it has none.
  std::string overlay;
};

/// One surface method. The built-in ones are in src/methods/; a program adds its own with
/// registerMethod (tests/model/toy_method_test.cpp adds a bilinear Coons method).
class SurfaceMethod {
 public:
  virtual ~SurfaceMethod() = default;

  /// The "type" of its model files ("vertex-frames").
  virtual const char* typeName() const = 0;
  /// The C++ type of its model values (what AnyModel holds).
  virtual std::type_index modelType() const = 0;
  /// What its model files call a patch: "frame" for vertex frames; the default "patch".
  virtual const char* patchName() const { return "patch"; }

  /// Parses and validates a model document whose "type" is typeName(); errors are ModelError
  /// naming `source` and the JSON path.
  virtual AnyModel parse(const nlohmann::json& document, const std::string& source) const = 0;
  /// The model as JSON text that parse reads back to the same model.
  virtual std::string serialize(const AnyModel& model) const = 0;
  /// The "name" the model gives (empty when none).
  virtual const std::string& name(const AnyModel& model) const = 0;

  /// Solves the model; refusals are ModelError naming `source`. The method reads its own
  /// member of `options` (SolveOptions: vertexFrames) and ignores the others; `topology` (a
  /// FrameTopology of this model's frames, or null) is the vertex-frame solver's.
  virtual std::shared_ptr<const SolvedSurface> solve(
      const AnyModel& model, const std::string& source, const SolveOptions& options,
      const std::shared_ptr<const FrameTopology>& topology) const = 0;
  /// Throws InvalidArgument when the method's member of `options` does not fit the model
  /// (the default: it fits).
  virtual void checkSolveOptions(const AnyModel& model, const SolveOptions& options) const;

  /// The model moved, turned or scaled whole (transform.hpp: what re-solving gives).
  virtual AnyModel transform(const AnyModel& model, const AffineMap& map) const = 0;
  /// Throws ModelError when the transformed model would not solve (the default: it does).
  virtual void checkTransform(const AnyModel& model, const AffineMap& map) const;

  /// What `build` reports. The default: the patch count and the largest C0 gap.
  virtual ModelReport report(const SolvedModel& solved) const;
  /// What `info` tells (model_info.hpp: ModelInfo): the method's facts, each a value with
  /// its label and JSON key, in the order a listing shows them; modelInfo adds the source and
  /// the name. The default: the type, the patch count, the largest C0 gap and the bounding
  /// box of a sample.
  virtual ModelInfo info(const SolvedModel& solved) const;

  /// Parses and validates an edit of `model` from its JSON ({"op": ..., "group": ...}, the
  /// fields of the op: docs/studio.md). Errors are ModelError with source "edit" and the
  /// JSON path. The default: the method takes no edits (a ModelError at "$.op").
  virtual ModelEdit parseEdit(std::string_view json, const AnyModel& model) const;
  /// Applies an edit parseEdit made (or a value of the method's edit type): the session's
  /// one path for every edit. Throws ModelError naming what is wrong, the session then left
  /// as it was. The default: throws std::logic_error (the method takes no edits).
  virtual EditResult applyEdit(const EditContext& context, const ModelEdit& edit) const;
  /// The structure a session keeps while edits leave it (vertex frames: the FrameTopology
  /// their solves share), or null (the default).
  virtual std::shared_ptr<const FrameTopology> topology(const AnyModel& model) const;

  /// Whether the model has editable parts (vertex frames: vertices, frames, forces), which
  /// the studio's frame tools edit and parseEdit checks fully: a session then solves the
  /// model only when asked and keeps no solution for undo. Without them (the default) every
  /// model a session makes is solved at once, its solver's refusal refusing the edit.
  virtual bool hasEditableParts() const { return false; }

  /// The handles and curves of the model's shape edits (spectral: its curves' points,
  /// tangent tips and spine points; B-spline PDE: its curves' points, tangent tips and a net's
  /// given control points), placed on `solved` where they are not the model's own points (a
  /// spine). The default: none (vertex frames: their handles are the model's vertices, which
  /// the studio's frame tools edit).
  virtual ModelHandles handles(const SolvedModel& solved) const;
  /// What the model offers to set whole (ModelSettings). The default: nothing.
  virtual ModelSettings settings(const AnyModel& model) const;
};

/// Adds a method to the registry, after the built-in ones. Throws InvalidArgument when
/// its type name or model type is already registered. `method` must outlive its use.
void registerMethod(const SurfaceMethod& method);
/// The method whose model files have this "type", else nullptr.
const SurfaceMethod* findMethod(std::string_view typeName);
/// Every method: the built-in ones in their order (vertex-frames, spectral, cross-sections,
/// bspline-pde), then the registered ones in the order they were added.
std::vector<const SurfaceMethod*> surfaceMethods();

}  // namespace pdesurf
