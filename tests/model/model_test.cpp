// The model layer (include/pdesurf/model.hpp) and the one session type for every model.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

#include "pdesurf/method.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_info.hpp"
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
  if (const auto* s = solved.surface().as<SolvedSpectral>()) return tessellate(*s, {resolution});
  return tessellate(solved.surface().get<SolvedBSplinePde>(), {resolution});
}

TEST(Model, EveryExampleSolvesTessellatesAndSamplesThroughOneType) {
  constexpr std::uint32_t kResolution = 9, kGrid = 3;
  for (const std::string& path : exampleFiles()) {
    SCOPED_TRACE(path);
    const SolvedModel solved = solve(loadModel(path), path);
    EXPECT_EQ(solved.type(), std::string(modelTypeName(loadModel(path))));
    EXPECT_TRUE(sameMesh(tessellate(solved, {kResolution}), engineMesh(solved, kResolution)));
    const std::vector<PatchSamples> samples = sample(solved, {kGrid});
    ASSERT_FALSE(samples.empty());
    for (std::size_t k = 0; k < samples.size(); ++k) {
      EXPECT_EQ(samples[k].index, k);
      EXPECT_EQ(samples[k].points.size(), std::size_t{kGrid} * kGrid);
    }
    const ModelReport r = report(solved);
    EXPECT_FALSE(r.summary.empty());
    EXPECT_FALSE(r.quality.empty());
    // Every type's info names the model's file and its box, every fact shown somewhere (a
    // listing's label or a JSON key), the box's corners in order.
    const ModelInfo info = modelInfo(solved);
    EXPECT_EQ(info.source, path);
    for (const InfoFact& fact : info.facts) EXPECT_FALSE(fact.label.empty() && fact.key.empty());
    const InfoFact* box = info.find("bbox");
    ASSERT_NE(box, nullptr);
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_LE(box->value["min"][i].get<double>(), box->value["max"][i].get<double>());
    // The NURBS faces cover every patch: one face per patch at least.
    EXPECT_GE(toNurbs(solved).faces.size(), solved.frames() ? solved.frames()->patches.size() : 1);
  }
}

TEST(Model, EachMethodNamesItsPatches) {
  // What `pdesurf sample` writes a patch's index under: vertex frames' patches are frames.
  EXPECT_STREQ(loadModel(example("mug.json")).method().patchName(), "frame");
  for (const char* file : {"shell.json", "vase-sections.json", "bspline-blend.json"})
    EXPECT_STREQ(loadModel(example(file)).method().patchName(), "patch") << file;
}

TEST(Model, OverlayDrawsControlPolygonsOfBSplinesAndNothingForFrames) {
  const SolvedModel bspline = solve(loadModel(example("bspline-blend.json")), "bspline-blend.json");
  std::size_t lines = 0;
  for (const BSplineSurface& piece : bspline.surface().get<SolvedBSplinePde>().pieces)
    lines += piece.net().nu + 1 + piece.net().nv + 1;
  EXPECT_EQ(overlay(bspline).curves.size(), lines);
  EXPECT_TRUE(overlay(bspline).spines.empty());
  const ModelOverlay frames = overlay(solve(loadModel(example("mug.json")), "mug.json"));
  EXPECT_TRUE(frames.curves.empty() && frames.spines.empty());
  const SolvedModel shell = solve(loadModel(example("shell.json")), "shell.json");
  EXPECT_EQ(overlay(shell).spines.size(), shell.spectral()->patchCount());
}

TEST(Model, SeedFrameOutOfRangeIsRefusedForFramesOnly) {
  const AnyModel mug = loadModel(example("mug.json"));
  const std::size_t frames = mug.get<VertexFrameModel>().frames.size();
  SolveOptions options;
  options.vertexFrames.seedFrame = static_cast<std::uint32_t>(frames);
  EXPECT_THROW(checkSolveOptions(mug, options), InvalidArgument);
  options.vertexFrames.seedFrame = static_cast<std::uint32_t>(frames - 1);
  EXPECT_NO_THROW(checkSolveOptions(mug, options));
  options.vertexFrames.seedFrame = 1000;  // the vertex frames' member: other types ignore it
  EXPECT_NO_THROW(checkSolveOptions(loadModel(example("shell.json")), options));
}

