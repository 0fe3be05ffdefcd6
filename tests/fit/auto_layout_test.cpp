// The automatic layout: any topology (closed, two boundary loops, genus 1, two components),
// a valid manifold frame model with no folds (at the start, and almost none after the fit),
// fits that never get worse with more frames, and the search for a target RMS.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "pdesurf/analysis.hpp"
#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "support/cgal_data.hpp"
#include "support/test_meshes.hpp"
#include "support/torus_mesh.hpp"

namespace pdesurf {
namespace {

/// "Never worse": a layout with more frames may fit worse than one with fewer by this fraction
/// of the RMS only (the sampling noise of the measure, and where both fits are at the mesh's
/// facets: the sphere's 60 and 120 frames fit to 0.0401 % and 0.0412 % with the fold-free
/// term, whose pull towards conformal frames costs a little RMS), never more.
constexpr double kNeverWorseSlack = 0.03;

/// Every frame corner lies on the mesh, so within the meshes' chord error of the exact
/// surface (below 1 - cos(π/24) ≈ 3.4e-3 of the radius for the meshes below); the middle of
/// a simplified triangle left off the mesh would lie 0.1 and more inside.
constexpr double kOnSurface = 5e-3;

/// The layouts checked for folds: about this many frames (the torus's layout folds at 150
/// frames, 7 of 12,150 samples split and 78 of 12,798 paired, where a frame spans a quarter
/// of the tube's girth).
constexpr std::uint32_t kFoldFreeFrames = 400;

/// A frame on a cylinder's side has a normal within 30° of horizontal (|n_z| < sin 30°), one
/// on a cap within 30° of vertical; a frame across a rim would lie between (about 45°).
constexpr double kSideways = 0.5, kUpright = 0.866;

/// The share of the surface samples a layout of paired triangles may fold over: none on the
/// sphere, 124 of 34,992 on the tube and 46 of 34,668 on the torus (docs/rebuild.md, Limits).
constexpr double kLayoutFoldAllowance = 0.005;

/// Fit iterations in the never-worse test on the closed-form shapes (the same for every
/// count; half the default, to keep the test quick).
constexpr std::uint32_t kQuickIterations = 15;

/// The issue's bound on a fitted model's folded area (a share of its area; the polygon peer
/// of the lion head folds 0.02 % at 0.18 % RMS). At kFoldFreeFrames the torus folds 0.006 %
/// after the fit; at 216 frames 0.16 % (docs/rebuild.md, Limits).
constexpr double kFittedFoldedArea = 1e-3;
/// The fitted models' RMS normal deviation (degrees) stays below this: the torus's is 4.7°,
/// the sphere's 2.9° (the polygon peers of the lion head and three_peaks at 0.07–0.18 %
/// RMS deviate 7.6–7.8° and 4.4–6.7°).
constexpr double kFittedNormalDeviation = 6.0;

/// The frame counts the tests ask for: three, growing.
constexpr std::uint32_t kCounts[] = {60, 120, 240};

struct Named {
  const char* name;
  Mesh mesh;
  int euler;                                      ///< V - E + F of the surface
  std::function<double(const Vec3&)> offSurface;  ///< distance from the exact surface
};

std::vector<Named> shapes() {
  // An open tube r(z) = 1 + ¼ sin(πz/2), z in [0, 2]: a cylinder's rings scaled (curved
  // along z, so no strip of it is flat).
  testing::CylinderOptions c;
  c.caps = false;
  c.segments = 48;
  c.rings = 24;
  auto radius = [](double z) { return 1.0 + 0.25 * std::sin(M_PI * z / 2); };
  Mesh tube = testing::cylinderMesh(c);
  for (std::size_t v = 0; v < tube.vertexCount(); ++v)
    for (int k = 0; k < 2; ++k)
      tube.positions[3 * v + k] *= static_cast<float>(radius(tube.positions[3 * v + 2]));
  return {{"sphere", testing::sphereMesh(1.0, 48, 24), 2,
           [](const Vec3& p) { return std::abs(p.norm() - 1.0); }},
          {"open tube", std::move(tube), 0,
           [=](const Vec3& p) { return std::abs(p.head<2>().norm() - radius(p.z())); }},
          {"torus", testing::torusMesh(1.0, 0.35, 64, 24), 0, [](const Vec3& p) {
             return std::abs(Eigen::Vector2d(p.head<2>().norm() - 1.0, p.z()).norm() - 0.35);
           }}};
}

/// Each frame side (corner, middle, corner) on one or two frames, and the Euler
/// characteristic of the frames' corner quads (corners, sides, frames).
int checkManifoldAndEuler(const VertexFrameModel& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;
  std::set<std::uint32_t> corners;
  for (const Frame& f : m.frames) {
    std::set<std::uint32_t> distinct(f.vertices.begin(), f.vertices.end());
    EXPECT_EQ(distinct.size(), 8u);
    for (int i = 0; i < 4; ++i) {
      corners.insert(f.vertices[2 * i]);
      ++sides[std::minmax(f.vertices[2 * i], f.vertices[(2 * i + 2) % 8])];
    }
  }
  for (const auto& [side, n] : sides) EXPECT_LE(n, 2) << side.first << "-" << side.second;
  return static_cast<int>(corners.size()) - static_cast<int>(sides.size()) +
         static_cast<int>(m.frames.size());
}

double rmsOf(const MeshDistance& d) {
  return std::sqrt(
      0.5 * (d.aToB.rmsRelative * d.aToB.rmsRelative + d.bToA.rmsRelative * d.bToA.rmsRelative));
}

TEST(AutoLayout, LaysValidFrameModelsOnClosedOpenAndGenusOneMeshesWithoutFolds) {
  for (const Named& s : shapes()) {
    SCOPED_TRACE(s.name);
    AutoLayoutOptions o;
    o.frames = kFoldFreeFrames;
    o.construction = QuadConstruction::SplitTriangles;
    const AutoLayout split = autoLayout(s.mesh, o, s.name);
    EXPECT_EQ(split.model.frames.size(), 3 * split.baseTriangles);  // three quads a triangle
    // The simplification stops at frames / 3 triangles, or one below (a collapse on a closed
    // mesh removes two).
    EXPECT_NEAR(double(split.baseTriangles), std::round(o.frames / 3.0), 1.0);
    o.construction = QuadConstruction::PairTriangles;  // the default
    const AutoLayout a = autoLayout(s.mesh, o, s.name);
    EXPECT_EQ(a.components, 1u);
    // frames / 2 triangles, four frames a pair and three an unpaired triangle.
    EXPECT_NEAR(double(a.baseTriangles), o.frames / 2.0, 1.0);
    EXPECT_GE(a.model.frames.size(), 2 * a.baseTriangles);
    EXPECT_LE(a.model.frames.size(), 3 * a.baseTriangles);
    for (const AutoLayout* layout : {&split, &a}) {
      // What model files accept, a manifold of frames with the input's topology.
      EXPECT_NO_THROW(parseVertexFrameModel(serializeVertexFrameModel(layout->model), s.name));
      EXPECT_EQ(checkManifoldAndEuler(layout->model), s.euler);
      for (const Frame& frame : layout->model.frames)
        for (int i = 0; i < 8; i += 2)
          EXPECT_LT(s.offSurface(layout->model.vertices[frame.vertices[i]]), kOnSurface);
      // The layout folds no sample over when split; pairs leave a few folded frames where
      // the surface turns fastest (measured at the fit's iteration 0).
      FitOptions measureOnly;
      measureOnly.maxIterations = 0;
      const FitMeasure m =
          fitVertexFrames(layout->model, s.mesh, measureOnly).iterations[0].measure;
      EXPECT_LE(m.foldedSamples, layout == &split ? 0.0 : kLayoutFoldAllowance * m.samples);
    }
  }
}

/// The fitted model's normals (its tessellation at 17 a side, as `compare` measures it) agree
/// with the mesh's: it faces the same way, folds below kFittedFoldedArea and deviates less
/// than kFittedNormalDeviation.
void expectAlmostNoFolds(const AutoFit& f, const Mesh& mesh) {
  const NormalDeviation n = normalDeviation(tessellate(solve(f.fit.model), {17}), mesh);
  EXPECT_FALSE(n.reversed);
  EXPECT_LT(n.foldedArea, kFittedFoldedArea);
  EXPECT_LT(n.rmsDegrees, kFittedNormalDeviation);
}

TEST(AutoLayout, FittedLayoutsFoldAlmostNothingOnTheClosedFormShapes) {
  // At the end of the fit (the fold-free term on, as by default), measured as `compare`
  // measures a model: its tessellation's normals against the mesh's.
  for (const Named& s : shapes()) {
    SCOPED_TRACE(s.name);
    AutoLayoutOptions o;
    o.frames = kFoldFreeFrames;
    FitOptions fit;
    fit.maxIterations = kQuickIterations;
    const AutoFit f = fitAutoLayout(s.mesh, o, fit, 17, {}, s.name);
    expectAlmostNoFolds(f, s.mesh);
    // The fit unfolds what the layout folded: no more folded samples than at its start.
    EXPECT_LE(f.fit.iterations.back().measure.foldedSamples,
              f.fit.iterations.front().measure.foldedSamples);
  }
}

TEST(AutoLayout, TheMushroomFittedFromTheDefaultLayoutFoldsBelowTheIssuesBound) {
  // A real scan: CGAL's mushroom.off at the default 200 frames folds 0.004 % of its area
  // and deviates 3.4° after the fit (docs/rebuild.md, "The automatic layout, fitted
  // fold-free"; the 8 × 8 grid folds 0.65 %).
  const Mesh mushroom = readMesh(testing::cgalData("mushroom.off"));
  const AutoFit f = fitAutoLayout(mushroom, {}, {}, 17, {}, "mushroom");
  expectAlmostNoFolds(f, mushroom);
}

TEST(AutoLayout, MoreFramesNeverFitWorse) {
  for (const Named& s : shapes()) {
    SCOPED_TRACE(s.name);
    double previous = 1e300;
    for (std::uint32_t n : kCounts) {
      AutoLayoutOptions o;
      o.frames = n;
      FitOptions fit;
      fit.maxIterations = kQuickIterations;
      const AutoFit f = fitAutoLayout(s.mesh, o, fit, 17, {}, s.name);
      const double rms = rmsOf(f.distance);
      EXPECT_LE(rms, previous * (1 + kNeverWorseSlack)) << n << " frames";
      previous = rms;
    }
  }
}

TEST(AutoLayout, TwoComponentsMakeOneModelCoveringBoth) {
  testing::CylinderOptions c;
  c.offset = Eigen::Vector3d(4, 0, 0);
  const Mesh two = testing::merged(testing::sphereMesh(1.0, 32, 16), testing::cylinderMesh(c));
  AutoLayoutOptions o;
  o.frames = 200;
  o.construction = QuadConstruction::SplitTriangles;
  const AutoLayout a = autoLayout(two, o, "two");
  EXPECT_EQ(a.components, 2u);
  // Frames on both: some vertex near the sphere, some on the capped cylinder.
  int onSphere = 0, onCylinder = 0;
  for (const Vec3& p : a.model.vertices) (p.x() < 2 ? onSphere : onCylinder) += 1;
  EXPECT_GT(onSphere, 0);
  EXPECT_GT(onCylinder, 0);
  // The cylinder's rims are creases (90°): they stay on frame edges.
  EXPECT_GT(a.creaseEdges, 0u);
  const FitResult fit = fitVertexFrames(a.model, two);
  EXPECT_EQ(fit.iterations.front().measure.foldedSamples, 0u);
  EXPECT_LT(fit.iterations.back().measure.rms(), fit.iterations.front().measure.rms());
}

TEST(AutoLayout, KeepsACylindersRimsOnFrameEdges) {
  // A capped cylinder: its two rims are creases (90°). A frame on the side faces sideways, a
  // frame on a cap up or down; a frame spanning a rim would face half way between.
  testing::CylinderOptions c;
  c.segments = 64;
  const Mesh cylinder = testing::cylinderMesh(c);
  for (QuadConstruction q : {QuadConstruction::SplitTriangles, QuadConstruction::PairTriangles}) {
    AutoLayoutOptions o;
    o.frames = 120;
    o.construction = q;
    const AutoLayout a = autoLayout(cylinder, o, "cylinder");
    EXPECT_EQ(a.creaseEdges, 2u * 64u);  // both rims, every edge of them
    int sideFrames = 0, capFrames = 0;
    for (const Frame& f : a.model.frames) {
      const auto& v = f.vertices;
      const Vec3 n = (a.model.vertices[v[4]] - a.model.vertices[v[0]])
                         .cross(a.model.vertices[v[6]] - a.model.vertices[v[2]])
                         .normalized();
      EXPECT_TRUE(std::abs(n.z()) < kSideways || std::abs(n.z()) > kUpright)
          << "a frame spans a rim: its normal " << n.transpose();
      sideFrames += std::abs(n.z()) < kSideways;
      capFrames += std::abs(n.z()) > kUpright;
    }
    EXPECT_GT(sideFrames, 0);
    EXPECT_GT(capFrames, 0);
  }
}

/// The pillow cube of the crease test: 16 × 16 quads a face, each face bulging by 0.1, so
/// that its edges are creases of 67°–90° and its faces are curved (no face is one frame).
constexpr int kPillowQuads = 16;
constexpr double kPillowBulge = 0.1;
/// A frame within one face of the pillow cube faces within 30° of that face's axis (the
/// faces tilt by at most atan(2 × 0.1) ≈ 11°); one spanning an edge faces about 45° away.
constexpr double kWithinAFace = 0.866;
/// The fitted pillow cube's RMS normal deviation (degrees) and RMS distance (of the
/// diagonal) stay below these: with the edges on frame edges 1.2° and 0.017 % (96 frames
/// asked for, 110 made); without the crease rule 24 frames span the edges and round them
/// off, 4.7° and 0.047 % (docs/rebuild.md, "Creases and boundaries stay on edges").
constexpr double kPillowNormalDeviation = 2.5, kPillowRms = 3e-4;

/// The frames of `m` whose corner quad faces no axis within kWithinAFace: those that span
/// an edge of the pillow cube.
int framesAcrossAnEdge(const VertexFrameModel& m) {
  int across = 0;
  for (const Frame& f : m.frames) {
    const auto& v = f.vertices;
    const Vec3 n = (m.vertices[v[4]] - m.vertices[v[0]])
                       .cross(m.vertices[v[6]] - m.vertices[v[2]])
                       .normalized();
    across += n.cwiseAbs().maxCoeff() < kWithinAFace;
  }
  return across;
}

TEST(AutoLayout, KeepsAPillowCubesEdgesOnFrameEdgesAndFitsThemSharp) {
  // The crease rule (creases stay on the simplified mesh's edges and no pair of triangles is
  // joined across one) keeps every frame within one face, and the fit then follows the
  // edges: the normals deviate little and the RMS stays low.
  const Mesh cube = testing::pillowCubeMesh(kPillowQuads, kPillowBulge);
  AutoLayoutOptions o;
  o.frames = 96;
  const AutoLayout a = autoLayout(cube, o, "pillow cube");
  EXPECT_EQ(a.creaseEdges, 12u * kPillowQuads);  // every edge of the cube, nothing else
  EXPECT_EQ(framesAcrossAnEdge(a.model), 0);
  FitOptions fit;
  fit.maxIterations = kQuickIterations;
  const AutoFit f = fitAutoLayout(cube, o, fit, 17, {}, "pillow cube");
  EXPECT_LT(f.normals.rmsDegrees, kPillowNormalDeviation);
  EXPECT_LT(rmsOf(f.distance), kPillowRms);
  // The check sees frames across the edges where the rule is off (no edge sharp enough to be
  // a crease): pairs of triangles on two faces become frames across the edge.
  o.creaseAngle = 180.0;
  const AutoLayout without = autoLayout(cube, o, "pillow cube");
  EXPECT_EQ(without.creaseEdges, 0u);
  EXPECT_GT(framesAcrossAnEdge(without.model), 0);
}

TEST(AutoLayout, BadMeshesAreRefusedWithTheReason) {
  auto refused = [](const Mesh& m, const std::string& what) {
    try {
      autoLayout(m, {}, "bad.off");
      ADD_FAILURE() << "not refused: " << what;
    } catch (const LayoutError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused(Mesh{}, "bad.off: the mesh has no triangles");
  // Three triangles on one edge.
  testing::MeshBuilder b;
  for (auto [x, y, z] :
       {std::array{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., -1., 0.}, {0., 0., 1.}})
    b.vertex(x, y, z);
  b.triangle(0, 1, 2);
  b.triangle(1, 0, 3);
  b.triangle(0, 1, 4);
  refused(b.mesh(), "triangle 2 (0 1 4) cannot join the others");
  // Only triangles without area.
  testing::MeshBuilder flat;
  for (int i = 0; i < 3; ++i) flat.vertex(i, 0, 0);
  flat.triangle(0, 1, 2);
  flat.triangle(0, 0, 1);
  refused(flat.mesh(), "none of the mesh's 2 triangles has an area");
}

TEST(AutoLayout, TargetRmsSearchReachesTheTargetWithTheSmallestLayoutItTried) {
  const Mesh torus = testing::torusMesh(1.0, 0.35, 64, 24);
  TargetSearchOptions o;
  o.targetRms = 1e-3;
  o.firstFrames = 24;
  std::vector<std::pair<std::size_t, double>> trials;  // frames made, worse RMS
  o.onTrial = [&](std::uint32_t, const AutoFit& f) {
    trials.emplace_back(f.layout.model.frames.size(), f.worseRms());
  };
  const TargetSearch s = searchTargetRms(torus, o, "torus");
  ASSERT_TRUE(s.reached);
  EXPECT_EQ(s.best.grid, 0u);  // a torus is no disk: no grid is tried
  EXPECT_LE(s.best.worseRms(), o.targetRms);
  EXPECT_EQ(s.trials, trials.size());
  // Every trial smaller than the answer missed the target.
  for (const auto& [frames, rms] : trials)
    if (frames < s.best.layout.model.frames.size()) EXPECT_GT(rms, o.targetRms) << frames;
  EXPECT_GE(trials.size(), 2u);  // the first count missed: it grew, or bisected
}

/// A sphere with bumps, r = 1 + 0.08 sin 6x sin 6y sin 6z on the unit directions (64 × 32):
/// the benchmark's levels 0.4 / 0.2 / 0.1 % take 22, 36 and 52 frames (9.7°, 8.3° and 6.4°
/// RMS normal deviation, within the default bound), each search a few seconds.
Mesh bumpySphere() {
  Mesh m = testing::sphereMesh(1.0, 64, 32);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    float* p = &m.positions[3 * v];
    const double r =
        1.0 + 0.08 * std::sin(6.0 * p[0]) * std::sin(6.0 * p[1]) * std::sin(6.0 * p[2]);
    for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(r * p[k]);
  }
  return m;
}

TEST(AutoLayout, TighterTargetsNeverGetFewerFramesAndEachStopsOneStepAboveAMiss) {
  // Issue 25's benchmark levels. The search grows from the fewest frames through counts that
  // depend on the mesh alone, then bisects: a looser level never gets more frames than a
  // tighter one (the search that started at 200 gave the pig 442 frames at 0.4 % and 200 at
  // 0.2 %), and each answer has a count within `precision` below it that missed (so a loose
  // level does not overshoot by more than one step).
  const Mesh bumpy = bumpySphere();
  std::size_t previous = 0;
  for (const double target : {4e-3, 2e-3, 1e-3}) {
    SCOPED_TRACE(target);
    TargetSearchOptions o;
    o.targetRms = target;
    struct Trial {
      std::uint32_t asked;
      std::size_t made;
      bool reached;
    };
    std::vector<Trial> trials;
    o.onTrial = [&](std::uint32_t asked, const AutoFit& f) {
      trials.push_back({asked, f.layout.model.frames.size(), checkTarget(f, o).all()});
    };
    const TargetSearch s = searchTargetRms(bumpy, o, "bumpy sphere");
    ASSERT_TRUE(s.reached);
    EXPECT_LE(s.best.worseRms(), target);
    EXPECT_LE(s.best.normals.foldedArea, o.maxFoldedArea);
    EXPECT_LE(s.best.normals.rmsDegrees, o.maxNormalDeviation);
    const std::size_t frames = s.best.layout.model.frames.size();
    EXPECT_GE(frames, previous);
    previous = frames;
    // The answer's count, and the miss just below it: it was tried (as asked for, or as the
    // frames a smaller request made), and missed.
    std::uint32_t asked = 0;
    for (const Trial& t : trials)
      if (t.reached && t.made == frames) asked = t.asked;
    ASSERT_GT(s.missedBelow, 0u) << "the first count reached " << target;
    EXPECT_LE(asked, s.missedBelow * (1.0 + o.precision));
    bool missTried = false;
    for (const Trial& t : trials)
      if ((t.asked == s.missedBelow || t.made == s.missedBelow) && !t.reached) missTried = true;
    EXPECT_TRUE(missTried);
    // No trial with fewer frames than the answer reached the level.
    for (const Trial& t : trials)
      if (t.made < frames) EXPECT_FALSE(t.reached) << t.made;
  }
}

/// The normal bound of the next test (degrees): below what the bumpy sphere's smallest
/// layouts that reach 0.4 % within the fold bound deviate (24 frames 9.2°, 36 frames 8.3°),
/// above what larger ones reach (42 frames 7.8°, 52 frames 6.4°).
constexpr double kBumpyNormalBound = 8.0;

TEST(AutoLayout, TargetRmsSearchRefusesLayoutsWhoseNormalsDeviateBeyondTheBound) {
  // Issue 25: the bear's 56-frame model reached 0.2 % but its ears were flat flaps (13.7°
  // RMS normal deviation against 7.8° at 118 frames). On the bumpy sphere at 0.4 % a layout
  // reaches the RMS within the fold bound before it follows the bumps' slopes: the normal
  // bound refuses it, and the answer is larger and within the bound.
  const Mesh bumpy = bumpySphere();
  TargetSearchOptions o;
  o.targetRms = 4e-3;
  o.maxNormalDeviation = kBumpyNormalBound;
  struct Trial {
    std::size_t frames;
    TargetCheck met;
    double degrees;
  };
  std::vector<Trial> trials;
  o.onTrial = [&](std::uint32_t, const AutoFit& f) {
    trials.push_back({f.layout.model.frames.size(), checkTarget(f, o), f.normals.rmsDegrees});
  };
  const TargetSearch s = searchTargetRms(bumpy, o, "bumpy sphere");
  ASSERT_TRUE(s.reached);
  EXPECT_EQ(s.stop, TargetSearch::Stop::Reached);
  EXPECT_LE(s.best.normals.rmsDegrees, kBumpyNormalBound);
  EXPECT_LE(s.best.worseRms(), o.targetRms);
  // A smaller trial reached the RMS within the fold bound and was refused for its normals
  // alone: without the bound it would have been the answer.
  const std::size_t best = s.best.layout.model.frames.size();
  bool refusedForNormals = false;
  for (const Trial& t : trials) {
    if (t.frames < best) EXPECT_FALSE(t.met.all()) << t.frames;
    if (t.frames < best && t.met.rms && t.met.folds) {
      EXPECT_GT(t.degrees, kBumpyNormalBound);
      refusedForNormals = true;
    }
  }
  EXPECT_TRUE(refusedForNormals);
}

/// The noisy sphere's radial noise (of the radius, uniform in ±): its facets' normals scatter
/// by several degrees, which no smooth model follows.
constexpr double kNoise = 0.005;
/// A bound below the noisy sphere's floor of normal deviation (degrees: its layouts of 30 and
/// 66 frames deviate 5.7° and 5.4°) ...
constexpr double kBelowNoiseFloor = 1.0;
/// ... and the most frames the search may try before it sees the deviation stall (it stops
/// at 66; the search's own limit is 20,000).
constexpr std::size_t kStallFrames = 400;

/// The unit sphere (64 × 32) with each vertex moved along its radius by up to ±kNoise (a
/// fixed sequence of pseudo-random numbers): a scan's noise.
Mesh noisySphere() {
  Mesh m = testing::sphereMesh(1.0, 64, 32);
  std::mt19937 random(25);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const double r = 1.0 + kNoise * (2.0 * double(random()) / double(random.max()) - 1.0);
    for (int k = 0; k < 3; ++k)
      m.positions[3 * v + k] = static_cast<float>(r * m.positions[3 * v + k]);
  }
  return m;
}

TEST(AutoLayout, TargetRmsSearchStopsGrowingWhereTheNormalDeviationStallsAndSaysSo) {
  // A bound below the deviation the noise sets: the layouts reach the RMS, the deviation
  // falls as they grow, then stops falling; the search stops there (not at 20,000 frames),
  // says the normal bound was missed, and keeps the layout before the stalling step.
  const Mesh noisy = noisySphere();
  TargetSearchOptions o;
  o.targetRms = 4e-3;
  o.maxNormalDeviation = kBelowNoiseFloor;
  std::vector<std::pair<std::size_t, double>> trials;  // frames made, degrees
  o.onTrial = [&](std::uint32_t, const AutoFit& f) {
    trials.emplace_back(f.layout.model.frames.size(), f.normals.rmsDegrees);
  };
  const TargetSearch s = searchTargetRms(noisy, o, "noisy sphere");
  EXPECT_FALSE(s.reached);
  EXPECT_EQ(s.stop, TargetSearch::Stop::NormalsStalled);
  EXPECT_TRUE(s.met.rms && s.met.folds && !s.met.normals);
  ASSERT_GE(trials.size(), 2u);
  double least = 1e300;
  for (const auto& [frames, degrees] : trials) {
    EXPECT_LE(frames, kStallFrames);
    least = std::min(least, degrees);
  }
  // The answer is the layout before the last step, which lowered the deviation by less than
  // kNormalStall: within that of the least deviation any trial reached.
  EXPECT_LT(s.best.layout.model.frames.size(), trials.back().first);
  EXPECT_LE(s.best.normals.rmsDegrees, least / (1.0 - kNormalStall));
}

/// A storage cap far below the default's 2× the mesh: 0.04× the smooth sphere's 109 KB, about
/// 35 frames, where its models' deviation still falls fast (12, 26, 54 frames: 3.9°, 2.4°,
/// 2.2°, the facets' floor; the stall would stop the search past 54) ...
constexpr double kSmallStorageRatio = 0.04;
/// ... and a normal bound that no layout meets: the cap, not the bound, stops the search.
constexpr double kUnreachableDeviation = 0.25;

TEST(AutoLayout, PastTheRmsTheSearchGrowsNoModelHeavierThanTheStorageCapAndSaysSo) {
  // The layouts reach the RMS at once; the normal bound would grow them on, but no layout
  // whose model takes more than maxStorageRatio times the mesh's bytes is tried: the largest
  // under the cap is tried last, and the search stops there (StorageLimit) with the closest.
  const Mesh sphere = testing::sphereMesh(1.0, 64, 32);
  TargetSearchOptions o;
  o.targetRms = 4e-3;
  o.maxNormalDeviation = kUnreachableDeviation;
  o.maxStorageRatio = kSmallStorageRatio;
  o.minStorageCap = 0;  // the sphere's 109 KB is below kMinStorageCap
  const double cap = kSmallStorageRatio * double(storageBytes(sphere));
  std::vector<std::pair<std::uint32_t, std::size_t>> trials;  // asked for, layout bytes
  o.onTrial = [&](std::uint32_t requested, const AutoFit& f) {
    if (f.foldsPrevented) return;  // the same layout again
    trials.emplace_back(requested, storageBytes(f.layout.model));
  };
  const TargetSearch s = searchTargetRms(sphere, o, "sphere");
  EXPECT_FALSE(s.reached);
  EXPECT_EQ(s.stop, TargetSearch::Stop::StorageLimit);
  EXPECT_TRUE(s.met.rms && s.met.folds && !s.met.normals);
  ASSERT_GE(trials.size(), 2u);
  // Every trial after the first (which reached the RMS) is under the cap ...
  for (std::size_t k = 1; k < trials.size(); ++k) EXPECT_LE(double(trials[k].second), cap);
  // ... the last is the count shrunk to the cap, not the next in the growth sequence, whose
  // model would have been over it ...
  const std::uint32_t before = trials[trials.size() - 2].first;
  AutoLayoutOptions next = o.layout;
  next.frames = static_cast<std::uint32_t>(std::ceil(before * o.growth));
  EXPECT_GT(double(storageBytes(autoLayout(sphere, next, "sphere").model)), cap);
  EXPECT_LT(trials.back().first, next.frames);
  EXPECT_GT(trials.back().first, before);
  // ... and the answer is the closest: the least deviation of the trials within RMS and folds.
  EXPECT_EQ(s.best.layout.model.frames.size(), autoLayout(
                                                   sphere,
                                                   [&] {
                                                     AutoLayoutOptions l = o.layout;
                                                     l.frames = trials.back().first;
                                                     return l;
                                                   }(),
                                                   "sphere")
                                                   .model.frames.size());
}

/// A target no smooth model of a coarse polyhedron reaches (a billionth of the diagonal).
constexpr double kUnreachableRms = 1e-9;

TEST(AutoLayout, WhereTheLayoutStopsGrowingTheSearchStopsWithoutFittingItAgain) {
  // A coarse sphere (8 × 4, 48 triangles): its layouts grow until no triangle is left to
  // collapse (96 frames: the triangles paired, four frames a pair), then a larger count makes
  // the same layout, which the search does not fit a second time.
  const Mesh coarse = testing::sphereMesh(1.0, 8, 4);
  TargetSearchOptions o;
  o.targetRms = kUnreachableRms;
  o.tryGrid = false;
  std::map<std::size_t, int> plainFits;  // frames made: plain fits of that layout
  o.onTrial = [&](std::uint32_t, const AutoFit& f) {
    if (!f.foldsPrevented) ++plainFits[f.layout.model.frames.size()];
  };
  const TargetSearch s = searchTargetRms(coarse, o, "coarse sphere");
  EXPECT_FALSE(s.reached);
  EXPECT_EQ(s.stop, TargetSearch::Stop::LayoutStopped);
  ASSERT_FALSE(plainFits.empty());
  AutoLayoutOptions all = o.layout;  // the largest layout the mesh gives
  all.frames = o.maxFrames;
  EXPECT_EQ(plainFits.rbegin()->first,
            autoLayout(coarse, all, "coarse sphere").model.frames.size());
  for (const auto& [frames, fits] : plainFits) EXPECT_EQ(fits, 1) << frames << " frames";
}

/// The fold bound of the search test below: no folded area at all. With the Jacobian
/// barrier the mushroom's layouts fold far below the issue's bound (the 18-frame one folded
/// 0.105 % before it; now the 22- and 26-frame ones that reach 0.2 % fold 0.0011 % and
/// 0.0006 %, the 37-frame one nothing), so the test asks for none to see the bound choose.
constexpr double kTightFoldBound = 0.0;

TEST(AutoLayout, TargetRmsSearchReturnsNoModelFoldedBeyondTheBound) {
  // CGAL's mushroom at 0.2 %: a layout that reaches the RMS but folds more than the bound is
  // refused, and the same layout fitted with folding steps refused, or a larger layout, is
  // taken (docs/rebuild.md, "A target accuracy"). Started at 18 frames to keep it quick.
  const Mesh mushroom = readMesh(testing::cgalData("mushroom.off"));
  TargetSearchOptions o;
  o.targetRms = 2e-3;
  o.maxFoldedArea = kTightFoldBound;
  o.firstFrames = 18;
  struct Trial {
    std::size_t frames;
    double rms, folded;
  };
  std::vector<Trial> trials;
  o.onTrial = [&](std::uint32_t, const AutoFit& f) {
    trials.push_back({f.layout.model.frames.size(), f.worseRms(), f.normals.foldedArea});
  };
  const TargetSearch s = searchTargetRms(mushroom, o, "mushroom");
  ASSERT_TRUE(s.reached);
  EXPECT_LE(s.best.worseRms(), o.targetRms);
  EXPECT_LE(s.best.normals.foldedArea, o.maxFoldedArea);
  // Every smaller trial missed the RMS or folded beyond the bound, and one of them (or the
  // same layout's plain fit, before the fit that refuses folding steps) reached the RMS
  // folded: the bound, not the RMS, chose the answer.
  const std::size_t best = s.best.layout.model.frames.size();
  bool refusedForFolds = false;
  for (const Trial& t : trials) {
    if (t.frames < best) EXPECT_TRUE(t.rms > o.targetRms || t.folded > o.maxFoldedArea) << t.frames;
    if (t.frames <= best && t.rms <= o.targetRms && t.folded > o.maxFoldedArea)
      refusedForFolds = true;
  }
  EXPECT_TRUE(refusedForFolds);
}

/// Before the Jacobian barrier the default fit of 100 frames asked for folded 0.137 % of
/// three_peaks (at 0.102 / 0.102 % RMS, 9.5°) and 1.89 % of the pig (0.264 / 0.172 %,
/// 23.4°); with it 0.024 % (0.103 / 0.103 %, 8.0°) and 0.059 % (0.156 / 0.158 %, 12.5°)
/// (docs/rebuild.md, "The Jacobian barrier"). Both now fold below the issue's bound
/// (kMaxFoldedArea), deviate less than these (degrees) ...
constexpr double kBarrierDeviation[] = {9.0, 15.0};
/// ... and reach at least this RMS both ways (of the diagonal; three_peaks' 0.102 % and the
/// pig's 0.264 % before).
constexpr double kBarrierRms[] = {1.1e-3, 2e-3};

TEST(AutoLayout, TheJacobianBarrierUnfoldsThreePeaksAndThePig) {
  const char* names[] = {"three_peaks.off", "pig.off"};
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE(names[i]);
    const Mesh mesh = readMesh(testing::cgalData(names[i]));
    AutoLayoutOptions o;
    o.frames = 100;
    const AutoFit f = fitAutoLayout(mesh, o, {}, 17, {}, names[i]);
    EXPECT_LT(f.normals.foldedArea, kMaxFoldedArea);
    EXPECT_LT(f.normals.rmsDegrees, kBarrierDeviation[i]);
    EXPECT_LT(f.worseRms(), kBarrierRms[i]);
  }
}

/// CGAL's boeing.off (122 components, many thin) at 60 frames asked for: the fit shrinks one
/// thin part's frame to a point, which no sample then weighs; without the fit's proximal
/// term the singular step flung it 2,000 units away (Hausdorff 74 diagonals). Every point of
/// the model must stay near the mesh: this bound, 10 % of the diagonal, is twice the largest
/// model-to-mesh distance the fixed fit leaves (1.3 %) and far below the failure ...
constexpr double kBoeingMaxDistance = 0.10;
/// ... and the fit still fits: RMS both ways at most 1 % (it reaches 0.13 / 0.68 %).
constexpr double kBoeingRms = 0.01;

TEST(AutoLayout, AFrameTheFitShrinksToAPointStaysOnTheMesh) {
  const Mesh boeing = readMesh(testing::cgalData("boeing.off"));
  AutoLayoutOptions o;
  o.frames = 60;
  const AutoFit f = fitAutoLayout(boeing, o, {}, 9, {}, "boeing");
  EXPECT_LT(f.distance.aToB.maxRelative, kBoeingMaxDistance);
  EXPECT_LT(f.worseRms(), kBoeingRms);
}

/// The normal-alignment term (FitOptions::normalWeight) on the bumpy sphere at kNormalFrames
/// frames asked for: the RMS normal deviation (as `compare` measures it) with the term at
/// kNormalWeight (the target search's default; a plain fit's is 0) is below the fit without it (ν =
/// 0) by at least the factor kNormalGain (measured: 5.61° without, 5.16° with, 1.088; at 24, 36 and
/// 60 frames 1.03–1.07: the sphere is smooth and finely meshed, so its seams kink little; the CGAL
/// meshes of docs/rebuild.md, "Normals", gain 1.09–1.21) ...
constexpr std::uint32_t kNormalFrames = 120;
constexpr double kNormalGain = 1.05;
/// ... at an RMS both ways no higher than this factor of the fit without it (measured 0.89:
/// 0.055 % against 0.062 %).
constexpr double kNormalRmsCost = 1.1;

TEST(AutoLayout, TheNormalTermLowersTheNormalDeviation) {
  const Mesh mesh = bumpySphere();
  AutoLayoutOptions o;
  o.frames = kNormalFrames;
  FitOptions off;
  off.normalWeight = 0.0;
  FitOptions on;
  on.normalWeight = kNormalWeight;
  const AutoFit without = fitAutoLayout(mesh, o, off, 17, {}, "bumpy sphere");
  const AutoFit with = fitAutoLayout(mesh, o, on, 17, {}, "bumpy sphere");
  EXPECT_LT(with.normals.rmsDegrees * kNormalGain, without.normals.rmsDegrees);
  EXPECT_LT(rmsOf(with.distance), kNormalRmsCost * rmsOf(without.distance));
  EXPECT_LT(with.normals.foldedArea, kMaxFoldedArea);
}

/// With the normal-alignment term on (kNormalWeight), more frames still fit the bumpy sphere
/// closer (measured: 0.216 %, 0.087 %, 0.055 % RMS at 30, 60, 120 frames asked for).
TEST(AutoLayout, MoreFramesFitCloserWithTheNormalTerm) {
  const Mesh mesh = bumpySphere();
  double previous = 1e300;
  for (std::uint32_t n : {30u, 60u, 120u}) {
    AutoLayoutOptions o;
    o.frames = n;
    FitOptions on;
    on.normalWeight = kNormalWeight;
    const AutoFit f = fitAutoLayout(mesh, o, on, 17, {}, "bumpy sphere");
    EXPECT_LT(rmsOf(f.distance), previous) << n << " frames";
    previous = rmsOf(f.distance);
  }
}

/// The target search fits with the normal-alignment term (TargetSearchOptions's default
/// kNormalWeight) because it lets a smaller layout meet the bounds where the normal bound holds
/// the layout up: the pig at 0.2 % (an 891-triangle polyhedron whose facets keep the normal
/// deviation high) is reached with fewer frames with the term than without (measured: 163
/// against 345 frames, 9.6° each; docs/rebuild.md, "A target accuracy").
TEST(AutoLayout, TheNormalTermLetsTheSearchStopSmaller) {
  const Mesh pig = readMesh(testing::cgalData("pig.off"));
  TargetSearchOptions with;
  with.targetRms = 0.002;
  TargetSearchOptions without = with;
  without.fit.normalWeight = 0.0;
  const TargetSearch a = searchTargetRms(pig, with, "pig");
  const TargetSearch b = searchTargetRms(pig, without, "pig");
  ASSERT_TRUE(a.reached);
  ASSERT_TRUE(b.reached);
  EXPECT_LT(a.best.fit.model.frames.size(), b.best.fit.model.frames.size());
}

/// On a disk the search tries the n × n grids too (TargetSearchOptions::tryGrid) and answers
/// with the smaller model that meets the target: three_peaks, a smooth height field, is met at
/// 0.2 % by the 5 × 5 grid (25 frames, 3,243 bytes, 8.9°) where the automatic layout needs 45
/// frames (5,387 bytes). The grid answer meets every criterion, takes fewer bytes than the
/// automatic layout's answer (the search without grids), and every grid tried with fewer
/// frames missed the target.
TEST(AutoLayout, OnADiskTheSearchAnswersWithTheGridWhereItIsSmaller) {
  const Mesh peaks = readMesh(testing::cgalData("three_peaks.off"));
  TargetSearchOptions with;
  with.targetRms = 0.002;
  std::vector<std::pair<std::uint32_t, bool>> grids;  // side, target met
  with.onTrial = [&](std::uint32_t, const AutoFit& f) {
    if (f.grid > 0) grids.emplace_back(f.grid, checkTarget(f, with).all());
  };
  TargetSearchOptions without = with;
  without.tryGrid = false;
  without.onTrial = nullptr;
  const TargetSearch a = searchTargetRms(peaks, with, "three_peaks");
  const TargetSearch b = searchTargetRms(peaks, without, "three_peaks");
  ASSERT_TRUE(a.reached);
  ASSERT_TRUE(b.reached);
  EXPECT_EQ(b.best.grid, 0u);
  ASSERT_GT(a.best.grid, 0u);
  EXPECT_EQ(a.best.fit.model.frames.size(), std::size_t{a.best.grid} * a.best.grid);
  EXPECT_LT(storageBytes(a.best.fit.model), storageBytes(b.best.fit.model));
  ASSERT_FALSE(grids.empty());
  for (const auto& [side, met] : grids) {
    EXPECT_LT(std::size_t{side} * side, b.best.fit.model.frames.size());  // fewer frames only
    if (side < a.best.grid) EXPECT_FALSE(met) << side;
  }
}

/// On a creased disk the grids must meet the same target, which a grid that smooths a sharp
/// crease over misses: CGAL's open_cube.off (a cube without its top, one boundary loop, its
/// 90° edges kept on frame edges by the automatic layout, whose flat frames fit it exactly)
/// is answered by the automatic layout; the grids with fewer frames were tried and missed
/// the RMS (3 × 3: 2.85 % mesh to model). kExactRms: the automatic model's worse one-way RMS,
/// 0 to the digits printed, far below any grid's.
constexpr double kExactRms = 1e-4;

TEST(AutoLayout, OnACreasedDiskTheGridsDoNotSmoothTheCreasesOver) {
  const Mesh cube = readMesh(testing::cgalData("open_cube.off"));
  TargetSearchOptions o;
  o.targetRms = 0.004;
  std::size_t grids = 0;
  o.onTrial = [&](std::uint32_t, const AutoFit& f) { grids += f.grid > 0; };
  const TargetSearch s = searchTargetRms(cube, o, "open_cube");
  ASSERT_TRUE(s.reached);
  EXPECT_GT(grids, 0u);
  EXPECT_EQ(s.best.grid, 0u);
  EXPECT_GT(s.best.layout.creaseEdges, 0u);
  EXPECT_LT(s.best.worseRms(), kExactRms);
}

TEST(AutoLayout, MoreFramesNeverFitThreePeaksWorse) {
  const Mesh peaks = readMesh(testing::cgalData("three_peaks.off"));
  double previous = 1e300;
  for (std::uint32_t n : kCounts) {
    AutoLayoutOptions o;
    o.frames = n;
    const AutoFit f = fitAutoLayout(peaks, o, {}, 17, {}, "three_peaks");
    const double rms = rmsOf(f.distance);
    EXPECT_LE(rms, previous * (1 + kNeverWorseSlack)) << n << " frames";
    previous = rms;
  }
}

}  // namespace
}  // namespace pdesurf
