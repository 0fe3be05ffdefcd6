// A mesh rebuilt from its cross sections (include/pdesurf/section_rebuild.hpp): more
// sections never rebuild it worse, on a closed-form tube and on real meshes (CGAL's sample
// data), the part measured is the one the sections cut, and bad input names the plane.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "support/cgal_data.hpp"
#include "support/mesh_checks.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// The accuracy target at 25 sections: RMS within 0.3 % of the part's diagonal,
/// no point farther than 2 % (model to part and part to model).
constexpr double kRmsTarget25 = 0.003;
constexpr double kMaxTarget25 = 0.02;
/// "Falls or stays level": an RMS may exceed the one at fewer sections by this fraction of
/// itself, the sampling noise of the distance measure (100,000 area-weighted samples whose
/// positions move with the tessellation; measured repeatability ~0.5 %).
constexpr double kLevelSlack = 0.02;

/// A star-shaped tube ρ(z, θ) = R(z)(1 + 0.15 cos 3θ), R(z) = 1 + 0.3 sin 2z + 0.1 z, over
/// z ∈ [0, 3], as a fine open triangle mesh (200 × 400 quads: chord error ~3e-5 of the
/// diagonal, far below the distances measured).
Mesh starTubeMesh() {
  testing::MeshBuilder b;
  const int rows = 200, cols = 400;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const double z = 3.0 * i / rows, theta = kTwoPi * j / cols;
      const double rho =
          (1.0 + 0.3 * std::sin(2.0 * z) + 0.1 * z) * (1.0 + 0.15 * std::cos(3 * theta));
      b.vertex(rho * std::cos(theta), rho * std::sin(theta), z);
    }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * cols + (j % cols)); };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) b.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return b.mesh();
}

struct Measured {
  double rms = 0.0, max = 0.0;  ///< relative to the part's diagonal, the worse of both ways
};

Measured measure(const Mesh& mesh, const SectionRebuildOptions& options) {
  const SectionRebuild r = rebuildFromSections(mesh, options);
  const Mesh part = sectionedPart(mesh, options.slice.axis, r.sections);
  TessellateOptions t;
  t.resolution =
      std::max<std::uint32_t>(3, 256 / static_cast<std::uint32_t>(r.chain.patches.size()) + 1);
  t.aroundResolution = 256;
  const MeshDistance d = meshDistance(tessellate(r.chain, t), part);
  return {std::max(d.aToB.rmsRelative, d.bToA.rmsRelative),
          std::max(d.aToB.maxRelative, d.bToA.maxRelative)};
}

/// Rebuilds with 7, 13, 25 and 49 sections; checks the RMS falls or stays level and the
/// 25-section targets; prints the table (docs/rebuild.md).
void expectConvergence(const std::string& name, const Mesh& mesh, SectionRebuildOptions options) {
  std::vector<Measured> m;
  std::string table = name + ":";
  for (std::uint32_t count : {7u, 13u, 25u, 49u}) {
    options.slice.count = count;
    m.push_back(measure(mesh, options));
    char cell[96];
    std::snprintf(cell, sizeof cell, "  K=%u RMS %.3f%% max %.3f%%", count, 100 * m.back().rms,
                  100 * m.back().max);
    table += cell;
  }
  std::printf("%s\n", table.c_str());
  for (std::size_t i = 1; i < m.size(); ++i)
    EXPECT_LE(m[i].rms, m[i - 1].rms * (1 + kLevelSlack)) << table;
  EXPECT_LT(m[2].rms, kRmsTarget25) << table;
  EXPECT_LT(m[2].max, kMaxTarget25) << table;
}

TEST(SectionRebuild, ClosedFormTubeConverges) {
  SectionRebuildOptions o;
  o.slice.axis = Axis::Z;
  o.slice.range = {0.05, 2.95};
  expectConvergence("star tube", starTubeMesh(), o);
}

struct Part {
  const char* name;
  const char* file;
  Axis axis;
  double from, to;
  Vec3 near;
  bool track;
};

// The parts of docs/rebuild.md: an elephant's standing leg and raised trunk, a man's lower
// leg, a camel's front leg.
const Part kParts[] = {
    {"elephant leg", "elephant.off", Axis::Y, -0.45, -0.32, Vec3(0.117, -0.4, -0.045), false},
    {"elephant trunk", "elephant.off", Axis::Y, 0.345, 0.42, Vec3(0.15, 0.345, 0.17), true},
    {"man leg", "man.off", Axis::Z, -0.42, -0.12, Vec3(0.05, 0.0, -0.3), false},
    {"camel leg", "camel.off", Axis::Y, -0.4, -0.15, Vec3(0.05, -0.3, 0.25), false},
};

TEST(SectionRebuild, RealPartsNeverGetWorseWithMoreSections) {
  for (const Part& p : kParts) {
    SCOPED_TRACE(p.name);
    const Mesh mesh = readMesh(testing::cgalData(p.file));
    SectionRebuildOptions o;
    o.slice.axis = p.axis;
    o.slice.range = {p.from, p.to};
    o.slice.near = p.near;
    o.slice.track = p.track;
    expectConvergence(p.name, mesh, o);
  }
}

TEST(SectionRebuild, PartIsTheSlabOfTheChosenLoops) {
  const Mesh elephant = readMesh(testing::cgalData("elephant.off"));
  SectionRebuildOptions o;
  o.slice.axis = Axis::Y;
  o.slice.count = 5;
  o.slice.range = {-0.45, -0.32};
  o.slice.near = Vec3(0.117, -0.4, -0.045);
  const SectionRebuild r = rebuildFromSections(elephant, o);
  const Mesh part = sectionedPart(elephant, Axis::Y, r.sections);
  ASSERT_GT(part.triangleCount(), 100u);
  // Between the end planes, near the chosen leg only (the other legs are 0.1 or more away).
  for (std::size_t v = 0; v < part.vertexCount(); ++v) {
    const Vec3 p(part.positions[3 * v], part.positions[3 * v + 1], part.positions[3 * v + 2]);
    EXPECT_GE(p.y(), -0.45f - 1e-6);
    EXPECT_LE(p.y(), -0.32f + 1e-6);
    EXPECT_LT(Eigen::Vector2d(p.x() - 0.117, p.z() + 0.045).norm(), 0.09);
  }
  // A tube: open at the two planes only, each edge there on a plane.
  const auto stats = testing::edgeStats(part);
  EXPECT_EQ(stats.nonManifoldEdges, 0u);
  EXPECT_GT(stats.boundaryEdges, 0u);
}

TEST(SectionRebuild, BadInputNamesThePlane) {
  const Mesh elephant = readMesh(testing::cgalData("elephant.off"));
  auto expectError = [&](const SectionRebuildOptions& o, const std::string& what) {
    try {
      rebuildFromSections(elephant, o);
      FAIL() << "accepted: " << what;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  SectionRebuildOptions legs;  // through the four legs, no part chosen
  legs.slice.axis = Axis::Y;
  legs.slice.count = 3;
  legs.slice.range = {-0.45, -0.4};
  expectError(legs, "plane 0 at y=-0.45 cuts 2 closed loops (separate parts of the mesh)");
  testing::CylinderOptions c;
  c.segments = 6;  // each plane crosses 6 quads, split in 2 triangles each: 12 points
  c.caps = false;
  SectionRebuildOptions coarse;
  coarse.slice.count = 4;
  try {
    rebuildFromSections(testing::cylinderMesh(c), coarse);
    FAIL() << "a 12-point section taken for 8 modes";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("the loop has 12 points, too few for 8 Fourier modes"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("plane 0 at z="), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pdesurf
