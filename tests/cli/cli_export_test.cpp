// Tests of `pdesurf export`: the real binary, its exit status, report, error messages and
// the files it leaves behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "pdesurf/nurbs.hpp"
#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

using testing::CliRun;

std::string example(const std::string& name) {
  return testing::shellQuote(
      (std::filesystem::path(PDESURF_SOURCE_DIR) / "examples" / name).string());
}

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

/// One flat frame over [0, 2]² at z = 0, named.
const char* kOneFrame = R"({"type": "vertex-frames", "name": "flat",
  "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
               [0, 1, 0]],
  "frames": [{"vertices": [0, 1, 2, 3, 4, 5, 6, 7]}]})";

class CliExport : public ::testing::Test {
 protected:
  void SetUp() override { put("flat.json", kOneFrame); }
  CliRun run(const std::string& args) { return testing::runCli(work_, capture_, args); }
  void put(const std::string& name, const std::string& text) {
    std::ofstream(work_.file(name), std::ios::binary) << text;
  }
  std::vector<std::string> entries() const { return work_.entries(); }
  std::string read(const std::string& name) const { return testing::readText(work_.file(name)); }

  testing::TempDir work_, capture_;
};

TEST_F(CliExport, WritesStepAndIgesAndReports) {
  const CliRun r = run("export flat.json -o flat.step");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "flat: 1 face (1 exact, 0 approximated)")) << r.out;
  EXPECT_TRUE(contains(r.out, "-> flat.step")) << r.out;
  EXPECT_TRUE(contains(r.out, "sewn: 1 shell, 4 free edges")) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_TRUE(read("flat.step").starts_with("ISO-10303-21;"));
  EXPECT_TRUE(contains(read("flat.step"), "B_SPLINE_SURFACE_WITH_KNOTS"));

  const CliRun i = run("export flat.json -o FLAT.IGS");
  ASSERT_EQ(i.code, 0) << i.err;
  EXPECT_TRUE(contains(read("FLAT.IGS"), "128,3,3,"));  // a bicubic B-spline surface entity
  EXPECT_EQ(entries(), (std::vector<std::string>{"FLAT.IGS", "flat.json", "flat.step"}));
}

TEST_F(CliExport, ReportsApproximationsAndJson) {
  const CliRun r = run("export " + example("sculpt.json") + " -o s.step --tolerance 1e-3 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "step");
  EXPECT_EQ(j["approximated_faces"], 1);
  EXPECT_EQ(j["exact_faces"], 0);
  EXPECT_DOUBLE_EQ(j["tolerance"].get<double>(), 1e-3);
  EXPECT_LE(j["max_deviation"].get<double>(), 1e-3);
  EXPECT_GT(j["max_deviation"].get<double>(), 0.0);
  EXPECT_EQ(j["faces"].size(), 1u);
  EXPECT_EQ(j["sewing"]["free_edges"], 4);
}

TEST_F(CliExport, BadToleranceIsAUsageError) {
  for (const char* t : {"0", "-1", "nan", "inf"}) {
    const CliRun r = run(std::string("export flat.json -o x.step --tolerance ") + t);
    EXPECT_EQ(r.code, 2) << t << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "--tolerance")) << r.err;
  }
  const CliRun word = run("export flat.json -o x.step --tolerance small");
  EXPECT_EQ(word.code, 2);
  EXPECT_EQ(entries(), std::vector<std::string>{"flat.json"});
}

TEST_F(CliExport, UnknownExtensionIsAUsageError) {
  const CliRun r = run("export flat.json -o flat.obj");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "flat.obj: unknown extension '.obj'")) << r.err;
  EXPECT_TRUE(contains(r.err, ".step")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"flat.json"});
}

TEST_F(CliExport, MissingOrInvalidModelExitsOneAndWritesNothing) {
  const CliRun missing = run("export nothere.json -o x.step");
  EXPECT_EQ(missing.code, 1);
  EXPECT_TRUE(contains(missing.err, "nothere.json")) << missing.err;
  put("bad.json",
      R"({"type": "vertex-frames", "vertices": [[0, 0, 0]], "frames": [{"vertices": [0, 0, 0, 0, 0, 0, 0, 9]}]})");
  const CliRun bad = run("export bad.json -o x.step");
  EXPECT_EQ(bad.code, 1);
  EXPECT_TRUE(contains(bad.err, "bad.json")) << bad.err;
  EXPECT_EQ(entries(), (std::vector<std::string>{"bad.json", "flat.json"}));
}

TEST_F(CliExport, AnUnreachableToleranceFailsAndLeavesNoFile) {
  const CliRun r = run("export " + example("sculpt.json") + " -o s.step --tolerance 1e-15");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "patch 0")) << r.err;
  EXPECT_TRUE(contains(r.err, "give a larger --tolerance")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"flat.json"});
}

TEST_F(CliExport, UnderTheDefaultToleranceAFaceOverItIsWrittenWithAWarning) {
  // Four spans cannot hold sculpt.json's forced patches within 1e-4 of the diagonal: with
  // the default tolerance the file is written all the same, each such face its finest fit.
  const CliRun r = run("export " + example("sculpt.json") + " -o s.step --max-spans 4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "warning: s.step:")) << r.err;
  EXPECT_TRUE(contains(r.err, "written as the finest fit tried")) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double tolerance = j["tolerance"].get<double>();
  std::size_t over = 0;
  for (const auto& face : j["faces"])
    if (!face["within_tolerance"].get<bool>()) {
      ++over;
      EXPECT_FALSE(face["exact"].get<bool>());
      // within_tolerance means deviation ≤ kApproximationSafety × tolerance (nurbs.hpp)
      EXPECT_GT(face["deviation"].get<double>(), kApproximationSafety * tolerance);
    }
  EXPECT_GT(over, 0u);
  EXPECT_EQ(j["faces_over_tolerance"].get<std::size_t>(), over);
  EXPECT_TRUE(read("s.step").starts_with("ISO-10303-21;"));

  // The same cap with a tolerance asked for is an error, and no file.
  const CliRun strict = run("export " + example("sculpt.json") +
                            " -o t.step --max-spans 4 --tolerance " + j["tolerance"].dump());
  EXPECT_EQ(strict.code, 2);
  EXPECT_TRUE(contains(strict.err, "give a larger --tolerance")) << strict.err;
  EXPECT_EQ(entries(), (std::vector<std::string>{"flat.json", "s.step"}));
}

TEST_F(CliExport, EveryBundledExampleExportsWithinTheDefaultTolerance) {
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(PDESURF_SOURCE_DIR) / "examples")) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().filename().string();
    const CliRun r = run("export " + example(name) + " -o x.step --json");
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << name << ": " << r.err;  // no face over the tolerance
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["faces_over_tolerance"].get<std::size_t>(), 0u) << name;
    EXPECT_LE(j["max_deviation"].get<double>(), j["tolerance"].get<double>()) << name;
  }
}

TEST_F(CliExport, AnUnwritableOutputExitsOneAndLeavesNoFile) {
  const CliRun r = run("export flat.json -o no/such/dir/x.step");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "no/such/dir/x.step")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"flat.json"});
}

}  // namespace
}  // namespace pdesurf
