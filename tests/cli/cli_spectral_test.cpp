// The CLI on spectral and cross-section models: build, sample, info, spine and fit, and
// their refusals (exit 1 for a bad file, 2 for bad usage, no output file on error).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <fmt/format.h>
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

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A lobed closed curve at height z as points (not a finite Fourier series of few modes).
std::string lobed(double r, double z, int count) {
  std::string pts;
  for (int j = 0; j < count; ++j) {
    const double v = 2 * std::numbers::pi * j / count;
    const double rr = r * (1 + 0.15 * std::cos(5 * v) + 0.05 * std::sin(9 * v));
    pts += fmt::format("{}[{}, {}, {}]", j ? ", " : "", rr * std::cos(v), rr * std::sin(v), z);
  }
  return fmt::format(R"({{"points": [{}]}})", pts);
}

std::string chainModel() {
  std::string curves;
  for (int k = 0; k < 7; ++k) curves += (k ? ", " : "") + lobed(1 + 0.3 * std::sin(k), 0.5 * k, 48);
  return fmt::format(R"({{"type": "cross-sections", "name": "lobes", "a": 1, "modes": 6,
                          "curves": [{}]}})",
                     curves);
}

class CliSpectral : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) { return runCli(work_, capture_, args); }
  TempDir work_, capture_;
};

