// The shape edits (ShapeEdit, session.hpp) of the spectral, cross-section and B-spline PDE
// methods, private to src/methods/. What every such method shares is here and in this folder
// (the curve edits, their falloff, parsing, the reach check); what is one method's own (the
// curves it names, its own edits, its handles) is in that method's folder, in its table
// ShapeEditsOf<Model>, which ShapeEditedMethod calls.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/json_reader.hpp"
#include "io/model_reader.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::detail {

/// A curve of a model, to change: a spectral curve (points or Fourier) or a list of points,
/// with what its points are (positions, or vectors: a derivative condition, a tangent) and
/// its JSON path in the model file.
struct CurveTarget {
  CurveInput* input = nullptr;
  std::vector<Vec3>* points = nullptr;
  bool vectors = false;
  std::string path;
};

/// The ops of the curve edits every shape-edited method takes (parse.cpp parses them).
inline constexpr std::array<const char*, 3> kCurveOps = {"move-curve-points", "transform-curve",
                                                         "set-fourier"};

/// A shape-edited method's own part, on its models (ShapeEditedMethod implements it with its
/// ShapeEditsOf<Model>): the shared code reaches a method's own part through this alone.
class ShapeEditor {
 public:
  /// The curve `ref` names in `model` (a copy an edit changes); throws ModelError (source
  /// "edit", at `path`) when the model has no such curve.
  virtual CurveTarget curve(AnyModel& model, const CurveRef& ref,
                            const std::string& path) const = 0;
  /// The ops of its own edits (besides move-curve-points, transform-curve, set-fourier).
  virtual std::span<const char* const> ownOps() const = 0;
  /// Parses one of ownOps() (`doc` is the edit's JSON, `op` its "op").
  virtual ShapeEdit parseOwnEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                                 const AnyModel& model) const = 0;
  /// Applies one of its own edits to `next` (`solved`: the model before it, solved).
  virtual void applyOwnEdit(AnyModel& next, const SolvedModel& solved,
                            const ShapeEdit& edit) const = 0;
  /// After a curve edit of `before` made `after`: what else moves with the curve (B-spline
  /// PDE: the corners other curves share).
  virtual void afterCurveEdit(const AnyModel& before, AnyModel& after) const = 0;
  /// The points of every curve and net that hold positions, in a fixed order (two models of
  /// one structure list corresponding points): what checkReach measures a drag by.
  virtual std::vector<Vec3> reachPoints(const AnyModel& model) const = 0;
  /// dragAdvice (session.hpp) for its models.
  virtual std::string dragAdvice(const AnyModel& model) const = 0;

 protected:
  ~ShapeEditor() = default;
};

/// The shape editor of `model`'s method, or nullptr (a method without shape edits). The one
/// place the shared code asks which kind of method it has: an interface, not a type.
inline const ShapeEditor* shapeEditor(const AnyModel& model) {
  return dynamic_cast<const ShapeEditor*>(&model.method());
}

/// The curve `ref` names in `model` (a copy the edit changes), by its method; throws
/// ModelError (source "edit", at `path`) when the model has no such curve.
CurveTarget curveTarget(AnyModel& model, const CurveRef& ref, const std::string& path);

/// Parses a shape edit of `model` (its method's `editor`); the common curve edits here, the
/// method's own by `editor`.
GroupedShapeEdit parseShapeEdit(const ShapeEditor& editor, std::string_view json,
                                const AnyModel& model);

/// Applies a shape edit (a ShapeEdit in `edit`) to the session's model (a drag's absolute
/// steps to the model as the group began): the result checked as its file would be, solved
/// and checked by checkReach. Throws ModelError (source "edit") naming what is wrong.
EditResult applyShapeEdit(const ShapeEditor& editor, const EditContext& context,
                          const ModelEdit& edit);

// Helpers the methods' own parsers and handles share.

/// Fails unless `doc` has only the listed members besides "op" and "group".
void onlyMembers(const ModelReader& rd, const Json& doc, std::initializer_list<const char*> keys);
/// "positions": one point per listed item.
std::vector<Vec3> positionsField(const ModelReader& rd, const Json& doc, std::size_t count);
/// The mean of `points` (summed in order, then divided: as the page summed them).
Vec3 meanOf(const std::vector<Vec3>& points);
/// Adds curve `ref` to the panel's curves (`vectors`: it holds vectors) and its points as
/// handles (`points`: its points when they are positions, else null); its centre is the mean
/// of its points, else `a0` (a Fourier curve's, or zero).
void addCurve(ModelHandles& out, const CurveRef& ref, std::string label,
              const std::vector<Vec3>* points, const Vec3& a0, bool vectors);
