// Tests of `pdesurf rebuild --as vertex-frames`: the real binary, the model file it writes,
// its distances, and its errors (exit status, message, no file left behind).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "support/cgal_data.hpp"
#include "support/cli_run.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

using Json = nlohmann::json;
using testing::CliRun;

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

class CliRebuild : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) { return testing::runCli(work_, capture_, args); }
  std::string path(const std::string& name) const { return work_.file(name); }
  void put(const std::string& name, const std::string& text) {
    std::ofstream(path(name), std::ios::binary) << text;
  }

  /// A bumpy torus of 3 × 4 frames as the target mesh (torus.obj) and, as the layout, the
  /// quads of its frame corners moved a little (cage.obj).
  void writeTorusAndCage() {
    std::mt19937 rng(5);
    testing::LatticeOptions o;
    o.rows = 3;
    o.cols = 4;
    o.closedU = o.closedV = true;
    o.noise = 0.1;
    const VertexFrameModel truth = testing::latticeModel(o, rng);
    writeMesh(tessellate(solve(truth), {17}), path("torus.obj"));
    std::normal_distribution<double> noise(0.0, 0.05);
    std::string obj;
    for (const Vec3& p : truth.vertices)
      obj +=
          fmt::format("v {} {} {}\n", p.x() + noise(rng), p.y() + noise(rng), p.z() + noise(rng));
    for (const Frame& f : truth.frames)
      obj += fmt::format("f {} {} {} {}\n", f.vertices[0] + 1, f.vertices[2] + 1, f.vertices[4] + 1,
                         f.vertices[6] + 1);
    put("cage.obj", obj);
  }

  testing::TempDir work_, capture_;
};

/// The relative RMS of "iteration N ...: RMS x%" in the output, for iteration N.
double iterationRms(const std::string& out, int iteration) {
  const std::string key = fmt::format("iteration {:>3} (", iteration);
  const auto at = out.find(key);
  if (at == std::string::npos) return -1.0;
  const auto rms = out.find("RMS ", at);
  return std::stod(out.substr(rms + 4)) / 100.0;
}

