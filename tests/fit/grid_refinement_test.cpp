// More frames never fit worse: the automatic grid layout of a disk-like mesh, refined, fitted
// and measured as `pdesurf compare` measures (both ways, relative to the diagonal), on a
// closed-form height field and on CGAL's real meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/rebuild.hpp"
#include "support/cgal_data.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

/// "Never worse": a finer grid's RMS may exceed a coarser one's by this fraction only (the
/// sampling noise of the distance measure, as for the tube layouts), never more.
constexpr double kNeverWorseSlack = 0.02;
/// The finest grid of each sweep is clearly better than the coarsest: at most this fraction
/// of its RMS (the sweeps below gain 4x to 10x; a fit that stopped improving with more frames
/// would fail).
constexpr double kRefinementGain = 0.5;
/// Samples per patch side when a fitted model is measured (as `compare` and the accuracy
/// benchmark do).
constexpr std::uint32_t kPatchResolution = 17;

/// RMS of the two one-way RMS distances (relative to the diagonal) between the model's mesh
/// and the target: the accuracy benchmark's measure.
double fittedRms(const VertexFrameModel& layout, const Mesh& target) {
  const FitResult fit = fitVertexFrames(layout, target);
  const MeshDistance d = meshDistance(tessellate(solve(fit.model), {kPatchResolution}), target);
  return std::sqrt(
      0.5 * (d.aToB.rmsRelative * d.aToB.rmsRelative + d.bToA.rmsRelative * d.bToA.rmsRelative));
}

/// The RMS of each grid in `sizes`, checked never to rise and to fall overall.
void expectRefinementNeverWorse(const Mesh& target, const std::string& name,
                                const std::vector<std::uint32_t>& sizes) {
  std::vector<double> rms;
  for (const std::uint32_t n : sizes) {
    SCOPED_TRACE(::testing::Message() << name << " " << n << " x " << n);
    rms.push_back(fittedRms(gridLayout(target, {n, n}, name), target));
    if (rms.size() > 1) EXPECT_LE(rms.back(), rms[rms.size() - 2] * (1 + kNeverWorseSlack));
  }
  EXPECT_LT(rms.back(), kRefinementGain * rms.front()) << name;
}

/// A smooth height field over the unit square: two bumps and a saddle, sampled on a fine
/// triangulated grid (one boundary loop).
Mesh heightField(int n) {
  testing::MeshBuilder b;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      const double z = 0.25 * std::exp(-20 * ((x - 0.3) * (x - 0.3) + (y - 0.4) * (y - 0.4))) +
                       0.15 * std::exp(-30 * ((x - 0.7) * (x - 0.7) + (y - 0.7) * (y - 0.7))) +
                       0.05 * (x - 0.5) * (y - 0.5);
      b.vertex(x, y, z);
    }
  auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) b.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return b.mesh();
}

TEST(GridRefinement, AHeightFieldFitsNeverWorseWithMoreFrames) {
  expectRefinementNeverWorse(heightField(96), "height field", {2, 3, 4, 6, 8});
}

TEST(GridRefinement, ThreePeaksFitsNeverWorseWithMoreFrames) {
  const std::string path = testing::cgalData("three_peaks.off");
  expectRefinementNeverWorse(readMesh(path), "three_peaks.off", {2, 3, 4, 6, 8});
}

TEST(GridRefinement, TheLionHeadFitsNeverWorseWithMoreFrames) {
  const std::string path = testing::cgalData("lion-head.off");
  expectRefinementNeverWorse(readMesh(path), "lion-head.off", {2, 4, 6, 8});
}

}  // namespace
}  // namespace pdesurf
