// Mesh-to-mesh distances with known answers: concentric spheres, a mesh and itself, a mesh
// and a part of it, a square under a tilted plane (area weighting), sampling density.
#include "pdesurf/mesh_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "pdesurf/mesh_io.hpp"
#include "support/cgal_data.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

/// Positions are stored as float: a point of size ~1 is off by up to ~1e-7; 1e-6 bounds
/// the resulting error of a distance between meshes of size ~1.
constexpr double kFloatTolerance = 1e-6;

/// A sample's distance to the triangle it was taken on: the closest point is the sample
/// itself up to the rounding of the projection onto the triangle's plane.
constexpr double kSelfDistanceTolerance = 1e-12;

Vec3 vertex(const Mesh& mesh, std::uint32_t v) {
  return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

/// The chord error of a mesh inscribed in the sphere of `radius` round the origin: how far
/// inside the sphere its triangles reach (radius minus the least distance from the centre
/// to a triangle's plane, an upper bound).
double chordError(const Mesh& mesh, double radius) {
  double least = radius;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 a = vertex(mesh, mesh.indices[3 * t]), b = vertex(mesh, mesh.indices[3 * t + 1]),
               c = vertex(mesh, mesh.indices[3 * t + 2]);
    const Vec3 n = (b - a).cross(c - a);
    if (n.norm() > 0) least = std::min(least, std::abs(a.dot(n.normalized())));
  }
  return radius - least;
}

TEST(MeshDistance, ConcentricSpheresAreTheirRadiusDifferenceApart) {
  const double r = 1.0, scale = 1.1;
  const Mesh a = testing::sphereMesh(r, 64, 32);
  const Mesh b = testing::scaled(a, scale);
  const MeshDistance d = meshDistance(a, b);
  // Every point of A is within chordError(A) inside the sphere of radius r, and B lies
  // between its sphere (radius 1.1 r) and chordError(B) inside it. As B is convex and A
  // inside it, a point's distance to B lies in [0.1 r - chordError(B), 0.1 r + chordError(A)];
  // the same bounds hold from B to A.
  const double gap = (scale - 1) * r;
  const double lo = gap - chordError(b, scale * r) - kFloatTolerance;
  const double hi = gap + chordError(a, r) + kFloatTolerance;
  ASSERT_LT(hi - lo, 0.02);  // the test means something: the band is narrow
  for (const OneWayDistance* w : {&d.aToB, &d.bToA}) {
    for (double value : {w->mean, w->rms, w->max}) {
      EXPECT_GE(value, lo);
      EXPECT_LE(value, hi);
    }
    EXPECT_LE(w->mean, w->rms + 1e-15);
    EXPECT_LE(w->rms, w->max + 1e-15);
  }
  // Relative values: divided by B's bounding-box diagonal, 2.2 √3 (B has vertices at ±1.1
  // on every axis: poles, and the equator ring at angles 0, 90°, 180°, 270°).
  EXPECT_NEAR(d.diagonal, 2 * scale * r * std::sqrt(3.0), kFloatTolerance);
  EXPECT_DOUBLE_EQ(d.aToB.rmsRelative, d.aToB.rms / d.diagonal);
  EXPECT_DOUBLE_EQ(d.bToA.maxRelative, d.bToA.max / d.diagonal);
  EXPECT_EQ(d.hausdorff, std::max(d.aToB.max, d.bToA.max));
  EXPECT_DOUBLE_EQ(d.hausdorffRelative, d.hausdorff / d.diagonal);
}

TEST(MeshDistance, MeshToItselfIsZero) {
  const Mesh sphere = testing::sphereMesh(1.0, 32, 16);
  const MeshDistance d = meshDistance(sphere, sphere);
  for (const OneWayDistance* w : {&d.aToB, &d.bToA}) {
    EXPECT_LE(w->max, kSelfDistanceTolerance);
    EXPECT_LE(w->rms, kSelfDistanceTolerance);
    // Vertices plus k² face samples per triangle, 100000 in all by default.
    EXPECT_GE(w->samples, sphere.vertexCount() + DistanceOptions{}.samples);
  }
}

TEST(MeshDistance, PartOfAMeshIsAsymmetric) {
  // A: the upper half of the sphere's triangles; B: the whole sphere.
  const int segments = 64;
  const Mesh b = testing::sphereMesh(1.0, segments, 32);
  Mesh a = b;
  a.indices.clear();
  for (std::size_t t = 0; t < b.triangleCount(); ++t) {
    double z = 0;
    for (int c = 0; c < 3; ++c) z += vertex(b, b.indices[3 * t + c]).z();
    if (z > 0) a.indices.insert(a.indices.end(), &b.indices[3 * t], &b.indices[3 * t] + 3);
  }
  const MeshDistance d = meshDistance(a, b);
  EXPECT_LE(d.aToB.max, kSelfDistanceTolerance);  // A lies on B
  // B's farthest point from A is its south pole (a vertex, so sampled exactly), at √2 from
  // the equator ring's vertices and √(1 + cos²(π/n)) from its chords' midpoints.
  EXPECT_LE(d.bToA.max, std::sqrt(2.0) + kFloatTolerance);
  EXPECT_GE(d.bToA.max, std::sqrt(1 + std::pow(std::cos(M_PI / segments), 2)) - kFloatTolerance);
  EXPECT_NEAR(d.bToA.maxAt.z(), -1.0, kFloatTolerance);
  EXPECT_EQ(d.hausdorff, d.bToA.max);
  EXPECT_GT(d.bToA.rms, 0.3);
}

