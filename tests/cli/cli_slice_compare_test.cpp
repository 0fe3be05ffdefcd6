// Tests of `pdesurf slice` and `pdesurf compare`: the real binary, its exit status, output,
// error messages and the files it leaves behind.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/mesh_io.hpp"
#include "support/cgal_data.hpp"
#include "support/cli_run.hpp"
#include "support/examples.hpp"
#include "support/test_meshes.hpp"

namespace pdesurf {
namespace {

using Json = nlohmann::json;
using testing::CliRun;

/// Positions are stored as float: 1e-6 bounds their rounding on shapes of size ~1.
constexpr double kFloatTolerance = 1e-6;

/// One flat frame over [0, 2]² at z = 0.
const char* kOneFrame = R"({"type": "vertex-frames",
  "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
               [0, 1, 0]],
  "frames": [{"vertices": [0, 1, 2, 3, 4, 5, 6, 7]}]})";

/// A model against its own tessellation: the same triangles, so the same normals up to the
/// float rounding of the written mesh, 1e-7 in a cosine near 1: an angle of sqrt(2e-7) rad,
/// 0.026°; 0.1° bounds it.
constexpr double kNormalDegreesTolerance = 0.1;

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

class CliMeshTools : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) { return testing::runCli(work_, capture_, args); }
  std::string path(const std::string& name) const { return work_.file(name); }
  std::vector<std::string> entries() const { return work_.entries(); }
  void put(const std::string& name, const std::string& text) {
    std::ofstream(path(name), std::ios::binary) << text;
  }

  testing::TempDir work_, capture_;
};

class CliSlice : public CliMeshTools {};
class CliCompare : public CliMeshTools {};

// ---------------------------------------------------------------------------------------
// slice

TEST_F(CliSlice, CylinderSectionsAsJsonOnStdoutAndInAFile) {
  testing::CylinderOptions o;  // radius 1, height 2, 64 segments
  writeMesh(testing::cylinderMesh(o), path("cyl.stl"));
  const CliRun r = run("slice cyl.stl --axis z --count 4");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json doc = Json::parse(r.out);
  EXPECT_EQ(doc["axis"], "z");
  ASSERT_EQ(doc["planes"].size(), 4u);
  const double n = o.segments;
  const double chordError = 1 - std::cos(M_PI / n);  // side quads: chords of the circle
  for (std::size_t i = 0; i < 4; ++i) {
    const Json& plane = doc["planes"][i];
    EXPECT_EQ(plane["index"], i);
    EXPECT_DOUBLE_EQ(plane["coordinate"].get<double>(), (i + 0.5) * 2 / 4);
    ASSERT_GE(plane["points"].size(), n);
    for (const Json& p : plane["points"]) {
      const double rho = std::hypot(p[0].get<double>(), p[1].get<double>());
      EXPECT_LE(rho, 1 + kFloatTolerance);
      EXPECT_GE(rho, 1 - chordError - kFloatTolerance);
      EXPECT_EQ(p[2], plane["coordinate"]);
    }
    const double polygonArea = 0.5 * n * std::sin(2 * M_PI / n);
    EXPECT_NEAR(plane["area"].get<double>(), polygonArea, kFloatTolerance);
    EXPECT_NEAR(plane["length"].get<double>(), 2 * n * std::sin(M_PI / n), kFloatTolerance);
  }
  // -o: the same document in a file, nothing on stdout.
  const CliRun w = run("slice cyl.stl --axis z --count 4 -o sections.json");
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_EQ(w.out, "");
  EXPECT_EQ(testing::readText(path("sections.json")), r.out);
  EXPECT_EQ(entries(), (std::vector<std::string>{"cyl.stl", "sections.json"}));
}

