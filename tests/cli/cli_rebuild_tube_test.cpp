// `pdesurf rebuild --as vertex-frames --tube RINGS SECTORS`: the real binary on a part of
// CGAL's elephant, the model it writes, and its errors (status, message, no file).
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "pdesurf/model_io.hpp"
#include "support/cgal_data.hpp"
#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

using testing::CliRun;

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

class CliRebuildTube : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) { return testing::runCli(work_, capture_, args); }
  std::string path(const std::string& name) const { return work_.file(name); }
  std::string elephant() const { return testing::shellQuote(testing::cgalData("elephant.off")); }
  testing::TempDir work_, capture_;
};

/// The standing leg of docs/rebuild.md.
const std::string kLeg = " --axis y --range -0.45 -0.32 --near 0.117 -0.4 -0.045";

TEST_F(CliRebuildTube, FitsRingsAndSectorsToTheLegAndWritesTheModelAndPart) {
  const CliRun r = run("rebuild " + elephant() + " --as vertex-frames --tube 2 5" + kLeg +
                       " -o leg.json --part part.obj");
  ASSERT_EQ(r.code, 0) << r.err;
  const VertexFrameModel model = loadVertexFrameModel(path("leg.json"));
  EXPECT_EQ(model.frames.size(), 10u);
  EXPECT_EQ(model.vertices.size(), 3u * 10u + 2u * 5u);  // (R + 1)·2S + R·S
  // Measured against the part between the end planes, not the whole elephant.
  EXPECT_TRUE(contains(r.out, "(the part between the end planes)")) << r.out;
  EXPECT_TRUE(std::ifstream(path("part.obj")).good());
}

TEST_F(CliRebuildTube, BadTubesExitNamingTheProblemAndWriteNothing) {
  // Two sectors would join along both sides: a usage error.
  CliRun r = run("rebuild " + elephant() + " --as vertex-frames --tube 2 2" + kLeg + " -o t.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "at least 3 sectors")) << r.err;
  // Without --near the planes cut two legs: refused naming the plane.
  r = run("rebuild " + elephant() +
          " --as vertex-frames --tube 2 5 --axis y --range -0.45 -0.4 -o t.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "plane 0 at y=-0.45 cuts 2 closed loops")) << r.err;
  // --tube with --grid: one layout only.
  r = run("rebuild " + elephant() + " --as vertex-frames --tube 2 5 --grid 2 2 -o t.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(std::ifstream(path("t.json")).good());
}

}  // namespace
}  // namespace pdesurf