TEST(MeshDistance, MeanAndRmsAreAreaWeighted) {
  // A: the unit square at z = 0. B: the plane z = x, large enough to hold every closest
  // point. The distance from (x, y, 0) is x / √2: mean 1 / (2√2), RMS √(1/6), max 1 / √2.
  testing::MeshBuilder square, plane;
  square.quad(square.vertex(0, 0, 0), square.vertex(1, 0, 0), square.vertex(1, 1, 0),
              square.vertex(0, 1, 0));
  plane.quad(plane.vertex(-1, -1, -1), plane.vertex(3, -1, 3), plane.vertex(3, 2, 3),
             plane.vertex(-1, 2, -1));
  const MeshDistance d = meshDistance(square.mesh(), plane.mesh());
  // Centroid sampling integrates the linear distance exactly and its square with an error
  // of order (spacing)², here about 1e-6 relative with 100000 samples.
  EXPECT_NEAR(d.aToB.mean, 1 / (2 * std::sqrt(2.0)), 1e-10);
  EXPECT_NEAR(d.aToB.rms, std::sqrt(1.0 / 6), 1e-5);
  EXPECT_NEAR(d.aToB.max, 1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.aToB.maxAt.x(), 1.0, 1e-12);
}

TEST(MeshDistance, SamplingDensityFollowsTheOptions) {
  const Mesh sphere = testing::sphereMesh(1.0, 16, 8);
  DistanceOptions sparse;
  sparse.samples = 1;
  sparse.minSamplesPerTriangle = 9;  // k = 3 on every triangle
  const MeshDistance d = meshDistance(sphere, sphere, sparse);
  EXPECT_EQ(d.aToB.samples, sphere.vertexCount() + 9 * sphere.triangleCount());
  DistanceOptions dense;
  dense.samples = 200000;
  const MeshDistance e = meshDistance(sphere, sphere, dense);
  EXPECT_GE(e.aToB.samples, sphere.vertexCount() + dense.samples);
  // About 28 rather than 3 subdivisions per side: the cover radius shrinks accordingly
  // (less on the triangles whose share of the samples is smallest for their size).
  EXPECT_LT(e.aToB.coverRadius, d.aToB.coverRadius / 6);
  EXPECT_GT(e.aToB.coverRadius, 0.0);
}

TEST(MeshDistance, SameResultForAnyThreadCount) {
  const Mesh a = testing::sphereMesh(1.0, 64, 32), b = testing::sphereMesh(1.2, 48, 24);
  DistanceOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const MeshDistance d1 = meshDistance(a, b, one), d3 = meshDistance(a, b, three);
  for (auto [w1, w3] : {std::pair{&d1.aToB, &d3.aToB}, {&d1.bToA, &d3.bToA}}) {
    EXPECT_EQ(w1->samples, w3->samples);
    EXPECT_EQ(w1->rms, w3->rms);
    EXPECT_EQ(w1->mean, w3->mean);
    EXPECT_EQ(w1->max, w3->max);
    EXPECT_EQ(w1->maxAt, w3->maxAt);
  }
}

TEST(MeshDistance, DegenerateMeshIsAnInvalidArgument) {
  testing::MeshBuilder line;
  line.triangle(line.vertex(0, 0, 0), line.vertex(1, 0, 0), line.vertex(2, 0, 0));
  EXPECT_THROW(meshDistance(line.mesh(), testing::sphereMesh(1, 8, 4)), InvalidArgument);
  EXPECT_THROW(meshDistance(testing::sphereMesh(1, 8, 4), Mesh{}), InvalidArgument);
}

