// The error hierarchy (include/pdesurf/error.hpp): what() composed of file, JSON path and
// message, and a sample of the library's entry points given bad input, each throwing an
// Error of its kind with the parts it should name.
#include "pdesurf/error.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/sections.hpp"
#include "pdesurf/spectral.hpp"
#include "pdesurf/transform.hpp"
#include "support/caught_error.hpp"

namespace pdesurf {
namespace {

using testing::caughtError;

/// A folder that does not exist: files in it can be neither read nor written.
const std::string kMissingFolder = "/nonexistent-pdesurf-folder";

TEST(Error, WhatJoinsFilePathAndMessageLeavingOutEmptyParts) {
  EXPECT_STREQ(Error("m.json", "$.frames[2]", "bad").what(), "m.json: $.frames[2]: bad");
  EXPECT_STREQ(Error("m.json", "", "bad").what(), "m.json: bad");
  EXPECT_STREQ(Error("", "$.a", "bad").what(), "$.a: bad");
  EXPECT_STREQ(Error("bad").what(), "bad");
  const Error e("m.json", "$.a", "bad");
  EXPECT_EQ(e.file(), "m.json");
  EXPECT_EQ(e.jsonPath(), "$.a");
  EXPECT_EQ(e.message(), "bad");
  // The kinds keep their accessors, and what() reads as before the hierarchy.
  const ModelError model("m.json", "$.a", "bad");
  EXPECT_EQ(model.problem(), "bad");
  EXPECT_STREQ(model.what(), "m.json: $.a: bad");
  const SectionError section(3, "encloses no area");
  EXPECT_EQ(section.section(), 3u);
  EXPECT_EQ(section.reason(), "encloses no area");
  EXPECT_STREQ(section.what(), "section 3: encloses no area");
  EXPECT_STREQ(MeshIoError("a.obj", "line 2: bad").what(), "a.obj: line 2: bad");
}

TEST(Error, AMalformedModelNamesItsFileAndJsonPath) {
  const auto e = caughtError<ModelError>(
      [] { parseModel(R"({"type": "vertex-frames", "vertices": 3})", "m.json"); });
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->ofKind);
  EXPECT_EQ(e->file, "m.json");
  EXPECT_EQ(e->jsonPath, "$.vertices");
  EXPECT_EQ(e->message, "expected an array, found a number");
  EXPECT_EQ(e->what, "m.json: $.vertices: expected an array, found a number");
}

TEST(Error, BadArgumentsOfTheEnginesAreInvalidArguments) {
  struct Case {
    const char* what;
    std::function<void()> call;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"a spectral operator of N = 0",
       [] {
         SpectralOperator op;
         op.power = 0;
         op.validate();
       },
       "Ugail operator needs N >= 1, got N = 0"},
      {"a B-spline boundary of nu = 2",
       [] {
         BSplineBoundary boundary;
         boundary.nu = 2;
         boundaryNet(boundary);
       },
       "boundaryNet: nu = 2, nv = 3; both last indices must be at least 3"},
      {"a scaling by 0", [] { AffineMap::scalingAbout(0.0, Vec3::Zero()); },
       "scale 0 is not a finite number above 0"},
      {"a slice range that is empty",
       [] {
         SliceOptions options;
         options.count = 3;
         options.range = {1.0, 1.0};
         slicePlanes(options, 0.0, 1.0);
       },
       ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto e = caughtError<InvalidArgument>(c.call);
    ASSERT_TRUE(e);
    EXPECT_TRUE(e->ofKind);
    EXPECT_EQ(e->file, "");
    EXPECT_EQ(e->jsonPath, "");
    EXPECT_FALSE(e->message.empty());
    if (!c.message.empty()) EXPECT_EQ(e->message, c.message);
    EXPECT_EQ(e->what, e->message);
  }
}

TEST(Error, ASectionThatIsNoCurveIsASectionError) {
  const std::vector<std::vector<Vec3>> loops = {
      {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
      {{1, 0, 1}, {0, 1, 1}},
  };
  const auto e = caughtError<SectionError>([&] { prepareSections(loops, {}); });
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->ofKind);
  EXPECT_EQ(e->message, "section 1: has 2 distinct points; a closed curve needs at least 3");
  EXPECT_EQ(e->what, e->message);
  // A bad argument: an InvalidArgument as well.
  EXPECT_TRUE(caughtError<InvalidArgument>([&] { prepareSections(loops, {}); })->ofKind);
}

TEST(Error, AMeshWithNothingToSliceIsAMeshSliceError) {
  const auto e = caughtError<MeshSliceError>([] { sliceMesh(Mesh{}, SliceOptions{}); });
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->ofKind);
  EXPECT_EQ(e->message, "cannot slice a mesh with no triangles");
}

TEST(Error, FilesThatCannotBeReadOrWrittenAreNamedInFile) {
  const std::string missing = kMissingFolder + "/a.obj";
  const auto read = caughtError<MeshIoError>([&] { readMesh(missing); });
  ASSERT_TRUE(read);
  EXPECT_TRUE(read->ofKind);
  EXPECT_EQ(read->file, missing);
  EXPECT_EQ(read->message.rfind("cannot open: ", 0), 0u) << read->message;
  EXPECT_EQ(read->what, missing + ": " + read->message);

  const auto format = caughtError<MeshIoError>([] { meshFormatFromPath("a.xyz"); });
  ASSERT_TRUE(format);
  EXPECT_EQ(format->file, "a.xyz");
  EXPECT_EQ(format->message, "unknown mesh format '.xyz' (use .obj, .ply, .stl, .glb or .off)");

  const std::string target = kMissingFolder + "/m.json";
  const auto write = caughtError<FileError>([&] { writeFileAtomically(target, "{}"); });
  ASSERT_TRUE(write);
  EXPECT_TRUE(write->ofKind);
  EXPECT_EQ(write->file, target);
  EXPECT_EQ(write->what, target + ": " + write->message);
}

TEST(Error, ASolveOptionTheModelCannotTakeIsAnInvalidArgument) {
  const AnyModel model = loadModel(PDESURF_SOURCE_DIR "/examples/mug.json");
  SolveOptions options;
  options.vertexFrames.seedFrame = 1000000;
  const auto e = caughtError<InvalidArgument>([&] { checkSolveOptions(model, options); });
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->ofKind);
  EXPECT_EQ(e->message.rfind("out of range, the model has ", 0), 0u) << e->message;
}

}  // namespace
}  // namespace pdesurf
