// The built-in surface methods (include/pdesurf/method.hpp), private to src/methods/: each
// method's description is defined in its own file beside its solved surface.
#pragma once

#include <cstdint>
#include <typeindex>
#include <vector>

#include "pdesurf/method.hpp"

namespace pdesurf::detail {

const SurfaceMethod& vertexFramesMethod();   // vertex_frames.cpp
const SurfaceMethod& spectralMethod();       // spectral.cpp
const SurfaceMethod& crossSectionsMethod();  // spectral.cpp
const SurfaceMethod& bsplinePdeMethod();     // bspline_pde.cpp

/// What every method over a model struct `Model` with a `name` and a transformModel
/// overload shares: its C++ type, its name, its transform.
template <class Model>
class MethodOf : public SurfaceMethod {
 public:
  std::type_index modelType() const override { return typeid(Model); }
  const std::string& name(const AnyModel& model) const override { return model.get<Model>().name; }
  AnyModel transform(const AnyModel& model, const AffineMap& map) const override {
    return transformModel(model.get<Model>(), map);
  }
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
/// pieces), each on the unit square with evaluate() and position().
template <class T, auto Patches>
class UnitSquarePatches : public SolvedSurfaceOf<T> {
 public:
  using SolvedSurfaceOf<T>::SolvedSurfaceOf;

  std::size_t patchCount() const override { return patches().size(); }
  PatchDomain domain(std::size_t) const override { return {}; }
  SurfacePoint evaluate(std::size_t patch, double u, double v) const override {
    return patches()[patch].evaluate(u, v);
  }

 protected:
  const auto& patches() const { return this->value_.*Patches; }
  /// Patch k at (i/(n−1), j/(n−1)), under the JSON key `label`.
  PatchSamples unitSamples(std::size_t k, std::uint32_t n, const char* label) const {
    const auto unit = [n](std::uint32_t i) { return static_cast<double>(i) / (n - 1); };
    return {label,
            k,
            n,
            std::nullopt,
            std::nullopt,
            sampleGrid(n, [&](std::uint32_t i, std::uint32_t j) {
              return patches()[k].position(unit(i), unit(j));
            })};
  }
};

}  // namespace pdesurf::detail