/// Adds the tips of vectors `at` drawn from `base` (one each) as handles of curve `ref`.
void addTangents(ModelHandles& out, const CurveRef& ref, const std::vector<Vec3>& at,
                 const std::vector<Vec3>& base, bool mean);

/// The settings of a method whose overlay shows its curves and spine (spectral, cross
/// sections): its operator at the model's values; `edits` is ShapeEditedMethod's.
inline ModelSettings curvesAndSpineSettings(const ModelSettings::Operator& op) {
  return {{}, op, "Curves and spine"};
}

/// What a shape-edited method's model type `Model` does itself, as ShapeEditor's members on
/// `Model` (ShapeEditedMethod calls them), its handles and its settings: one table a method,
/// made in the method's folder (spectral/edits.cpp, cross_sections/edits.cpp,
/// bspline_pde/edits.cpp).
template <class Model>
struct ShapeEditsOf {
  std::span<const char* const> ops;
  CurveTarget (*curve)(Model& m, const CurveRef& ref, const std::string& path);
  ShapeEdit (*parseOwnEdit)(std::string_view op, const ModelReader& rd, const Json& doc,
                            const Model& m);
  void (*applyOwnEdit)(Model& m, const SolvedModel& solved, const ShapeEdit& edit);
  /// Null: nothing moves with an edited curve but its points.
  void (*afterCurveEdit)(const Model& before, Model& after) = nullptr;
  std::vector<Vec3> (*reachPoints)(const Model& m);
  /// Null: no advice.
  std::string (*dragAdvice)(const Model& m) = nullptr;
  ModelHandles (*handles)(const Model& m, const SolvedModel& solved);
  /// Its operator's values and its overlay's caption (ModelSettings; `edits` is filled by
  /// ShapeEditedMethod).
  ModelSettings (*settings)(const Model& m);
};

/// A method whose edits are shape edits (ShapeEdit, session.hpp: its curves, nets, spines
/// and operators): spectral, cross-sections, B-spline PDE. `Base` is an OptionlessMethod;
/// `own` is the method's table.
template <class Base>
class ShapeEditedMethod : public Base, public ShapeEditor {
 public:
  using Model = typename Base::ModelType;
  ShapeEditedMethod(const ShapeEditsOf<Model>& own, const char* type,
                    typename Base::Parse parseFile, typename Base::Solve solveFile)
      : Base(type, parseFile, solveFile), own_(own) {}

  ModelEdit parseEdit(std::string_view json, const AnyModel& model) const override {
    GroupedShapeEdit e = parseShapeEdit(*this, json, model);
    return {std::move(e.edit), std::move(e.group)};
  }
  EditResult applyEdit(const EditContext& context, const ModelEdit& edit) const override {
    return applyShapeEdit(*this, context, edit);
  }
  ModelHandles handles(const SolvedModel& solved) const override {
    return own_.handles(solved.model().template get<Model>(), solved);
  }
  /// The method's own settings, its edits the curve edits and then its own.
  ModelSettings settings(const AnyModel& model) const override {
    ModelSettings out = own_.settings(model.template get<Model>());
    out.edits.assign(kCurveOps.begin(), kCurveOps.end());
    out.edits.insert(out.edits.end(), own_.ops.begin(), own_.ops.end());
    return out;
  }

  CurveTarget curve(AnyModel& model, const CurveRef& ref, const std::string& path) const override {
    return own_.curve(model.template get<Model>(), ref, path);
  }
  std::span<const char* const> ownOps() const override { return own_.ops; }
  ShapeEdit parseOwnEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                         const AnyModel& model) const override {
    return own_.parseOwnEdit(op, rd, doc, model.template get<Model>());
  }
  void applyOwnEdit(AnyModel& next, const SolvedModel& solved,
                    const ShapeEdit& edit) const override {
    own_.applyOwnEdit(next.template get<Model>(), solved, edit);
  }
  void afterCurveEdit(const AnyModel& before, AnyModel& after) const override {
    if (own_.afterCurveEdit)
      own_.afterCurveEdit(before.template get<Model>(), after.template get<Model>());
  }
  std::vector<Vec3> reachPoints(const AnyModel& model) const override {
    return own_.reachPoints(model.template get<Model>());
  }
  std::string dragAdvice(const AnyModel& model) const override {
    return own_.dragAdvice ? own_.dragAdvice(model.template get<Model>()) : std::string();
  }

 private:
  const ShapeEditsOf<Model>& own_;
};

}  // namespace pdesurf::detail
