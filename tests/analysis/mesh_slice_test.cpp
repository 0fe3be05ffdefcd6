// Cross sections of meshes with known answers: cylinders (circles of known radius and area,
// planes through vertex rings), boxes (faces in the plane), open and non-manifold meshes,
// error messages, and CGAL's elephant (real data).
#include "pdesurf/mesh_slice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>

#include "pdesurf/mesh_io.hpp"
#include "support/cgal_data.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

using testing::cylinderMesh;
using testing::CylinderOptions;

/// Positions are stored as float: a coordinate of size ~1 is off by up to 2^-24 ≈ 6e-8
/// relative; 1e-6 bounds the resulting error of a section point, length or area of size ~1.
constexpr double kFloatTolerance = 1e-6;

/// Shoelace area of a closed polyline in the plane's (u, w) = (axis+1, axis+2) coordinates,
/// computed here independently of the library: positive when counter-clockwise seen from +axis.
double signedArea(const std::vector<Vec3>& points, int axis) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  double twice = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const Vec3& q = points[(i + 1) % points.size()];
    twice += p[u] * q[w] - q[u] * p[w];
  }
  return 0.5 * twice;
}

/// The invariants of every section: on its plane exactly, at least three points, no point
/// repeated next to itself (the closing pair included), counter-clockwise seen from +axis,
/// and `area` and `length` those of the polyline.
void expectWellFormed(const MeshSection& s, Axis axis) {
  const int k = static_cast<int>(axis);
  ASSERT_GE(s.points.size(), 3u) << "plane " << s.index;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    EXPECT_EQ(s.points[i][k], s.coordinate) << "plane " << s.index << " point " << i;
    EXPECT_NE(s.points[i], s.points[(i + 1) % s.points.size()])
        << "plane " << s.index << " point " << i;
  }
  const double area = signedArea(s.points, k);
  EXPECT_GT(area, 0.0) << "plane " << s.index;
  EXPECT_NEAR(s.area, area, 1e-9 * std::max(1.0, area)) << "plane " << s.index;
  double length = 0.0;
  for (std::size_t i = 0; i < s.points.size(); ++i)
    length += (s.points[(i + 1) % s.points.size()] - s.points[i]).norm();
  EXPECT_NEAR(s.length, length, 1e-9 * length) << "plane " << s.index;
}

TEST(MeshSlice, CylinderSectionsAreItsRegularPolygon) {
  CylinderOptions o;
  o.radius = 1.5;
  o.segments = 48;
  const Mesh mesh = cylinderMesh(o);
  SliceOptions options;
  options.count = 7;
  const std::vector<MeshSection> sections = sliceMesh(mesh, options);
  ASSERT_EQ(sections.size(), 7u);
  // The side is made of planar quads: a section is the regular n-gon inscribed in the circle
  // (plus points on its sides where the plane cuts the quads' diagonals), so its points lie
  // between the chord midpoints' radius r cos(π/n) and r: the chord error bounds them.
  const double n = o.segments, r = o.radius;
  const double chordError = r * (1 - std::cos(M_PI / n));
  const double polygonArea = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  const double polygonLength = 2 * n * r * std::sin(M_PI / n);
  for (std::uint32_t i = 0; i < sections.size(); ++i) {
    const MeshSection& s = sections[i];
    expectWellFormed(s, Axis::Z);
    EXPECT_EQ(s.index, i);
    // The default rule: the middle of K equal slabs of the extent [0, 2].
    EXPECT_DOUBLE_EQ(s.coordinate, (i + 0.5) * o.height / 7);
    for (const Vec3& p : s.points) {
      const double rho = std::hypot(p.x(), p.y());
      EXPECT_LE(rho, r + kFloatTolerance);
      EXPECT_GE(rho, r - chordError - kFloatTolerance);
    }
    EXPECT_NEAR(s.area, polygonArea, kFloatTolerance * polygonArea);
    EXPECT_NEAR(s.length, polygonLength, kFloatTolerance * polygonLength);
    // And the circle's own area within the chord error's effect, 2 chordError / r relative.
    EXPECT_NEAR(s.area, M_PI * r * r, 2 * chordError / r * M_PI * r * r);
  }
}

