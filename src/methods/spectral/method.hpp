// The "spectral" and "cross-sections" methods (include/pdesurf/method.hpp), private to
// src/methods/: their one solved surface (SolvedSpectral: a patch or a chain) and the
// description both instantiate (spectral/method.cpp, cross_sections/method.cpp), each with its
// model's shape edits (spectral/edits.hpp, cross_sections/edits.hpp).
#pragma once

#include <algorithm>
#include <numbers>

#include "methods/builtin.hpp"
#include "methods/reports.hpp"
#include "methods/shape_edits/shape_edits.hpp"
#include "pdesurf/analysis.hpp"

namespace pdesurf::detail {

class SolvedSpectralSurface final : public SolvedSurfaceOf<SolvedSpectral> {
 public:
  using SolvedSurfaceOf::SolvedSurfaceOf;

  std::size_t patchCount() const override { return value_.patchCount(); }
  /// The patch's shown u range and v ∈ [0, 2π].
  PatchDomain domain(std::size_t patch) const override {
    const auto [u0, u1] = value_.range(patch);
    return {u0, u1, 0.0, 2.0 * std::numbers::pi};
  }
  SurfacePoint evaluate(std::size_t patch, double u, double v) const override {
    return value_.patchAt(patch).evaluate(u, v);
  }
  Mesh tessellate(const TessellateOptions& options) const override {
    return pdesurf::tessellate(value_, options);
  }
  std::vector<PatchSamples> sample(const SampleOptions& options) const override {
    const std::uint32_t n = options.grid;
    std::vector<PatchSamples> out;
    for (std::size_t k = 0; k < value_.patchCount(); ++k) {
      const auto [u0, u1] = value_.range(k);
      out.push_back({k, n, std::pair{u0, u1}, std::nullopt,
                     sampleGrid(n, [&](std::uint32_t i, std::uint32_t j) {
                       // As the CLI always sampled (same rounding).
                       return value_.patchAt(k).position(
                           u0 + (u1 - u0) * static_cast<double>(i) / (n - 1),
                           2.0 * std::numbers::pi * static_cast<double>(j) / (n - 1));
                     })});
    }
    return out;
  }
  NurbsModel toNurbs(const NurbsExportOptions& options) const override {
    return pdesurf::toNurbs(value_, options);
  }
  double largestC0Gap() const override {
    double gap = 0.0;
    if (value_.chain)
      for (const JointGap& g : measureJointGaps(*value_.chain)) gap = std::max(gap, g.c0);
    return gap;
  }
  ModelOverlay overlay() const override {
    constexpr std::uint32_t kViewCurveSamples = 96, kViewSpineSamples = 65;
    // A condition at u within this of a patch's range belongs to it (its ends are computed).
    constexpr double kRangeSlack = 1e-12;
    ModelOverlay out;
    const SolvedSpectral& s = value_;
    // Each patch's position curves (closed, sampled at kViewCurveSamples v) and spine.
    for (std::size_t k = 0; k < s.patchCount(); ++k) {
      const SpectralPatch& p = s.patchAt(k);
      const auto [u0, u1] = s.range(k);
      for (const auto& c : p.conditions()) {
        if (c.derivative != 0 || c.u < std::min(u0, u1) - kRangeSlack ||
            c.u > std::max(u0, u1) + kRangeSlack)
          continue;
        std::vector<Vec3> line;
        for (std::uint32_t j = 0; j < kViewCurveSamples; ++j)
          line.push_back(p.position(c.u, 2.0 * std::numbers::pi * j / kViewCurveSamples));
        out.curves.push_back(std::move(line));
      }
      std::vector<Vec3> spine;
      for (std::uint32_t i = 0; i < kViewSpineSamples; ++i)
        spine.push_back(p.spine(u0 + (u1 - u0) * i / (kViewSpineSamples - 1.0)));
      out.spines.push_back(std::move(spine));
    }
    return out;
  }
};

/// "spectral" (SpectralModel) and "cross-sections" (CrossSectionModel): the same solved
/// surface and reports.
template <class Model>
class SpectralMethod final
    : public ShapeEditedMethod<OptionlessMethod<Model, SolvedSpectral, SolvedSpectralSurface>> {
 public:
  using Base = ShapeEditedMethod<OptionlessMethod<Model, SolvedSpectral, SolvedSpectralSurface>>;
  SpectralMethod(const ShapeEditsOf<Model>& edits, const char* type, typename Base::Parse parseFile)
      : Base(edits, type, parseFile, pdesurf::solve) {}

  ModelReport report(const SolvedModel& solved) const override {
    return spectralReport(solved.surface().get<SolvedSpectral>());
  }
  ModelInfo info(const SolvedModel& solved) const override {
    return spectralInfo(solved.surface().get<SolvedSpectral>());
  }
};

}  // namespace pdesurf::detail
