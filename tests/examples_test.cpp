// Every model in examples/ is built and checked: a new example is tested for free.
#include <gtest/gtest.h>

#include <filesystem>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/examples.hpp"
#include "support/mesh_checks.hpp"

namespace pdesurf {
namespace {

namespace fs = std::filesystem;

using testing::exampleFiles;

/// The examples whose model is of type T (VertexFrameModel, SpectralModel, ...).
template <typename T>
std::vector<std::string> examplesOf() {
  std::vector<std::string> files;
  for (const std::string& f : exampleFiles())
    if (loadModel(f).is<T>()) files.push_back(f);
  return files;
}

class Example : public ::testing::TestWithParam<std::string> {};

constexpr double kVertexParams[8][2] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5},
                                        {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};

TEST_P(Example, InterpolatesItsVerticesAndIsExactlyC0WithBothSolvers) {
  const VertexFrameModel m = loadVertexFrameModel(GetParam());
  for (Solver solver : {Solver::Global, Solver::Local}) {
    const VertexFrameSurface s = solve(m, {solver, 0});
    const double diag = surfaceBounds(s).diagonal();
    ASSERT_GT(diag, 0.0);
    EXPECT_LT(measureC0Gap(s).maxGap / diag, kC0RelativeTolerance);
    double worst = 0;
    for (std::size_t k = 0; k < m.frames.size(); ++k)
      for (int i = 0; i < 8; ++i) {
        const Vec3 p = s.patches[k].position(kVertexParams[i][0], kVertexParams[i][1]);
        worst = std::max(worst, (p - m.vertices[m.frames[k].vertices[i]]).norm());
      }
    EXPECT_LT(worst / diag, kC0RelativeTolerance) << "vertex interpolation";
  }
}

TEST_P(Example, TessellatesToAWatertightOrientedMeshThatSurvivesEveryFormat) {
  const VertexFrameModel m = loadVertexFrameModel(GetParam());
  const VertexFrameSurface s = solve(m);
  const std::uint32_t n = 9;
  const Mesh mesh = tessellate(s, {n});
  const auto stats = testing::edgeStats(mesh);
  // Open edges of the mesh are exactly the model's unshared, uncollapsed edges.
  std::size_t openModelEdges = 0;
  for (std::uint32_t e = 0; e < s.topology->edges.size(); ++e)
    if (s.topology->sides(e).size() == 1 && !s.topology->edges[e].collapsed()) ++openModelEdges;
  EXPECT_EQ(stats.boundaryEdges, openModelEdges * (n - 1));
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(testing::duplicatePositions(mesh), 0u);
  EXPECT_GT(testing::minCornerNormalAgreement(mesh), testing::kNoBackwardNormals);

  const fs::path dir =
      fs::temp_directory_path() / ("pdesurf-example-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* ext : {".obj", ".ply", ".stl", ".glb"}) {
    const std::string path = (dir / (fs::path(GetParam()).stem().string() + ext)).string();
    writeMesh(mesh, path);
    const Mesh back = readMesh(path);
    EXPECT_EQ(back.vertexCount(), mesh.vertexCount()) << ext;
    EXPECT_EQ(back.triangleCount(), mesh.triangleCount()) << ext;
    // Still watertight where the model is: the same open edges, all oriented alike.
    const auto backStats = testing::edgeStats(back);
    EXPECT_EQ(backStats.boundaryEdges, stats.boundaryEdges) << ext;
    EXPECT_EQ(backStats.inconsistentlyOrientedEdges, 0u) << ext;
  }
  fs::remove_all(dir);
}

TEST_P(Example, RoundTripsThroughTheModelWriter) {
  const VertexFrameModel m = loadVertexFrameModel(GetParam());
  const VertexFrameModel back = parseVertexFrameModel(serializeVertexFrameModel(m), "round-trip");
  ASSERT_EQ(back.vertices.size(), m.vertices.size());
  ASSERT_EQ(back.frames.size(), m.frames.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) EXPECT_EQ(back.vertices[i], m.vertices[i]);
  EXPECT_EQ(storageBytes(back), storageBytes(m));
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Examples, Example, ::testing::ValuesIn(examplesOf<VertexFrameModel>()),
                         testName);

/// Spectral and cross-section examples: conditions met, joints exact, a clean mesh.
class SpectralExample : public ::testing::TestWithParam<std::string> {};

/// Relative error to which an example's conditions hold (issue 4: 1e-9 relative).
constexpr double kExampleConditionTolerance = 1e-9;
/// Relative C0, C1, C2 gaps at the joints of a "c2" chain: exact up to rounding.
constexpr double kExampleJointTolerance = 1e-9;

TEST_P(SpectralExample, MeetsItsConditionsAndTessellatesCleanly) {
  const AnyModel any = loadModel(GetParam());
  std::vector<const SpectralPatch*> patches;
  std::optional<SpectralPatch> patch;
  std::optional<CrossSectionChain> chain;
  if (const auto* m = any.as<SpectralModel>()) {
    patch = solve(*m, GetParam()).patch;
    patches.push_back(&*patch);
  } else {
    const auto& cs = any.get<CrossSectionModel>();
    chain = solve(cs, GetParam()).chain;
    for (const ChainPatch& p : chain->patches) patches.push_back(&p.patch);
    if (cs.options.method == ChainMethod::ExactC2)
      for (const JointGap& g : measureJointGaps(*chain)) {
        EXPECT_LT(g.c0Relative, kExampleJointTolerance) << "joint at curve " << g.curve;
        EXPECT_LT(g.c1Relative, kExampleJointTolerance) << "joint at curve " << g.curve;
        EXPECT_LT(g.c2Relative, kExampleJointTolerance) << "joint at curve " << g.curve;
      }
  }
  for (const SpectralPatch* p : patches)
    for (double e : conditionErrors(*p)) EXPECT_LT(e, kExampleConditionTolerance);

  const TessellateOptions options{.resolution = 9, .aroundResolution = 16};
  const Mesh mesh = chain ? tessellate(*chain, options) : tessellate(*patch, options);
  ASSERT_GT(mesh.triangleCount(), 0u);
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  // Closed around v: the only open edges are the two end curves (fewer when one collapses).
  EXPECT_LE(stats.boundaryEdges, 2u * options.aroundResolution);
  for (float x : mesh.positions) ASSERT_TRUE(std::isfinite(x));
  for (float x : mesh.normals) ASSERT_TRUE(std::isfinite(x));
}

INSTANTIATE_TEST_SUITE_P(Examples, SpectralExample, ::testing::ValuesIn([] {
                           auto files = examplesOf<SpectralModel>();
                           for (auto& f : examplesOf<CrossSectionModel>()) files.push_back(f);
                           return files;
                         }()),
                         testName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(SpectralExample);

/// B-spline PDE examples (seed 004): every piece solves the PDE, blends are C1, the mesh is
/// clean and open only along the region's border.
class BSplineExample : public ::testing::TestWithParam<std::string> {};

/// The PDE residual of a solved piece and the relative C1 gap of a blend: rounding.
constexpr double kExampleBSplineTolerance = 1e-12;
constexpr double kExampleBlendGapTolerance = 1e-9;

TEST_P(BSplineExample, SolvesThePdeAndTessellatesCleanly) {
  const AnyModel any = loadModel(GetParam());
  const auto& model = any.get<BSplinePdeModel>();
  const SolvedBSplinePde solved = solve(model, GetParam());
  for (const BSplineSurface& piece : solved.pieces)
    EXPECT_LT(pdeResidual(piece), kExampleBSplineTolerance);
  if (solved.c1Gap) EXPECT_LT(*solved.c1Gap, kExampleBlendGapTolerance);
  if (model.form == BSplinePdeModel::Form::Net)  // the given points come out as written
    for (std::uint32_t i = 0; i <= model.net.nu; ++i)
      for (std::uint32_t j = 0; j <= model.net.nv; ++j)
        if (model.net.given(i, j)) EXPECT_EQ(solved.pieces[0].net()(i, j), model.net(i, j));
  const Mesh mesh = tessellate(solved, {17});
  ASSERT_GT(mesh.triangleCount(), 0u);
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  EXPECT_EQ(stats.nonManifoldEdges, 0u);
  for (float x : mesh.positions) ASSERT_TRUE(std::isfinite(x));
  for (float x : mesh.normals) ASSERT_TRUE(std::isfinite(x));
}

INSTANTIATE_TEST_SUITE_P(Examples, BSplineExample,
                         ::testing::ValuesIn(examplesOf<BSplinePdeModel>()), testName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(BSplineExample);

TEST(Examples, AreAllThere) {
  // The list: a mug with a handle, a basket with a strap, a vase, a hat, a dress,
  // a single-frame sculpting demo.
  const auto files = exampleFiles();
  // Issue 5: the seed 004 examples 1-5 (docs/bspline-pde.md).
  for (const char* name : {"mug", "basket", "vase", "hat", "dress", "sculpt", "bspline-wave",
                           "bspline-catenoid", "bspline-spiral", "bspline-blend", "bspline-tube"}) {
    const bool found = std::any_of(files.begin(), files.end(), [&](const std::string& f) {
      return fs::path(f).stem() == name;
    });
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace pdesurf
