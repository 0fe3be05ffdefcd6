// Model measurements: storage under the seed's Table 1 convention, coincident vertices.
#include <gtest/gtest.h>

#include <string>

#include "pdesurf/analysis.hpp"

namespace pdesurf {
namespace {

VertexFrameModel unitFrame() {
  VertexFrameModel m;
  m.vertices = {{0, 0, 0}, {0.5, 0, 0.1}, {1, 0, 0}, {1, 0.5, 0.1},
                {1, 1, 0}, {0.5, 1, 0.1}, {0, 1, 0}, {0, 0.5, 0.1}};
  Frame f;
  f.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
  m.frames = {f};
  return m;
}

TEST(Storage, CountsEveryNumberAtSixSignificantDigitsWithOneSeparator) {
  VertexFrameModel m = unitFrame();
  const std::string vertices =
      "0 0 0\n0.5 0 0.1\n1 0 0\n1 0.5 0.1\n1 1 0\n0.5 1 0.1\n0 1 0\n0 0.5 0.1\n";
  EXPECT_EQ(storageBytes(m), (vertices + "0 1 2 3 4 5 6 7 1 1 1 1 1 1\n").size());
  // A force adds f0 and its region; 1/3 is written as 0.333333 (six significant digits).
  m.frames[0].forces.push_back({Vec3(1.0 / 3.0, 0, -2), Region{0.25, 0.75, 0, 1}});
  EXPECT_EQ(storageBytes(m),
            (vertices + "0 1 2 3 4 5 6 7 1 1 1 1 1 1 0.333333 0 -2 0.25 0.75 0 1\n").size());
}

TEST(Coincident, CountsUsedVerticesAtTheSamePositionUnderAnotherIndex) {
  VertexFrameModel m = unitFrame();
  EXPECT_EQ(coincidentVertices(m), 0u);
  m.vertices.push_back(m.vertices[2]);  // unused duplicate: not counted
  EXPECT_EQ(coincidentVertices(m), 0u);
  Frame g;
  g.vertices = {8, 1, 0, 7, 6, 5, 4, 3};  // uses the duplicate of vertex 2
  m.frames.push_back(g);
  EXPECT_EQ(coincidentVertices(m), 1u);
}

}  // namespace
}  // namespace pdesurf