TEST(MeshSlice, PlanesThroughVertexRingsGiveTheRingExactly) {
  // Rings at z = 0, 0.5, 1, 1.5, 2 (exact in float); the end planes lie on the caps' faces.
  const CylinderOptions o;
  const Mesh mesh = cylinderMesh(o);
  SliceOptions options;
  options.count = 5;
  options.range = {{0.0, 2.0}};
  const std::vector<MeshSection> sections = sliceMesh(mesh, options);
  ASSERT_EQ(sections.size(), 5u);
  for (std::uint32_t i = 0; i < 5; ++i) {
    const MeshSection& s = sections[i];
    expectWellFormed(s, Axis::Z);
    EXPECT_EQ(s.coordinate, 0.5 * i);
    // Exactly the ring's vertices, each once.
    std::set<std::tuple<double, double, double>> ring, got;
    for (int j = 0; j < o.segments; ++j) {
      const std::size_t v = static_cast<std::size_t>(i) * o.segments + j;
      ring.insert({mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]});
    }
    for (const Vec3& p : s.points) got.insert({p.x(), p.y(), p.z()});
    EXPECT_EQ(s.points.size(), static_cast<std::size_t>(o.segments)) << "plane " << i;
    EXPECT_EQ(got, ring) << "plane " << i;
  }
}

TEST(MeshSlice, BoxSectionsAlongEachAxisIncludingFacesInThePlane) {
  const Mesh box = testing::boxMesh({0, 0, 0}, {1, 2, 3});
  const double extent[3] = {1, 2, 3};
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const int k = static_cast<int>(axis);
    SliceOptions options;
    options.axis = axis;
    options.count = 3;
    options.range = {{0.0, extent[k]}};  // both end planes hold a face
    const std::vector<MeshSection> sections = sliceMesh(box, options);
    ASSERT_EQ(sections.size(), 3u);
    const double area = 6.0 / extent[k];
    const double length = 2 * (extent[(k + 1) % 3] + extent[(k + 2) % 3]);
    for (const MeshSection& s : sections) {
      expectWellFormed(s, axis);
      // The end planes hold a face: its four corners. The middle one also crosses the side
      // faces' diagonals: four more points, on the rectangle's sides.
      EXPECT_EQ(s.points.size(), s.index == 1 ? 8u : 4u) << axisName(axis) << " plane " << s.index;
      EXPECT_NEAR(s.area, area, 1e-12) << axisName(axis) << " plane " << s.index;
      EXPECT_NEAR(s.length, length, 1e-12) << axisName(axis) << " plane " << s.index;
    }
  }
}

TEST(MeshSlice, KeepsTheLargestLoop) {
  CylinderOptions small, large;
  small.radius = 1.0;
  large.radius = 2.0;
  large.offset = {10, 0, 0};
  const Mesh mesh = testing::merged(cylinderMesh(small), cylinderMesh(large));
  SliceOptions options;
  options.count = 3;
  for (const MeshSection& s : sliceMesh(mesh, options)) {
    expectWellFormed(s, Axis::Z);
    for (const Vec3& p : s.points) EXPECT_NEAR(p.x(), 10, 2 + kFloatTolerance);
  }
}

TEST(MeshSlice, OrientationDoesNotDependOnTheMeshOrientation) {
  Mesh inward = cylinderMesh({});
  for (std::size_t t = 0; t < inward.triangleCount(); ++t)
    std::swap(inward.indices[3 * t + 1], inward.indices[3 * t + 2]);
  for (const MeshSection& s : sliceMesh(inward, {})) expectWellFormed(s, Axis::Z);
}

TEST(MeshSlice, PlaneMissingTheMeshIsAnErrorNamingItAndTheExtent) {
  SliceOptions options;
  options.count = 2;
  options.range = {{1.0, 3.0}};
  try {
    sliceMesh(cylinderMesh({}), options);
    FAIL() << "no error";
  } catch (const MeshSliceError& e) {
    EXPECT_EQ(std::string(e.what()), "plane 1 at z=3 does not meet the mesh (extent z in [0, 2])");
  }
}

TEST(MeshSlice, PlaneBetweenTwoPartsIsAnError) {
  CylinderOptions upper;
  upper.offset = {0, 0, 5};
  const Mesh mesh = testing::merged(cylinderMesh({}), cylinderMesh(upper));
  SliceOptions options;
  options.count = 1;
  options.range = {{3.5, 3.5}};
  try {
    sliceMesh(mesh, options);
    FAIL() << "no error";
  } catch (const MeshSliceError& e) {
    EXPECT_NE(std::string(e.what()).find("plane 0 at z=3.5 cuts no triangle"), std::string::npos)
        << e.what();
  }
}