// Real data: CGAL's elephant against itself and against a copy scaled by 1.01 about its
// bounding-box centre (within the bounds a uniform scaling allows).
TEST(MeshDistance, ElephantAgainstItselfAndAScaledCopy) {
  const Mesh elephant = readMesh(testing::cgalData("elephant.off"));
  const MeshDistance self = meshDistance(elephant, elephant);
  EXPECT_LE(self.hausdorffRelative, kSelfDistanceTolerance);
  Mesh bigger = elephant;
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (std::size_t v = 0; v < elephant.vertexCount(); ++v) {
    lo = lo.cwiseMin(vertex(elephant, static_cast<std::uint32_t>(v)));
    hi = hi.cwiseMax(vertex(elephant, static_cast<std::uint32_t>(v)));
  }
  const Vec3 centre = (lo + hi) / 2;
  double farthest = 0;
  for (std::size_t v = 0; v < elephant.vertexCount(); ++v) {
    const Vec3 p = vertex(elephant, static_cast<std::uint32_t>(v));
    const Vec3 q = centre + 1.01 * (p - centre);
    farthest = std::max(farthest, (q - p).norm());
    for (int c = 0; c < 3; ++c) bigger.positions[3 * v + c] = static_cast<float>(q[c]);
  }
  const MeshDistance d = meshDistance(elephant, bigger);
  // No point moves farther than the farthest vertex does.
  EXPECT_GT(d.hausdorff, 0.0);
  EXPECT_LE(d.hausdorff, farthest + kFloatTolerance);
  EXPECT_LT(d.aToB.rms, d.aToB.max);
}

// ---------------------------------------------------------------------------------------
// Normals: folded area and RMS normal deviation of a mesh against a reference.

/// Angles and area shares computed from float positions: a few ulps of float (1e-7
/// relative) in each normal, far below 1e-4 of a degree or of the area.
constexpr double kNormalTolerance = 1e-4;

/// An n × n grid of squares, two triangles each, over [x0, x1] × [y0, y1] at height z, its
/// triangles wound counter-clockwise seen from +z (normal +z), or the other way (`down`).
Mesh gridSheet(double x0, double x1, double y0, double y1, double z, int n, bool down = false) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      for (double c : {x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, z})
        m.positions.push_back(static_cast<float>(c));
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      for (std::uint32_t v : down ? std::array{a, c, b, a, d, c} : std::array{a, b, c, a, c, d})
        m.indices.push_back(v);
    }
  return m;
}

TEST(NormalDeviation, APlaneAgainstAPlaneAndReversed) {
  const Mesh reference = gridSheet(-1, 1, -1, 1, 0, 16);
  const Mesh model = gridSheet(-0.8, 0.8, -0.8, 0.8, 0.01, 7);
  const NormalDeviation same = normalDeviation(model, reference);
  EXPECT_EQ(same.foldedArea, 0.0);
  EXPECT_LT(same.rmsDegrees, kNormalTolerance);
  EXPECT_FALSE(same.reversed);
  // Facing the other way throughout: the majority rule takes its orientation as it is.
  const NormalDeviation reversed =
      normalDeviation(gridSheet(-0.8, 0.8, -0.8, 0.8, 0.01, 7, true), reference);
  EXPECT_EQ(reversed.foldedArea, 0.0);
  EXPECT_LT(reversed.rmsDegrees, kNormalTolerance);
  EXPECT_TRUE(reversed.reversed);
}

TEST(NormalDeviation, AFlapFoldedBackIsItsShareOfTheArea) {
  // A Z fold over a plane: a sheet from x = 0 to 0.6, the flap folded back from 0.6 to 0.4
  // just above it (facing down), and a sheet from 0.4 on to 1 above that: the flap is 0.2 of
  // the 1.4 units of length, so 1/7 of the area, and its normals are 180° off.
  const Mesh reference = gridSheet(-0.5, 1.5, -0.5, 1.5, 0, 20);
  const Mesh folded = testing::merged(
      testing::merged(gridSheet(0, 0.6, 0, 1, 0.01, 6), gridSheet(0.4, 0.6, 0, 1, 0.02, 2, true)),
      gridSheet(0.4, 1, 0, 1, 0.03, 6));
  const NormalDeviation d = normalDeviation(folded, reference);
  EXPECT_NEAR(d.foldedArea, 1.0 / 7.0, kNormalTolerance);
  EXPECT_FALSE(d.reversed);
  EXPECT_NEAR(d.rmsDegrees, std::sqrt(180.0 * 180.0 / 7.0), kNormalTolerance);
}

TEST(NormalDeviation, ATiltedPlaneDeviatesByItsTilt) {
  const Mesh reference = gridSheet(-2, 2, -2, 2, 0, 8);
  for (double degrees : {5.0, 30.0, 80.0}) {
    SCOPED_TRACE(degrees);
    // The unit square tilted about the y axis (it stays within the reference's extent).
    Mesh tilted = gridSheet(-0.5, 0.5, -0.5, 0.5, 0, 5);
    const double t = degrees * std::numbers::pi / 180.0;
    for (std::size_t v = 0; v < tilted.vertexCount(); ++v) {
      const double x = tilted.positions[3 * v];
      tilted.positions[3 * v] = static_cast<float>(x * std::cos(t));
      tilted.positions[3 * v + 2] = static_cast<float>(0.1 + x * std::sin(t));
    }
    const NormalDeviation d = normalDeviation(tilted, reference);
    EXPECT_EQ(d.foldedArea, 0.0);
    EXPECT_NEAR(d.rmsDegrees, degrees, kNormalTolerance);
  }
}

}  // namespace
}  // namespace pdesurf
