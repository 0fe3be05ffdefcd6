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

/// Two separate cylinders: the small one round the z axis (radius 1), the large one
/// (radius 2) round x = 10. Every plane z in (0, 2) cuts both.
Mesh twoCylinders() {
  CylinderOptions small, large;
  small.radius = 1.0;
  large.radius = 2.0;
  large.offset = {10, 0, 0};
  return testing::merged(cylinderMesh(small), cylinderMesh(large));
}

/// Every point of the section within `radius` (plus float rounding) of (cx, cy).
void expectAround(const MeshSection& s, double cx, double cy, double radius) {
  for (const Vec3& p : s.points)
    EXPECT_LE(std::hypot(p.x() - cx, p.y() - cy), radius + kFloatTolerance)
        << "plane " << s.index << " point (" << p.x() << ", " << p.y() << ")";
}

TEST(MeshSlice, NearPicksTheLoopNearestThePointOnEveryPlane) {
  const Mesh mesh = twoCylinders();
  SliceOptions options;
  options.count = 5;
  // Default: the largest loop, the cylinder at x = 10.
  for (const MeshSection& s : sliceMesh(mesh, options)) expectAround(s, 10, 0, 2);
  // Near a point by the small cylinder: the small one on every plane. The point's z does
  // not matter (it is projected onto each plane).
  options.near = Vec3(0.3, -0.2, 57.0);
  const std::vector<MeshSection> sections = sliceMesh(mesh, options);
  ASSERT_EQ(sections.size(), 5u);
  for (const MeshSection& s : sections) {
    expectWellFormed(s, Axis::Z);
    expectAround(s, 0, 0, 1);
    EXPECT_EQ(s.loops, 2u);
    // The area centroid of the regular polygon is its centre.
    EXPECT_NEAR(s.centroid.x(), 0.0, kFloatTolerance);
    EXPECT_NEAR(s.centroid.y(), 0.0, kFloatTolerance);
    EXPECT_EQ(s.centroid.z(), s.coordinate);
  }
  // Nearer the large one (in the plane): the large one.
  options.near = Vec3(6.0, 0.0, -3.0);
  for (const MeshSection& s : sliceMesh(mesh, options)) expectAround(s, 10, 0, 2);
}

TEST(MeshSlice, TrackFollowsAPartThatMovesAcrossThePlanes) {
  // A unit cylinder sheared so that its axis runs from (0, 0, 0) to (5, 0, 2), and a fixed
  // cylinder of radius 0.5 round (3, 3). A fixed point near the sheared one's foot loses
  // it on the upper planes (its centre moves away by 2.5 z, the fixed one is 4.24 away);
  // tracking keeps it on every plane.
  CylinderOptions slanted, post;
  slanted.rings = 8;
  post.radius = 0.5;
  post.offset = {3, 3, 0};
  Mesh moving = cylinderMesh(slanted);
  for (std::size_t v = 0; v < moving.vertexCount(); ++v)
    moving.positions[3 * v] += static_cast<float>(2.5 * moving.positions[3 * v + 2]);
  const Mesh mesh = testing::merged(moving, cylinderMesh(post));
  SliceOptions options;
  options.count = 9;
  options.range = {{0.05, 1.95}};
  options.near = Vec3(0, 0, 0);
  std::size_t jumped = 0;
  for (const MeshSection& s : sliceMesh(mesh, options))
    if (std::abs(s.centroid.x() - 3) < 1e-3 && std::abs(s.centroid.y() - 3) < 1e-3) ++jumped;
  EXPECT_GT(jumped, 0u) << "a fixed point should lose the moving part on the upper planes";
  options.track = true;
  const std::vector<MeshSection> sections = sliceMesh(mesh, options);
  ASSERT_EQ(sections.size(), 9u);
  for (const MeshSection& s : sections) {
    expectWellFormed(s, Axis::Z);
    EXPECT_EQ(s.loops, 2u);
    // A sheared circle: centred on the axis at x = 2.5 z, within 1 of it in y.
    EXPECT_NEAR(s.centroid.x(), 2.5 * s.coordinate, 1e-3) << "plane " << s.index;
    EXPECT_NEAR(s.centroid.y(), 0.0, 1e-3) << "plane " << s.index;
  }
  // Track without near starts from the largest loop (the moving one: area π against π/4).
  options.near.reset();
  for (const MeshSection& s : sliceMesh(mesh, options))
    EXPECT_NEAR(s.centroid.x(), 2.5 * s.coordinate, 1e-3) << "plane " << s.index;
}

TEST(MeshSlice, NearOnAPlaneWithoutClosedLoopIsAnError) {
  CylinderOptions slit;
  slit.caps = false;
  slit.slitSegments = 3;
  SliceOptions options;
  options.near = Vec3(0, 0, 0);
  options.track = true;
  try {
    sliceMesh(cylinderMesh(slit), options);
    FAIL() << "no error";
  } catch (const MeshSliceError& e) {
    EXPECT_NE(std::string(e.what()).find("plane 0 at z=0.1 has no closed loop"), std::string::npos)
        << e.what();
  }
  options.near = Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0);
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), InvalidArgument);
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
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), InvalidArgument);
  options.count = 2;
  options.range = {{1.0, 1.0}};
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), InvalidArgument);
  options.range = {{1.0, 0.5}};
  EXPECT_THROW(sliceMesh(cylinderMesh({}), options), InvalidArgument);
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
