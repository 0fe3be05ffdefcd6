// The built-in surface methods (include/pdesurf/method.hpp), private to src/methods/: each
// method's description is defined in its own folder beside its solved surface and its edits.
#pragma once

#include <cstdint>
#include <typeindex>
#include <vector>

#include "pdesurf/edit_io.hpp"
#include "pdesurf/method.hpp"

namespace pdesurf::detail {

const SurfaceMethod& vertexFramesMethod();   // vertex_frames/method.cpp
const SurfaceMethod& spectralMethod();       // spectral/method.cpp
const SurfaceMethod& crossSectionsMethod();  // cross_sections/method.cpp
const SurfaceMethod& bsplinePdeMethod();     // bspline_pde/method.cpp

/// What every method over a model struct `Model` with a `name` and a transformModel
/// overload shares: its C++ type, its name, its transform.
template <class Model>
class MethodOf : public SurfaceMethod {
 public:
  using ModelType = Model;
  std::type_index modelType() const override { return typeid(Model); }
  const std::string& name(const AnyModel& model) const override { return model.get<Model>().name; }
  AnyModel transform(const AnyModel& model, const AffineMap& map) const override {
    return transformModel(model.get<Model>(), map);
  }
};

/// A method whose model has its own document parser, writer (serializeModel) and solver
/// that takes no options: spectral, cross-sections, B-spline PDE. `Surface` is the
/// SolvedSurfaceOf<Solved> the solve returns.
template <class Model, class Solved, class Surface>
class OptionlessMethod : public MethodOf<Model> {
 public:
  using Parse = Model (*)(const nlohmann::json&, const std::string&);
  using Solve = Solved (*)(const Model&, const std::string&);
  OptionlessMethod(const char* type, Parse parseFile, Solve solveFile)
      : type_(type), parse_(parseFile), solve_(solveFile) {}

  const char* typeName() const override { return type_; }
  AnyModel parse(const nlohmann::json& document, const std::string& source) const override {
    return parse_(document, source);
  }
  std::string serialize(const AnyModel& model) const override {
    return serializeModel(model.template get<Model>());
  }
  std::shared_ptr<const SolvedSurface> solve(
      const AnyModel& model, const std::string& source, const SolveOptions&,
      const std::shared_ptr<const FrameTopology>&) const override {
    return std::make_shared<const Surface>(solve_(model.template get<Model>(), source));
  }

 private:
  const char* type_;
  Parse parse_;
  Solve solve_;
};

/// points[j*n+i] = f(i, j): a patch's samples.
template <class F>
std::vector<Vec3> sampleGrid(std::uint32_t n, F&& f) {
  std::vector<Vec3> points;
  points.reserve(std::size_t{n} * n);
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) points.push_back(f(i, j));
  return points;
}

/// A solved surface whose patches are the list `T::*Patches` (vertex-frame patches, B-spline
/// pieces), each on the unit square with evaluate() and position(), tessellated by the
/// engine's tessellate(const T&, const TessellateOptions&).
template <class T, auto Patches>
class UnitSquarePatches : public SolvedSurfaceOf<T> {
 public:
  using SolvedSurfaceOf<T>::SolvedSurfaceOf;

  std::size_t patchCount() const override { return patches().size(); }
  PatchDomain domain(std::size_t) const override { return {}; }
  SurfacePoint evaluate(std::size_t patch, double u, double v) const override {
    return patches()[patch].evaluate(u, v);
  }
  /// The engine's own mesh of the solved value (pdesurf::tessellate of a `T`).
  Mesh tessellate(const TessellateOptions& options) const override {
    return pdesurf::tessellate(this->value_, options);
  }
  /// Each patch on a grid × grid lattice of its unit square.
  std::vector<PatchSamples> sample(const SampleOptions& options) const override {
    std::vector<PatchSamples> out;
    for (std::size_t k = 0; k < patches().size(); ++k) out.push_back(unitSamples(k, options.grid));
    return out;
  }

 protected:
  const auto& patches() const { return this->value_.*Patches; }
  /// Patch k at (i/(n−1), j/(n−1)).
  PatchSamples unitSamples(std::size_t k, std::uint32_t n) const {
    const auto unit = [n](std::uint32_t i) { return static_cast<double>(i) / (n - 1); };
    return {k, n, std::nullopt, std::nullopt, sampleGrid(n, [&](std::uint32_t i, std::uint32_t j) {
              return patches()[k].position(unit(i), unit(j));
            })};
  }
};

}  // namespace pdesurf::detail
