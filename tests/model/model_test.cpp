// The model layer (include/pdesurf/model.hpp) and the one session type for every model.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

#include "pdesurf/method.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/examples.hpp"

namespace pdesurf {
namespace {

using testing::example;
using testing::exampleFiles;

/// Whether two meshes hold the same bytes.
bool sameMesh(const Mesh& a, const Mesh& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return same(a.positions, b.positions) && same(a.normals, b.normals) &&
         same(a.indices, b.indices) && same(a.patchIds, b.patchIds);
}

/// The engine's own mesh of a solved model, by its type: what the model layer must give.
Mesh engineMesh(const SolvedModel& solved, std::uint32_t resolution) {
  if (const auto* s = solved.surface().as<VertexFrameSurface>())
    return tessellate(*s, {resolution});
  if (const auto* s = solved.surface().as<SolvedSpectral>()) return tessellate(*s, resolution);
  return tessellate(solved.surface().get<SolvedBSplinePde>(), resolution);
}

TEST(Model, EveryExampleSolvesTessellatesAndSamplesThroughOneType) {
  constexpr std::uint32_t kResolution = 9, kGrid = 3;
  for (const std::string& path : exampleFiles()) {
    SCOPED_TRACE(path);
    const SolvedModel solved = loadAndSolve(path);
    EXPECT_EQ(solved.type(), std::string(modelTypeName(loadModel(path))));
    EXPECT_TRUE(sameMesh(tessellate(solved, {kResolution}), engineMesh(solved, kResolution)));
    const std::vector<PatchSamples> samples = sample(solved, kGrid);
    ASSERT_FALSE(samples.empty());
    for (std::size_t k = 0; k < samples.size(); ++k) {
      EXPECT_EQ(samples[k].index, k);
      EXPECT_EQ(samples[k].points.size(), std::size_t{kGrid} * kGrid);
    }
    const ModelReport r = report(solved);
    EXPECT_FALSE(r.summary.empty());
    EXPECT_FALSE(r.quality.empty());
    // Every type's info names the model's file, as text and as JSON.
    EXPECT_NE(infoText(solved, false).find(path), std::string::npos);
    EXPECT_NE(infoText(solved, true).find("\"model\""), std::string::npos);
    // The NURBS faces cover every patch: one face per patch at least.
    EXPECT_GE(toNurbs(solved).faces.size(), solved.frames() ? solved.frames()->patches.size() : 1);
  }
}

TEST(Model, EachMethodNamesItsPatches) {
  // What `pdesurf sample` writes a patch's index under: vertex frames' patches are frames.
  EXPECT_STREQ(loadAndSolve(example("mug.json")).model().method().patchName(), "frame");
  for (const char* file : {"shell.json", "vase-sections.json", "bspline-blend.json"})
    EXPECT_STREQ(loadAndSolve(example(file)).model().method().patchName(), "patch") << file;
}

TEST(Model, OverlayDrawsControlPolygonsOfBSplinesAndNothingForFrames) {
  const SolvedModel bspline = loadAndSolve(example("bspline-blend.json"));
  std::size_t lines = 0;
  for (const BSplineSurface& piece : bspline.surface().get<SolvedBSplinePde>().pieces)
    lines += piece.net().nu + 1 + piece.net().nv + 1;
  EXPECT_EQ(overlay(bspline).curves.size(), lines);
  EXPECT_TRUE(overlay(bspline).spines.empty());
  const ModelOverlay frames = overlay(loadAndSolve(example("mug.json")));
  EXPECT_TRUE(frames.curves.empty() && frames.spines.empty());
  const SolvedModel shell = loadAndSolve(example("shell.json"));
  EXPECT_EQ(overlay(shell).spines.size(), shell.spectral()->patchCount());
}

TEST(Model, SeedFrameOutOfRangeIsRefusedForFramesOnly) {
  const AnyModel mug = loadModel(example("mug.json"));
  const std::size_t frames = mug.get<VertexFrameModel>().frames.size();
  SolveOptions options;
  options.seedFrame = static_cast<std::uint32_t>(frames);
  EXPECT_THROW(checkSolveOptions(mug, options), InvalidArgument);
  options.seedFrame = static_cast<std::uint32_t>(frames - 1);
  EXPECT_NO_THROW(checkSolveOptions(mug, options));
  options.seedFrame = 1000;  // other types have no seed frame to check
  EXPECT_NO_THROW(checkSolveOptions(loadModel(example("shell.json")), options));
}

TEST(Model, TessellatorKeepsItsLayoutUntilTheTrianglesChange) {
  const SolvedModel shell = loadAndSolve(example("shell.json"));
  const SolvedModel mug = loadAndSolve(example("mug.json"));
  ModelTessellator t;
  t.tessellate(shell, {9});
  const std::uint64_t first = t.layoutVersion();
  EXPECT_TRUE(sameMesh(t.tessellate(shell, {9}), tessellate(shell, {9})));
  EXPECT_EQ(t.layoutVersion(), first);
  t.tessellate(shell, {11});
  EXPECT_NE(t.layoutVersion(), first);
  const std::uint64_t shellLayout = t.layoutVersion();
  EXPECT_TRUE(sameMesh(t.tessellate(mug, {9}), tessellate(mug, {9})));
  EXPECT_NE(t.layoutVersion(), shellLayout);
  const std::uint64_t mugLayout = t.layoutVersion();
  t.tessellate(mug, {9});
  EXPECT_EQ(t.layoutVersion(), mugLayout);
}

// A session on a B-spline model holds its B-spline solution, not an empty spectral one
// (session.cpp once built an empty SolvedSpectral tagged "bspline-pde").
TEST(ModelSession, BSplineModelsAreSolvedAsThemselvesAndTransformWithUndo) {
  ModelSession session(loadModel(example("bspline-dome.json")), "dome");
  EXPECT_FALSE(session.hasEditableParts());
  EXPECT_EQ(session.solved().spectral(), nullptr);
  const auto* solved = session.solved().surface().as<SolvedBSplinePde>();
  ASSERT_NE(solved, nullptr);
  ASSERT_FALSE(solved->pieces.empty());
  const Mesh before = tessellate(session.solved(), {9});
  const AffineMap map = AffineMap::translationBy({0, 0, 1});
  session.transform(map);
  const Mesh moved = tessellate(session.solved(), {9});
  ASSERT_EQ(moved.positions.size(), before.positions.size());
  // Translating the control points translates the surface (B-spline bases sum to 1); in
  // float, to a few ulps of the coordinates' size.
  constexpr double kFloatTolerance = 1e-5;
  for (std::size_t i = 2; i < moved.positions.size(); i += 3)
    EXPECT_NEAR(moved.positions[i], before.positions[i] + 1.0, kFloatTolerance);
  ASSERT_TRUE(session.undo());
  EXPECT_TRUE(sameMesh(tessellate(session.solved(), {9}), before));
  EXPECT_THROW(session.apply(MoveVertex{0, Vec3::Zero()}), std::logic_error);
}

TEST(ModelSession, ARefusedTransformChangesNothing) {
  // a1.z + a2.z = 0: the force may push in x and y only, and a turn about y tips it into z.
  ModelSession session(
      parseModel(R"({"type": "vertex-frames", "vertices": [[0,0,0],[1,0,0],[2,0,0],[2,1,0],
          [2,2,0],[1,2,0],[0,2,0],[0,1,0]], "frames": [{"vertices": [0,1,2,3,4,5,6,7],
          "a1": [1, 1, 1], "a2": [1, 1, -1], "forces": [{"f0": [0.5, 0, 0]}]}]})",
                 "m"),
      "m");
  const Mesh before = tessellate(session.solved(), {5});
  EXPECT_THROW(session.transform(AffineMap::rotationAbout({0, 1, 0}, 0.3, Vec3::Zero())),
               ModelError);
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_EQ(session.undoDepth(), 0u);
  EXPECT_TRUE(sameMesh(tessellate(session.solved(), {5}), before));
  session.transform(AffineMap::rotationAbout({0, 0, 1}, 0.3, Vec3::Zero()));  // stays in x, y
  EXPECT_EQ(session.undoDepth(), 1u);
}

}  // namespace
}  // namespace pdesurf
