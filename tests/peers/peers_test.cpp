// The accuracy peers: each meets its RMS target, one step coarser misses it, and the
// B-spline least-squares fit agrees with Open CASCADE's approximation of the same samples.
#include <gtest/gtest.h>

#include <cmath>

#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include "pdesurf/analysis.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/tube_layout.hpp"
#include "peers.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

/// Distances sampled as the benchmark samples them, fewer for speed.
DistanceOptions testDistance() {
  DistanceOptions d;
  d.samples = 20000;
  return d;
}

/// The height field z = h(x, y) on [0, 1]², smooth, a few bumps.
double height(double x, double y) { return 0.15 * std::sin(3 * x) * std::cos(2 * y) + 0.1 * x * y; }

Mesh heightField(int n) {
  testing::MeshBuilder b;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      b.vertex(double(i) / n, double(j) / n, height(double(i) / n, double(j) / n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      b.quad(j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
             (j + 1) * (n + 1) + i);
  return b.mesh();
}

/// Our bicubic least-squares fit and Open CASCADE's (GeomAPI_PointsToBSplineSurface, degree 3,
/// C2, iso-parametric) of the same 21 × 21 samples agree to this fraction of the size.
constexpr double kOcctAgreement = 1e-3;

TEST(BSplinePeer, AgreesWithOpenCascadesApproximationOfTheSameGrid) {
  constexpr int kGrid = 21;
  TColgp_Array2OfPnt points(1, kGrid, 1, kGrid);
  std::vector<ParamSample> samples;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const double u = double(i) / (kGrid - 1), v = double(j) / (kGrid - 1);
      points.SetValue(i + 1, j + 1, gp_Pnt(u, v, height(u, v)));
      samples.push_back({u, v, Vec3(u, v, height(u, v)), 1.0});
    }
  GeomAPI_PointsToBSplineSurface occt;
  occt.Init(points, Approx_IsoParametric, 3, 3, GeomAbs_C2, 1e-5);
  ASSERT_TRUE(occt.IsDone());
  const Handle(Geom_BSplineSurface) reference = occt.Surface();
  double u0, u1, v0, v1;
  reference->Bounds(u0, u1, v0, v1);
  const BSplineGrid ours = fitBSpline(samples, 12, 12, false, false);
  double worst = 0.0, worstToSamples = 0.0;
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i) {
      const double u = i / 40.0, v = j / 40.0;
      const gp_Pnt q = reference->Value(u0 + u * (u1 - u0), v0 + v * (v1 - v0));
      worst = std::max(worst, (ours.position(u, v) - Vec3(q.X(), q.Y(), q.Z())).norm());
    }
  for (const ParamSample& s : samples)
    worstToSamples = std::max(worstToSamples, (ours.position(s.u, s.v) - s.p).norm());
  EXPECT_LT(worst, kOcctAgreement * std::sqrt(2.0));
  EXPECT_LT(worstToSamples, kOcctAgreement * std::sqrt(2.0));
  // A net too coarse for the bumps does not agree: the comparison can fail.
  const BSplineGrid coarse = fitBSpline(samples, 4, 4, false, false);
  double coarseWorst = 0.0;
  for (const ParamSample& s : samples)
    coarseWorst = std::max(coarseWorst, (coarse.position(s.u, s.v) - s.p).norm());
  EXPECT_GT(coarseWorst, kOcctAgreement * std::sqrt(2.0));
}

TEST(BSplinePeer, AClosedNetIsSeamless) {
  BSplineGrid s;
  s.nu = 6;
  s.nv = 5;
  s.closedU = true;
  for (std::uint32_t j = 0; j < s.nv; ++j)
    for (std::uint32_t i = 0; i < s.nu; ++i)
      s.control.push_back(Vec3(std::cos(i), std::sin(i), j) + Vec3(0.1 * i * j, 0, 0));
  for (double v : {0.0, 0.3, 1.0})
    EXPECT_LT((s.position(0.0, v) - s.position(1.0, v)).norm(), 1e-12);
  EXPECT_EQ(tessellate(s, 12, 7).vertexCount(), 12u * 7u);
}

TEST(PolygonPeer, TheFewestEdgesWithinTheTargetAndOneFewerMisses) {
  const Mesh truth = heightField(48);
  for (double target : {2e-3, 4e-4}) {
    SCOPED_TRACE(target);
    const PolygonPeer peer = simplifiedPeer(truth, target, testDistance());
    EXPECT_TRUE(peer.reached);
    EXPECT_LE(peer.rms, target);
    EXPECT_GT(peer.rms, 0.0);  // simplified, not the truth itself
    EXPECT_LT(peer.mesh.vertexCount(), truth.vertexCount());
    EXPECT_GT(peer.coarserRms, target);  // the search returned the minimum
    EXPECT_EQ(peer.bytes, storageBytes(peer.mesh));
  }
}

TEST(NurbsPeer, TheCoarsestNetWithinTheTargetOnAGridAndATube) {
  // A 3 × 3 grid of frames fitted to the height field gives the parameterisation.
  const Mesh field = heightField(48);
  const FitResult fit = fitVertexFrames(gridLayout(field, {3, 3}, "field"), field);
  const auto samples = layoutSamples(solve(fit.model), {3, 3, false, false}, field, 10000);
  for (const ParamSample& s : samples) {
    ASSERT_GE(s.u, 0.0);
    ASSERT_LE(s.u, 1.0);
  }
  for (double target : {1e-3, 4e-4}) {
    SCOPED_TRACE(target);
    const NurbsPeer peer =
        bsplinePeer(samples, {3, 3, false, false}, field, target, testDistance());
    EXPECT_TRUE(peer.reached);
    EXPECT_LE(peer.rms, target);
    EXPECT_GT(peer.coarserRms, target);
    EXPECT_EQ(peer.bytes, storageBytes(peer.surface));
  }
  // A tube: closed round (periodic in u).
  testing::CylinderOptions c;
  c.caps = false;
  c.rings = 32;
  c.segments = 128;
  const Mesh cylinder = testing::cylinderMesh(c);
  TubeLayoutOptions o;
  o.rings = 2;
  o.sectors = 4;
  const TubeLayout tube = tubeLayout(cylinder, o, "cylinder");
  const FitResult tubeFit = fitVertexFrames(tube.model, tube.part);
  const LayoutGrid grid{4, 2, true, false};
  const auto tubeSamples = layoutSamples(solve(tubeFit.model), grid, tube.part, 10000);
  const NurbsPeer peer = bsplinePeer(tubeSamples, grid, tube.part, 1e-3, testDistance());
  EXPECT_TRUE(peer.reached);
  EXPECT_LE(peer.rms, 1e-3);
  EXPECT_TRUE(peer.surface.closedU);
}

}  // namespace
}  // namespace pdesurf
