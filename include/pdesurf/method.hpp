// Surface methods: one description per method (vertex frames, spectral, cross-sections,
// B-spline PDE, or one a program registers) that holds everything pdesurf does with a model
// of that method: its type name, parse, serialise, solve, transform, report. The registry
// finds a description by the "type" of a model file or by the C++ type of a model value.
// docs/architecture.md says where the descriptions live and how a method is added.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "pdesurf/model.hpp"
#include "pdesurf/transform.hpp"

namespace pdesurf {

/// One surface method. The built-in ones are in src/methods/; a program adds its own with
/// registerMethod (tests/model/toy_method_test.cpp adds a bilinear Coons method).
class SurfaceMethod {
 public:
  virtual ~SurfaceMethod() = default;

  /// The "type" of its model files ("vertex-frames").
  virtual const char* typeName() const = 0;
  /// The C++ type of its model values (what AnyModel holds).
  virtual std::type_index modelType() const = 0;

  /// Parses and validates a model document whose "type" is typeName(); errors are ModelError
  /// naming `source` and the JSON path.
  virtual AnyModel parse(const nlohmann::json& document, const std::string& source) const = 0;
  /// The model as JSON text that parse reads back to the same model.
  virtual std::string serialize(const AnyModel& model) const = 0;
  /// The "name" the model gives (empty when none).
  virtual const std::string& name(const AnyModel& model) const = 0;

  /// Solves the model; refusals are ModelError naming `source`. `options` and `topology`
  /// (a FrameTopology of this model's frames, or null) are the vertex-frame solver's: the
  /// other methods take no options.
  virtual std::shared_ptr<const SolvedSurface> solve(
      const AnyModel& model, const std::string& source, const SolveOptions& options,
      const std::shared_ptr<const FrameTopology>& topology) const = 0;
  /// Throws InvalidArgument when `options` do not fit the model (the default: they fit).
  virtual void checkSolveOptions(const AnyModel& model, const SolveOptions& options) const;

  /// The model moved, turned or scaled whole (transform.hpp: what re-solving gives).
  virtual AnyModel transform(const AnyModel& model, const AffineMap& map) const = 0;
  /// Throws ModelError when the transformed model would not solve (the default: it does).
  virtual void checkTransform(const AnyModel& model, const AffineMap& map) const;

  /// What `build` reports. The default: the patch count and the largest C0 gap.
  virtual ModelReport report(const SolvedModel& solved) const;
  /// `info`, as text or as JSON. The default: the model, its name, patch count, C0 gap and
  /// the bounding box of a sample.
  virtual std::string info(const SolvedModel& solved, bool json) const;

  /// Whether a session edits the model's parts (vertex frames) rather than its shape
  /// (shape edits) or only whole (transforms). The default: no.
  virtual bool editsParts() const { return false; }
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