TEST(Model, VertexFrameSolveOptionsChangeNothingForTheOtherMethods) {
  SolveOptions local;
  local.vertexFrames = {Solver::Local, 1000};  // a seed frame no example has
  for (const std::string& path : exampleFiles()) {
    const AnyModel model = loadModel(path);
    if (model.is<VertexFrameModel>()) continue;
    SCOPED_TRACE(path);
    EXPECT_NO_THROW(checkSolveOptions(model, local));
    EXPECT_TRUE(
        sameMesh(tessellate(solve(model, path, local), {9}), tessellate(solve(model, path), {9})));
  }
}

TEST(Model, EveryTessellateChecksItsOptions) {
  for (const std::string& path : exampleFiles()) {
    SCOPED_TRACE(path);
    const SolvedModel solved = solve(loadModel(path), path);
    EXPECT_THROW(tessellate(solved, {.resolution = 1}), InvalidArgument);
    EXPECT_THROW(tessellate(solved, {.resolution = 9, .aroundResolution = 2}), InvalidArgument);
    EXPECT_NO_THROW(tessellate(solved, {.resolution = 2}));
  }
  const SolvedModel blend = solve(loadModel(example("bspline-blend.json")), "bspline-blend.json");
  const BSplineSurface& piece = blend.surface().get<SolvedBSplinePde>().pieces.front();
  EXPECT_THROW(tessellate(piece, {.resolution = 0}), InvalidArgument);
  const SolvedModel shell = solve(loadModel(example("shell.json")), "shell.json");
  EXPECT_THROW(tessellate(*shell.spectral()->patch, {.resolution = 1}), InvalidArgument);
}

TEST(Model, SpectralColumnsAroundDefaultToFourARowAndAtLeastEight) {
  const SolvedModel shell = solve(loadModel(example("shell.json")), "shell.json");
  const SolvedSpectral& s = *shell.spectral();
  const Mesh nine = tessellate(s, {.resolution = 9});
  EXPECT_TRUE(sameMesh(nine, tessellate(s, {.resolution = 9, .aroundResolution = 32})));
  EXPECT_FALSE(sameMesh(nine, tessellate(s, {.resolution = 9, .aroundResolution = 31})));
  EXPECT_TRUE(sameMesh(tessellate(s, {.resolution = 2}),
                       tessellate(s, {.resolution = 2, .aroundResolution = 8})));
}

// docs/library.md, "Names and options": the page's example as written there, and what it
// says of it.
TEST(Model, TheLibraryPagesNamingExample) {
  const AnyModel model = loadModel(example("mug.json"));
  SolveOptions solveOptions;
  solveOptions.vertexFrames.solver = Solver::Local;  // read by vertex frames alone
  const SolvedModel solved = solve(model, "mug.json", solveOptions);
  const Mesh mesh = tessellate(solved, {.resolution = 9});
  const auto samples = sample(solved, {.grid = 5});
  const VertexFrameSurface& frames = *solved.frames();
  const Mesh same = tessellate(frames, {.resolution = 9});
  EXPECT_TRUE(sameMesh(mesh, same));
  EXPECT_EQ(solved.options().vertexFrames.solver, Solver::Local);
  ASSERT_EQ(samples.size(), frames.patches.size());
  EXPECT_EQ(samples.front().points.size(), 25u);
  const VertexFrameSurface global = solve(model.get<VertexFrameModel>());
  EXPECT_FALSE(sameMesh(mesh, tessellate(global, {.resolution = 9})));  // the option was read
}

TEST(Model, TessellatorKeepsItsLayoutUntilTheTrianglesChange) {
  const SolvedModel shell = solve(loadModel(example("shell.json")), "shell.json");
  const SolvedModel mug = solve(loadModel(example("mug.json")), "mug.json");
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