TEST(MeshSlice, OpenChainsAreNotLoops) {
  CylinderOptions slit;
  slit.caps = false;
  slit.slitSegments = 3;  // a tube with a slit down its side: every section is an open arc
  try {
    sliceMesh(cylinderMesh(slit), {});
    FAIL() << "no error";
  } catch (const MeshSliceError& e) {
    EXPECT_NE(std::string(e.what()).find("plane 0 at z=0.1 has no closed loop: the section is 1 "
                                         "open chain"),
              std::string::npos)
        << e.what();
  }
  // An open tube (no caps, no slit) still has closed sections.
  CylinderOptions tube;
  tube.caps = false;
  for (const MeshSection& s : sliceMesh(cylinderMesh(tube), {})) expectWellFormed(s, Axis::Z);
}

TEST(MeshSlice, BoxesSharingAnEdgeAreSliced) {
  // Two unit cubes sharing the vertical edge x = y = 1 (the same vertex indices): a
  // non-manifold edge that every plane z in (0, 1) crosses.
  testing::MeshBuilder b;
  std::uint32_t first[8];
  for (int i = 0; i < 8; ++i) first[i] = b.vertex(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::uint32_t second[8] = {first[3],          b.vertex(2, 1, 0), b.vertex(1, 2, 0),
                                   b.vertex(2, 2, 0), first[7],          b.vertex(2, 1, 1),
                                   b.vertex(1, 2, 1), b.vertex(2, 2, 1)};
  const std::uint32_t* cubes[2] = {first, second};
  for (const std::uint32_t* c : cubes) {  // faces as in testing::boxMesh
    b.quad(c[0], c[2], c[3], c[1]);
    b.quad(c[4], c[5], c[7], c[6]);
    b.quad(c[0], c[1], c[5], c[4]);
    b.quad(c[2], c[6], c[7], c[3]);
    b.quad(c[0], c[4], c[6], c[2]);
    b.quad(c[1], c[3], c[7], c[5]);
  }
  SliceOptions options;
  options.count = 3;
  for (const MeshSection& s : sliceMesh(b.mesh(), options)) {
    expectWellFormed(s, Axis::Z);
    // One square, or both as a figure eight through the shared corner.
    EXPECT_TRUE(std::abs(s.area - 1) < 1e-12 || std::abs(s.area - 2) < 1e-12) << s.area;
  }
}

TEST(MeshSlice, BadOptionsAreInvalidArguments) {
  SliceOptions options;
  options.count = 0;
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), std::invalid_argument);
  options.count = 2;
  options.range = {{1.0, 1.0}};
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), std::invalid_argument);
  options.range = {{1.0, 0.5}};
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), std::invalid_argument);
}

TEST(MeshSlice, FlatMeshIsAnError) {
  testing::MeshBuilder b;
  b.triangle(b.vertex(0, 0, 0), b.vertex(1, 0, 0), b.vertex(0, 1, 0));
  EXPECT_THROW(sliceMesh(b.mesh(), {}), MeshSliceError);
}

// Real data: CGAL's elephant (libcgal-demo). Every plane along every axis gives a loop whose
// points are where the plane crosses mesh edges.
TEST(MeshSlice, ElephantSectionsAreClosedLoopsOnTheMesh) {
  const Mesh mesh = readMesh(testing::cgalData("elephant.off"));
  ASSERT_GT(mesh.triangleCount(), 5000u);
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const int k = static_cast<int>(axis);
    SliceOptions options;
    options.axis = axis;
    options.count = 25;
    const std::vector<MeshSection> sections = sliceMesh(mesh, options);
    ASSERT_EQ(sections.size(), 25u);
    for (const MeshSection& s : sections) {
      expectWellFormed(s, axis);
      // Each point lies on an edge of the mesh that the plane crosses (to float rounding).
      std::vector<std::pair<Vec3, Vec3>> crossing;
      for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int c = 0; c < 3; ++c) {
          const std::uint32_t a = mesh.indices[3 * t + c], e = mesh.indices[3 * t + (c + 1) % 3];
          const Vec3 pa(mesh.positions[3 * a], mesh.positions[3 * a + 1],
                        mesh.positions[3 * a + 2]);
          const Vec3 pe(mesh.positions[3 * e], mesh.positions[3 * e + 1],
                        mesh.positions[3 * e + 2]);
          if (std::min(pa[k], pe[k]) <= s.coordinate && s.coordinate <= std::max(pa[k], pe[k]))
            crossing.push_back({pa, pe});
        }
      for (const Vec3& p : s.points) {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& [a, e] : crossing) {
          const double t =
              std::clamp((p - a).dot(e - a) / std::max(1e-300, (e - a).squaredNorm()), 0.0, 1.0);
          best = std::min(best, (a + t * (e - a) - p).norm());
        }
        EXPECT_LT(best, kFloatTolerance) << axisName(axis) << " plane " << s.index;
      }
    }
  }
}

}  // namespace
}  // namespace pdesurf
