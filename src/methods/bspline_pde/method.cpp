// The "bspline-pde" method (include/pdesurf/method.hpp): its description and its solved
// surface (SolvedBSplinePde: a surface or a blend of pieces), with its shape edits
// (bspline_pde/edits.hpp).
#include <span>

#include "io/model_reader.hpp"
#include "methods/bspline_pde/edits.hpp"
#include "methods/builtin.hpp"
#include "methods/reports.hpp"
#include "methods/shape_edits/shape_edits.hpp"
#include "pdesurf/bspline_pde_io.hpp"

namespace pdesurf::detail {

namespace {

class SolvedBSplineSurface final
    : public UnitSquarePatches<SolvedBSplinePde, &SolvedBSplinePde::pieces> {
 public:
  using UnitSquarePatches::UnitSquarePatches;

  std::vector<PatchSamples> sample(const SampleOptions& options) const override {
    std::vector<PatchSamples> out = UnitSquarePatches::sample(options);
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k].origin = value_.origin[k];  // the piece's origin in the blend
    return out;
  }
  NurbsModel toNurbs(const NurbsExportOptions& options) const override {
    return pdesurf::toNurbs(std::span<const BSplineSurface>(value_.pieces), options);
  }
  /// Reported as 0, as it always was for this method (no gap measure between pieces yet).
  double largestC0Gap() const override { return 0.0; }
  ModelOverlay overlay() const override {
    ModelOverlay out;
    // The control polygon of each piece: its rows and its columns.
    for (const BSplineSurface& piece : value_.pieces) {
      const ControlNet& net = piece.net();
      for (int direction = 0; direction < 2; ++direction) {
        const std::uint32_t lines = direction == 0 ? net.nu : net.nv;
        const std::uint32_t along = direction == 0 ? net.nv : net.nu;
        for (std::uint32_t a = 0; a <= lines; ++a) {
          std::vector<Vec3> line;
          for (std::uint32_t k = 0; k <= along; ++k)
            line.push_back(direction == 0 ? net(a, k) : net(k, a));
          out.curves.push_back(std::move(line));
        }
      }
    }
    return out;
  }
};

class BSplinePdeMethod final
    : public ShapeEditedMethod<
          OptionlessMethod<BSplinePdeModel, SolvedBSplinePde, SolvedBSplineSurface>> {
 public:
  BSplinePdeMethod()
      : ShapeEditedMethod(kBSplinePdeEdits, "bspline-pde", parseBSplinePdeDocument,
                          pdesurf::solve) {}

  ModelReport report(const SolvedModel& solved) const override {
    return bsplineReport(solved.surface().get<SolvedBSplinePde>());
  }
  ModelInfo info(const SolvedModel& solved) const override {
    return bsplineInfo(solved.model().get<BSplinePdeModel>(),
                       solved.surface().get<SolvedBSplinePde>());
  }
};

}  // namespace

const SurfaceMethod& bsplinePdeMethod() {
  static const BSplinePdeMethod method;
  return method;
}

}  // namespace pdesurf::detail
