// A layout's errors are pdesurf::Errors naming the mesh they come from (include/pdesurf/error.hpp).
#include <gtest/gtest.h>

#include "pdesurf/rebuild.hpp"
#include "support/caught_error.hpp"

namespace pdesurf {
namespace {

using testing::caughtError;

TEST(LayoutError, AFaceThatIsNoQuadNamesTheMeshTheFaceAndWhy) {
  PolygonMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}, {0, 1, 2}};
  const auto e = caughtError<LayoutError>([&] { quadLayout(mesh, "quads.obj"); });
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->ofKind);
  EXPECT_EQ(e->file, "quads.obj");
  EXPECT_EQ(e->jsonPath, "");
  EXPECT_EQ(e->message,
            "face 1 has 3 corners: a vertex-frame layout takes quads only (one frame per quad)");
  EXPECT_EQ(e->what, "quads.obj: " + e->message);
}

}  // namespace
}  // namespace pdesurf