TEST_F(CliRebuild, AQuadLayoutFittedToATorusWritesAModelThatCompareConfirms) {
  writeTorusAndCage();
  const CliRun r = run("rebuild torus.obj --as vertex-frames --layout cage.obj -o torus.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const VertexFrameModel model = loadVertexFrameModel(path("torus.json"));
  EXPECT_EQ(model.frames.size(), 12u);
  EXPECT_EQ(model.vertices.size(), 12u + 24u);  // V + E of the cage
  const double start = iterationRms(r.out, 0), end = iterationRms(r.out, 1);
  ASSERT_GT(start, 0.0) << r.out;
  ASSERT_GT(end, 0.0) << r.out;
  EXPECT_LT(end, start) << r.out;
  EXPECT_TRUE(contains(r.out, "storage ")) << r.out;
  // What rebuild printed, compare measures again from the file.
  const CliRun c = run("compare torus.json torus.obj --json");
  ASSERT_EQ(c.code, 0) << c.err;
  const Json d = Json::parse(c.out);
  const double rms = d["model_to_mesh"]["rms_relative"].get<double>();
  EXPECT_LT(rms, 0.1 * start) << r.out;
  EXPECT_TRUE(contains(r.out, fmt::format("RMS {:.6g} (", d["model_to_mesh"]["rms"].get<double>())))
      << r.out;
}

TEST_F(CliRebuild, AGridOnADiskMeshMakesUTimesVFrames) {
  const std::string mesh = testing::cgalData("three_peaks.off");
  const CliRun r = run("rebuild " + testing::shellQuote(mesh) +
                       " --as vertex-frames --grid 4 3 --iterations 3 -o peaks.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const VertexFrameModel model = loadVertexFrameModel(path("peaks.json"));
  EXPECT_EQ(model.frames.size(), 12u);
  EXPECT_EQ(model.vertices.size(), 9u * 7u - 12u);  // the lattice but the 4 × 3 frames' centres
  EXPECT_LE(iterationRms(r.out, 1), iterationRms(r.out, 0)) << r.out;
  // Nothing else is printed or written (CGAL's iterative authalic parameterizer would
  // print its progress and leave last_solve.off behind).
  EXPECT_EQ(r.out.rfind("iteration   0 (layout)", 0), 0u) << r.out;
  EXPECT_EQ(work_.entries(), std::vector<std::string>{"peaks.json"});
}

/// The line of `text` that starts with `prefix` (empty if none).
std::string lineStarting(const std::string& text, const std::string& prefix) {
  const auto at = text.rfind("\n" + prefix);
  if (at == std::string::npos) return "";
  return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

TEST_F(CliRebuild, TheNormalsLineIsCompares) {
  const std::string mesh = testing::shellQuote(testing::cgalData("three_peaks.off"));
  const CliRun r =
      run("rebuild " + mesh + " --as vertex-frames --grid 4 3 --iterations 3 -o peaks.json");
  ASSERT_EQ(r.code, 0) << r.err;
  // Every iteration reports its folded area; the end, the model's normals as compare does.
  EXPECT_TRUE(contains(lineStarting(r.out, "iteration   1"), "folded ")) << r.out;
  const std::string normals = lineStarting(r.out, "normals ");
  EXPECT_TRUE(contains(normals, "% of the model's area, RMS deviation ")) << r.out;
  const CliRun c = run("compare peaks.json " + mesh);
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(lineStarting(c.out, "normals "), normals) << c.out;
  // The fold-free term's weight: 0 turns it off, a negative one is a usage error.
  EXPECT_EQ(run("rebuild " + mesh +
                " --as vertex-frames --grid 4 3 --iterations 3 --fold-weight 0 -o off.json")
                .code,
            0);
  const CliRun bad =
      run("rebuild " + mesh + " --as vertex-frames --grid 4 3 --fold-weight -1 -o bad.json");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_TRUE(contains(bad.err, "--fold-weight")) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(path("bad.json")));
  // The normal-alignment term's weight reaches the fit (another model than without it); a
  // negative one is a usage error naming it.
  ASSERT_EQ(run("rebuild " + mesh +
                " --as vertex-frames --grid 4 3 --iterations 3 --normal-weight 3e-4 -o n.json")
                .code,
            0);
  EXPECT_NE(testing::readText(path("n.json")), testing::readText(path("peaks.json")));
  const CliRun badNormal =
      run("rebuild " + mesh + " --as vertex-frames --grid 4 3 --normal-weight -1 -o bad.json");
  EXPECT_EQ(badNormal.code, 2) << badNormal.err;
  EXPECT_TRUE(contains(badNormal.err, "--normal-weight")) << badNormal.err;
  EXPECT_FALSE(std::filesystem::exists(path("bad.json")));
}

/// The last "iteration N" line's number in the output.
int lastIteration(const std::string& out) {
  const auto at = out.rfind("\niteration ");
  return at == std::string::npos ? -1 : std::stoi(out.substr(at + 11));
}

TEST_F(CliRebuild, FitShapeFitsForcesAndParametersAfterTheVerticesAndEndsNoHigher) {
  writeTorusAndCage();
  const CliRun plain =
      run("rebuild torus.obj --as vertex-frames --layout cage.obj --iterations 8 -o plain.json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  const CliRun shaped =
      run("rebuild torus.obj --as vertex-frames --layout cage.obj --iterations 8 --fit-shape -o "
          "shaped.json");
  ASSERT_EQ(shaped.code, 0) << shaped.err;
  // The vertex iterations are the plain fit's; the shape iterations follow, marked.
  const int plainLast = lastIteration(plain.out), shapedLast = lastIteration(shaped.out);
  ASSERT_GT(shapedLast, plainLast) << shaped.out;
  EXPECT_EQ(shaped.out.find(fmt::format("iteration {:>3} (step", plainLast + 1)), std::string::npos)
      << shaped.out;
  EXPECT_TRUE(contains(shaped.out, fmt::format("iteration {:>3} (shape: step", plainLast + 1)))
      << shaped.out;
  EXPECT_TRUE(contains(shaped.out, "vertices, forces, a1 and a2: ")) << shaped.out;
  EXPECT_LE(iterationRms(shaped.out, shapedLast), iterationRms(plain.out, plainLast)) << shaped.out;
  const VertexFrameModel model = loadVertexFrameModel(path("shaped.json"));
  std::size_t forces = 0;
  for (const Frame& f : model.frames) forces += f.forces.size();
  EXPECT_GT(forces, 0u);
  // The model file is what compare measures; the distances it prints are the file's.
  const CliRun c = run("compare shaped.json torus.obj --json");
  ASSERT_EQ(c.code, 0) << c.err;
  const Json d = Json::parse(c.out);
  EXPECT_TRUE(
      contains(shaped.out, fmt::format("RMS {:.6g} (", d["model_to_mesh"]["rms"].get<double>())))
      << shaped.out;
}

TEST_F(CliRebuild, FitShapeInBadCombinationsIsAUsageError) {
  writeTorusAndCage();
  CliRun r = run("rebuild torus.obj --as cross-sections --fit-shape -o out.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err,
                       "--fit-shape fits the force, a1 and a2 of vertex frames: it needs "
                       "--as vertex-frames"))
      << r.err;
  r =
      run("rebuild torus.obj --as vertex-frames --layout cage.obj --fit-shape --iterations 0 -o "
          "out.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "--fit-shape with --iterations 0 would fit nothing")) << r.err;
  EXPECT_FALSE(std::ifstream(path("out.json")).good());
}

TEST_F(CliRebuild, BadLayoutsAndMeshesExitOneNamingTheProblemAndWriteNothing) {
  writeTorusAndCage();
  put("tri.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 3 4\n");
  CliRun r = run("rebuild torus.obj --as vertex-frames --layout tri.obj -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "tri.obj: face 1 has 3 corners")) << r.err;
  r = run("rebuild " + testing::shellQuote(testing::cgalData("cube.off")) +
          " --as vertex-frames --grid 2 2 -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "0 boundary loops")) << r.err;
  r = run("rebuild missing.obj --as vertex-frames --layout cage.obj -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "missing.obj")) << r.err;
  EXPECT_FALSE(std::ifstream(path("out.json")).good());
}

TEST_F(CliRebuild, LayoutAndGridTogetherIsAUsageError) {
  writeTorusAndCage();
  CliRun r = run("rebuild torus.obj --as vertex-frames --layout cage.obj --grid 2 2 -o out.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "give one of --layout QUADS, --grid U V and --tube RINGS SECTORS"))
      << r.err;
  r = run("rebuild torus.obj --as nurbs --layout cage.obj -o out.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(std::ifstream(path("out.json")).good());
}

}  // namespace
}  // namespace pdesurf