TEST_F(CliSpectral, BuildsAChainIntoAClosedAroundMeshAndReportsIt) {
  writeFile(work_.file("lobes.json"), chainModel());
  const CliRun r = run("build lobes.json -o lobes.ply --resolution 9");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("lobes: cross-sections, order 6, 6 modes,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("joint C0 gap"), std::string::npos) << r.out;
  const Mesh mesh = readMesh(work_.file("lobes.ply"));
  const auto stats = testing::edgeStats(mesh);
  EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
  // Open only at the first and last curve: 4(9 − 1) = 32 columns each.
  EXPECT_EQ(stats.boundaryEdges, 2u * 32u);
}

TEST_F(CliSpectral, SampleMatchesTheLibraryAndInfoReportsJoints) {
  writeFile(work_.file("lobes.json"), chainModel());
  const CliRun s = run("sample lobes.json --grid 5");
  ASSERT_EQ(s.code, 0) << s.err;
  const Json j = Json::parse(s.out);
  const auto model = loadModel(work_.file("lobes.json")).get<CrossSectionModel>();
  const CrossSectionChain chain = *solve(model, "lobes.json").chain;
  ASSERT_EQ(j["patches"].size(), chain.patches.size());
  for (std::size_t k = 0; k < chain.patches.size(); ++k) {
    const Json& p = j["patches"][k];
    const double u0 = p["u"][0], u1 = p["u"][1];
    EXPECT_EQ(u0, chain.patches[k].tStart);
    EXPECT_EQ(u1, chain.patches[k].tEnd);
    for (int jj = 0; jj < 5; ++jj)
      for (int i = 0; i < 5; ++i) {
        const Vec3 expected = chain.patches[k].patch.position(u0 + (u1 - u0) * i / 4.0,
                                                              2 * std::numbers::pi * jj / 4.0);
        const Json& q = p["points"][jj * 5 + i];
        EXPECT_EQ(Vec3(q[0], q[1], q[2]), expected);  // printed round-trippable
      }
  }
  const CliRun info = run("info lobes.json --json");
  ASSERT_EQ(info.code, 0) << info.err;
  const Json ij = Json::parse(info.out);
  EXPECT_EQ(ij["type"], "cross-sections");
  EXPECT_EQ(ij["method"], "global");  // the default
  EXPECT_EQ(ij["joints"].size(), chain.patches.size() - 1);
  for (const Json& g : ij["joints"]) {
    EXPECT_LT(g["c0_relative"].get<double>(), 1e-9);
    EXPECT_LT(g["c2_relative"].get<double>(), 1e-9);
  }
  EXPECT_LT(ij["condition_error_relative"].get<double>(), 1e-9);
}

TEST_F(CliSpectral, SpineAndFit) {
  writeFile(work_.file("lobes.json"), chainModel());
  const CliRun sp = run("spine lobes.json --count 4");
  ASSERT_EQ(sp.code, 0) << sp.err;
  const Json spine = Json::parse(sp.out);
  ASSERT_FALSE(spine["patches"].empty());
  EXPECT_EQ(spine["patches"][0]["points"].size(), 4u);
  // The spine runs up the stack of sections: its z rises along each patch.
  for (const Json& p : spine["patches"])
    for (std::size_t i = 1; i < p["points"].size(); ++i)
      EXPECT_GT(p["points"][i][2].get<double>(), p["points"][i - 1][2].get<double>());

  // Fitting lobed curves (cos 5v, sin 9v wobbles) at the v they were made with (--uniform):
  // errors fall as terms grow, and vanish once the series holds every frequency of the
  // curve. By chord length (the default) they fall too, but the curve is no longer a finite
  // series in that parameter.
  const CliRun chord = run("fit lobes.json --terms 2 6 12 --json");
  ASSERT_EQ(chord.code, 0) << chord.err;
  for (const Json& c : Json::parse(chord.out)["curves"]) {
    const Json& e = c["fits"];
    EXPECT_GT(e[0]["max_error"].get<double>(), e[1]["max_error"].get<double>());
    EXPECT_GT(e[1]["mean_error"].get<double>(), e[2]["mean_error"].get<double>());
  }
  const CliRun f = run("fit lobes.json --terms 2 6 12 --uniform --json");
  ASSERT_EQ(f.code, 0) << f.err;
  const Json fits = Json::parse(f.out);
  ASSERT_EQ(fits["curves"].size(), 7u);
  for (const Json& c : fits["curves"]) {
    const Json& e = c["fits"];
    EXPECT_GT(e[0]["max_error"].get<double>(), e[1]["max_error"].get<double>());
    EXPECT_GT(e[1]["max_error"].get<double>(), e[2]["max_error"].get<double>());
    EXPECT_LT(e[2]["max_error"].get<double>(), 1e-9);
  }
}

TEST_F(CliSpectral, RefusesWithExitCodesAndLeavesNoFile) {
  writeFile(work_.file("bad.json"),
            R"({"type": "cross-sections", "curves": [{"points": [[0,0,0],[1,0,0],[0,1,0]]}]})");
  CliRun r = run("build bad.json -o bad.obj");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.json: $.curves: the \"global\" method needs at least 2 curves"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(work_.entries(), std::vector<std::string>{"bad.json"});

  // spine of a vertex-frames model is a usage error; fit of Fourier curves a file error.
  writeFile(work_.file("frame.json"), R"({"type": "vertex-frames",
    "vertices": [[0,0,0],[1,0,0],[2,0,0],[2,1,0],[2,2,0],[1,2,0],[0,2,0],[0,1,0]],
    "frames": [{"vertices": [0,1,2,3,4,5,6,7]}]})");
  r = run("spine frame.json");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("only spectral and cross-sections models have a spine"), std::string::npos)
      << r.err;
  writeFile(work_.file("fourier.json"),
            R"({"curves": [{"fourier": {"a0": [0,0,0], "a": [[1,0,0]], "b": [[0,1,0]]}}]})");
  r = run("fit fourier.json --terms 2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("fourier.json: $.curves[0]: this curve is given by Fourier coefficients"),
            std::string::npos)
      << r.err;
  writeFile(work_.file("few.json"), R"({"curves": [{"points": [[0,0,0],[1,0,0],[0,1,0]]}]})");
  r = run("fit few.json --terms 4");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("few.json: $.curves[0]: "), std::string::npos) << r.err;
  r = run("fit few.json");
  EXPECT_EQ(r.code, 2);  // --terms is required
}

}  // namespace
}  // namespace pdesurf
