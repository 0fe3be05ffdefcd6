// The CLI on "bspline-pde" models: build, sample and info agree with the library, and the
// refusals (exit 1 naming the file and JSON path, no output file left behind).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "pdesurf/mesh_io.hpp"
#include "pdesurf/spectral_io.hpp"
#include "support/cli_run.hpp"
#include "support/mesh_checks.hpp"

namespace pdesurf {
namespace {

using testing::CliRun;
using testing::runCli;
using testing::TempDir;
using Json = nlohmann::json;

class CliBSpline : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) { return runCli(work_, capture_, args); }
  static std::string example(const std::string& name) {
    return (std::filesystem::path(PDESURF_SOURCE_DIR) / "examples" / (name + ".json")).string();
  }
  TempDir work_, capture_;
};

TEST_F(CliBSpline, BuildsSamplesAndReportsABlend) {
  const std::string model = example("bspline-blend");
  const CliRun r = run("build " + model + " -o blend.obj --resolution 13");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("bspline-blend: bspline-pde, 4 pieces, 7 x 7 control points each"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("C1 gap"), std::string::npos) << r.out;
  const Mesh mesh = readMesh(work_.file("blend.obj"));
  // 4 spans a piece, 3 segments a span (12 ≥ 13 − 1): a 25 × 25 grid shared by 4 pieces.
  EXPECT_EQ(mesh.vertexCount(), 25u * 25u);
  EXPECT_EQ(testing::edgeStats(mesh).boundaryEdges, 4u * 24u);

  // sample: the library's evaluation, point for point.
  const CliRun s = run("sample " + model + " --grid 5");
  ASSERT_EQ(s.code, 0) << s.err;
  const Json j = Json::parse(s.out);
  const SolvedBSplinePde solved = solve(loadModel(model).get<BSplinePdeModel>(), model);
  ASSERT_EQ(j["patches"].size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const Json& p = j["patches"][k];
    EXPECT_EQ(p["origin"][0].get<std::uint32_t>(), solved.origin[k][0]);
    EXPECT_EQ(p["origin"][1].get<std::uint32_t>(), solved.origin[k][1]);
    for (int jj = 0; jj < 5; ++jj)
      for (int i = 0; i < 5; ++i) {
        const Vec3 expected = solved.pieces[k].position(i / 4.0, jj / 4.0);
        const Json& q = p["points"][static_cast<std::size_t>(jj * 5 + i)];
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(q[static_cast<std::size_t>(c)].get<double>(), expected[c]);
      }
  }

  const CliRun info = run("info " + model + " --json");
  ASSERT_EQ(info.code, 0) << info.err;
  const Json ij = Json::parse(info.out);
  EXPECT_EQ(ij["type"], "bspline-pde");
  EXPECT_EQ(ij["form"], "blend");
  EXPECT_EQ(ij["pieces"], 4);
  EXPECT_LT(ij["pde_residual"].get<double>(), 1e-12);
  EXPECT_LT(ij["c1_gap_relative"].get<double>(), 1e-9);
  ASSERT_EQ(ij["seams"].size(), 2u);
  EXPECT_EQ(ij["seams"][0]["seam"], "U = 1");
  EXPECT_LT(ij["seams"][1]["c1_gap_relative"].get<double>(), 1e-9);
  EXPECT_EQ(ij["control_points"][0], 7);
}

TEST_F(CliBSpline, ExportsEveryPieceExactlyAndSewsTheSeams) {
  // Example 4: four exact faces sewn along the two seams; the region's border, each side
  // split in two, stays free.
  const CliRun r = run("export " + example("bspline-blend") + " -o blend.step --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["exact_faces"], 4);
  EXPECT_EQ(j["approximated_faces"], 0);
  EXPECT_LT(j["max_deviation_relative"].get<double>(), 1e-12);
  EXPECT_EQ(j["sewing"]["shells"], 1);
  EXPECT_EQ(j["sewing"]["free_edges"], 8);
  EXPECT_TRUE(std::filesystem::exists(work_.file("blend.step")));
}

TEST_F(CliBSpline, RefusesBadFilesWithoutLeavingOutput) {
  std::ofstream(work_.file("bad.json")) << R"({"type": "bspline-pde", "blend": {"n": 2}})";
  CliRun r = run("build bad.json -o bad.obj");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.json: $.blend.n: 2 is out of range"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(work_.file("bad.obj")));
  r = run("spine " + example("bspline-wave"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("this is a bspline-pde model"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pdesurf