TEST_F(CliSlice, RangeAndOtherAxes) {
  writeMesh(testing::boxMesh({0, 0, 0}, {1, 2, 3}), path("box.obj"));
  const CliRun r = run("slice box.obj --axis y --count 3 --range 0 2");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json doc = Json::parse(r.out);
  EXPECT_EQ(doc["axis"], "y");
  ASSERT_EQ(doc["planes"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(doc["planes"][i]["coordinate"].get<double>(), 1.0 * i);
    EXPECT_NEAR(doc["planes"][i]["area"].get<double>(), 3.0, 1e-12);  // 1 × 3
    EXPECT_EQ(doc["planes"][i]["points"].size(), i == 1 ? 8u : 4u);   // + face diagonals
  }
}

TEST_F(CliSlice, ElephantSlices) {
  const std::string elephant = testing::cgalData("elephant.off");
  const CliRun r = run("slice " + testing::shellQuote(elephant) + " --axis x --count 30");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json doc = Json::parse(r.out);
  ASSERT_EQ(doc["planes"].size(), 30u);
  for (const Json& plane : doc["planes"]) {
    EXPECT_GE(plane["points"].size(), 3u);
    EXPECT_GT(plane["area"].get<double>(), 0.0);
  }
}

TEST_F(CliSlice, BadAxisIsAUsageError) {
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  const CliRun r = run("slice cyl.off --axis w --count 3 -o out.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "--axis")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"cyl.off"});
}

TEST_F(CliSlice, BadCountOrRangeIsAUsageError) {
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  for (const char* args :
       {"--count 0", "--count 3 --range 2 1", "--count 3 --range 1", "--count 2 --range 1 1"}) {
    const CliRun r = run(std::string("slice cyl.off --axis z ") + args + " -o out.json");
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"cyl.off"});
}

TEST_F(CliSlice, MissingFileNamesIt) {
  const CliRun r = run("slice nothing.off --axis z --count 3 -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "nothing.off")) << r.err;
  EXPECT_TRUE(entries().empty());
}

TEST_F(CliSlice, PlaneMissingTheMeshFailsAndLeavesNoFile) {
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  const CliRun r = run("slice cyl.off --axis z --count 4 --range 1 4 -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(
      contains(r.err, "cyl.off: plane 2 at z=3 does not meet the mesh (extent z in [0, 2])"))
      << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(entries(), std::vector<std::string>{"cyl.off"});
}

TEST_F(CliSlice, UnwritableOutputFailsNamingIt) {
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  const CliRun r = run("slice cyl.off --axis z --count 2 -o no/such/dir/out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "no/such/dir/out.json")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"cyl.off"});
}

TEST_F(CliSlice, OpenChainsOnlyFailsNamingThePlane) {
  testing::CylinderOptions slit;
  slit.caps = false;
  slit.slitSegments = 2;
  writeMesh(testing::cylinderMesh(slit), path("slit.ply"));
  const CliRun r = run("slice slit.ply --axis z --count 2 -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "slit.ply: plane 0 at z=0.5 has no closed loop")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"slit.ply"});
}

TEST_F(CliSlice, NearAndTrackPickOneOfTwoCylinders) {
  // The small cylinder (radius 1) round the z axis, the large one (radius 2) round x = 10.
  testing::CylinderOptions small, large;
  large.radius = 2.0;
  large.offset = {10, 0, 0};
  writeMesh(testing::merged(testing::cylinderMesh(small), testing::cylinderMesh(large)),
            path("two.off"));
  // Every point of every plane within `radius` of (cx, 0).
  auto around = [](const Json& doc, double cx, double radius) {
    EXPECT_EQ(doc["planes"].size(), 4u);
    for (const Json& plane : doc["planes"])
      for (const Json& p : plane["points"])
        EXPECT_LE(std::hypot(p[0].get<double>() - cx, p[1].get<double>()),
                  radius + kFloatTolerance);
  };
  const CliRun largest = run("slice two.off --axis z --count 4");
  ASSERT_EQ(largest.code, 0) << largest.err;
  around(Json::parse(largest.out), 10, 2);
  const CliRun near = run("slice two.off --axis z --count 4 --near 0.5 0 -9");
  ASSERT_EQ(near.code, 0) << near.err;
  around(Json::parse(near.out), 0, 1);
  const CliRun tracked = run("slice two.off --axis z --count 4 --near 0 0 0 --track -o s.json");
  ASSERT_EQ(tracked.code, 0) << tracked.err;
  EXPECT_EQ(testing::readText(path("s.json")), near.out);
  const CliRun trackLargest = run("slice two.off --axis z --count 4 --track");
  ASSERT_EQ(trackLargest.code, 0) << trackLargest.err;
  EXPECT_EQ(trackLargest.out, largest.out);
  // The help names both options.
  const CliRun help = run("slice --help");
  EXPECT_TRUE(contains(help.out, "--near")) << help.out;
  EXPECT_TRUE(contains(help.out, "--track")) << help.out;
}

TEST_F(CliSlice, BadNearIsAUsageError) {
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  for (const char* args : {"--near 1 2", "--near 1 2 x", "--near nan 0 0"}) {
    const CliRun r = run(std::string("slice cyl.off --axis z --count 2 ") + args + " -o out.json");
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "--near")) << args << "\n" << r.err;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"cyl.off"});
}

TEST_F(CliSlice, NearWithoutClosedLoopFailsNamingThePlane) {
  testing::CylinderOptions slit;
  slit.caps = false;
  slit.slitSegments = 2;
  writeMesh(testing::cylinderMesh(slit), path("slit.ply"));
  const CliRun r = run("slice slit.ply --axis z --count 2 --near 0 0 0 --track -o out.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "slit.ply: plane 0 at z=0.5 has no closed loop")) << r.err;
  EXPECT_EQ(entries(), std::vector<std::string>{"slit.ply"});
}

// ---------------------------------------------------------------------------------------
// compare

TEST_F(CliCompare, ModelAgainstItsOwnMeshAndAShiftedCopy) {
  put("m.json", kOneFrame);
  ASSERT_EQ(run("build m.json -o m.off -q").code, 0);
  const CliRun same = run("compare m.json m.off --json");
  ASSERT_EQ(same.code, 0) << same.err;
  const Json s = Json::parse(same.out);
  EXPECT_LE(s["hausdorff_relative"].get<double>(), kFloatTolerance);

  // Every point of the flat square is 0.25 from its copy raised by 0.25, both ways.
  Mesh shifted = readMesh(path("m.off"));
  for (std::size_t v = 0; v < shifted.vertexCount(); ++v) shifted.positions[3 * v + 2] += 0.25f;
  writeMesh(shifted, path("up.off"));
  const CliRun r = run("compare m.json up.off --json --resolution 9");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json d = Json::parse(r.out);
  EXPECT_EQ(d["resolution"], 9);
  EXPECT_NEAR(d["diagonal"].get<double>(), 2 * std::sqrt(2.0), kFloatTolerance);
  for (const char* way : {"model_to_mesh", "mesh_to_model"})
    for (const char* key : {"rms", "mean", "max"}) {
      EXPECT_NEAR(d[way][key].get<double>(), 0.25, kFloatTolerance) << way << " " << key;
      EXPECT_NEAR(d[way][std::string(key) + "_relative"].get<double>(), 0.25 / (2 * std::sqrt(2.0)),
                  kFloatTolerance)
          << way << " " << key;
    }
  EXPECT_NEAR(d["hausdorff"].get<double>(), 0.25, kFloatTolerance);

  const CliRun text = run("compare m.json up.off");
  ASSERT_EQ(text.code, 0) << text.err;
  for (const char* word : {"model -> mesh  RMS 0.25 (8.84%)", "mesh -> model  RMS 0.25 (8.84%)",
                           "Hausdorff      0.25 (8.84%)", "bounding-box diagonal 2.82843"})
    EXPECT_TRUE(contains(text.out, word)) << word << "\n" << text.out;
}

// A B-spline and a spectral model against their own tessellation: the normals agree
// everywhere, and the line and the JSON say so.
TEST_F(CliCompare, NormalsOfBSplineAndSpectralModels) {
  for (const char* file : {"bspline-dome.json", "vase.json"}) {
    SCOPED_TRACE(file);
    const std::string model = testing::example(file);
    ASSERT_EQ(run("build " + model + " -o own.off -q --resolution 9").code, 0);
    const CliRun text = run("compare " + model + " own.off --resolution 9");
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_TRUE(contains(text.out, "normals        folded 0% of the model's area, RMS deviation "))
        << text.out;
    const CliRun r = run("compare " + model + " own.off --resolution 9 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const Json n = Json::parse(r.out)["normals"];
    EXPECT_EQ(n["folded_area"].get<double>(), 0.0);
    EXPECT_LT(n["rms_degrees"].get<double>(), kNormalDegreesTolerance);
    EXPECT_FALSE(n["reversed"].get<bool>());
  }
}

TEST_F(CliCompare, MissingFilesAreNamed) {
  put("m.json", kOneFrame);
  CliRun r = run("compare m.json nothing.off");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "nothing.off")) << r.err;
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  r = run("compare nothing.json cyl.off");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "nothing.json")) << r.err;
}

TEST_F(CliCompare, UsageErrors) {
  put("m.json", kOneFrame);
  writeMesh(testing::cylinderMesh({}), path("cyl.off"));
  for (const char* args : {"m.json", "m.json cyl.off --resolution 1", "m.json cyl.off --samples 0",
                           "m.json cyl.off --seed-frame 3"}) {
    const CliRun r = run(std::string("compare ") + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  }
}

TEST_F(CliCompare, HelpNamesTheOptions) {
  const CliRun r = run("compare --help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* word : {"model", "mesh", "--resolution", "--samples", "--json", "--solver"})
    EXPECT_TRUE(contains(r.out, word)) << word << "\n" << r.out;
  const CliRun s = run("slice --help");
  EXPECT_EQ(s.code, 0) << s.err;
  for (const char* word : {"mesh", "--axis", "--count", "--range", "-o,--output"})
    EXPECT_TRUE(contains(s.out, word)) << word << "\n" << s.out;
}

}  // namespace
}  // namespace pdesurf
