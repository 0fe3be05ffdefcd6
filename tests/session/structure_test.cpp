// Structure edits of vertex-frame models (session.hpp: extrude, add, delete, split, weld,
// flip) and new models: each edit's validation, its effect, and that undo restores the model's
// file byte for byte.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pdesurf/analysis.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf {
namespace {

VertexFrameModel newModel(NewModelOptions::Kind kind, std::uint32_t u, std::uint32_t v) {
  NewModelOptions o;
  o.kind = kind;
  o.u = u;
  o.v = v;
  return newFrameModel(o);
}

/// Edges run by two frames.
std::size_t sharedEdges(const VertexFrameModel& m) {
  const FrameTopology t = buildTopology(m);
  return std::count_if(t.edges.begin(), t.edges.end(),
                       [](const ModelEdge& e) { return e.sideCount == 2; });
}

std::size_t boundaryEdges(const VertexFrameModel& m) {
  const FrameTopology t = buildTopology(m);
  return std::count_if(t.edges.begin(), t.edges.end(),
                       [](const ModelEdge& e) { return e.sideCount == 1 && !e.collapsed(); });
}

double relativeGap(const VertexFrameModel& m) {
  const VertexFrameSurface s = solve(m);
  const double diagonal = surfaceBounds(s).diagonal();
  return measureC0Gap(s).maxGap / diagonal;
}

/// Every frame faces the way of frame 0 (none is mirrored against its connected part).
bool facesOneWay(const VertexFrameModel& m) {
  const FrameTopology t = buildTopology(m);
  return t.orientable && std::all_of(t.flipped.begin(), t.flipped.end(),
                                     [&](std::uint8_t f) { return f == t.flipped[0]; });
}

/// Applies an edit given as JSON, as the studio does.
void applyJson(ModelSession& s, std::string_view json) {
  s.apply(parseFrameEdit(json, *s.frames()).edit);
}

/// The problem a refused edit reports, and that it changed nothing.
std::string refusal(ModelSession& s, std::string_view json) {
  const std::string before = serializeModel(s.model());
  const std::uint64_t revision = s.revision();
  const std::size_t undo = s.undoDepth();
  try {
    applyJson(s, json);
  } catch (const ModelError& e) {
    EXPECT_EQ(serializeModel(s.model()), before) << json;
    EXPECT_EQ(s.revision(), revision) << json;
    EXPECT_EQ(s.undoDepth(), undo) << json;
    return e.problem();
  }
  ADD_FAILURE() << "not refused: " << json;
  return "";
}

bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

TEST(NewModel, SingleGridAndTube) {
  const VertexFrameModel one = newModel(NewModelOptions::Kind::Single, 5, 5);
  EXPECT_EQ(one.frames.size(), 1u);
  EXPECT_EQ(one.vertices.size(), 8u);  // the 3 × 3 lattice but its centre, which no frame uses
  const VertexFrameModel grid = newModel(NewModelOptions::Kind::Grid, 3, 2);
  EXPECT_EQ(grid.frames.size(), 6u);
  EXPECT_EQ(grid.vertices.size(), 7u * 5 - 6);    // the 7 × 5 lattice but the 6 frame centres
  EXPECT_EQ(sharedEdges(grid), 2u * 2 + 3u * 1);  // (u - 1) v inner columns, u (v - 1) rows
  EXPECT_TRUE(facesOneWay(grid));
  const VertexFrameModel tube = newModel(NewModelOptions::Kind::Tube, 4, 2);
  EXPECT_EQ(tube.frames.size(), 8u);
  EXPECT_EQ(tube.vertices.size(), 8u * 5 - 8);  // 8 round × 5 along, but the 8 frame centres
  // Every vertex of a new model belongs to a frame (no handle that moves nothing).
  for (const VertexFrameModel* m : {&one, &grid, &tube}) {
    std::vector<int> uses(m->vertices.size(), 0);
    for (const Frame& f : m->frames)
      for (const std::uint32_t v : f.vertices) ++uses[v];
    EXPECT_EQ(std::count(uses.begin(), uses.end(), 0), 0);
  }
  EXPECT_EQ(boundaryEdges(tube), 2u * 4);  // only the two rims
  EXPECT_TRUE(facesOneWay(tube));
  EXPECT_LT(relativeGap(tube), kC0RelativeTolerance);
  // What a file would be refused for, a new model is not.
  EXPECT_NO_THROW(parseVertexFrameModel(serializeVertexFrameModel(tube), "tube"));
}

TEST(NewModel, RefusesCountsAndSizesOutOfRange) {
  NewModelOptions o;
  o.kind = NewModelOptions::Kind::Tube;
  o.u = 2;
  EXPECT_THROW(newFrameModel(o), ModelError);
  o.u = 3;
  o.size = 0;
  EXPECT_THROW(newFrameModel(o), ModelError);
  o.size = 1;
  o.v = NewModelOptions::kMaxFrames + 1;
  EXPECT_THROW(newFrameModel(o), ModelError);
}

TEST(Structure, ExtrudeTwiceBuildsAnLShape) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Single, 1, 1)));
  applyJson(s, R"({"op":"extrude","edges":[{"frame":0,"side":1}]})");  // u = 1
  applyJson(s, R"({"op":"extrude","edges":[{"frame":1,"side":2}]})");  // v = 1 of the new frame
  const VertexFrameModel& m = *s.frames();
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_EQ(sharedEdges(m), 2u);
  EXPECT_TRUE(facesOneWay(m));
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  // The first new frame is the first moved across its u = 1 side: its P1 is frame 0's P3,
  // its P3 at x = 2.
  EXPECT_EQ(m.frames[1].vertices[0], m.frames[0].vertices[2]);
  EXPECT_EQ(m.vertices[m.frames[1].vertices[2]], Vec3(2, 0, 0));
  // The second reaches up from frame 1's v = 1 side by frame 1's height.
  EXPECT_EQ(m.frames[2].vertices[0], m.frames[1].vertices[6]);
  EXPECT_EQ(m.vertices[m.frames[2].vertices[4]], Vec3(2, 2, 0));
  EXPECT_EQ(s.undoDepth(), 2u);
}

TEST(Structure, ExtrudingAChainSharesTheWalls) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Grid, 2, 1)));
  const std::size_t vertices = s.frames()->vertices.size();
  applyJson(
      s, R"({"op":"extrude","edges":[{"frame":0,"side":0},{"frame":1,"side":0}],"distance":0.5})");
  const VertexFrameModel& m = *s.frames();
  EXPECT_EQ(m.frames.size(), 4u);
  EXPECT_EQ(sharedEdges(m), 4u);  // the old seam, two edges extruded, the new wall
  // 3 far corners, 3 wall middles and 2 far middles.
  EXPECT_EQ(m.vertices.size(), vertices + 8);
  EXPECT_TRUE(facesOneWay(m));
  EXPECT_EQ(m.vertices[m.frames[2].vertices[0]].y(), -0.5);  // reaching away, by distance
}

TEST(Structure, ExtrudeRefusesInnerEdgesAndPoles) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Grid, 2, 1)));
  EXPECT_TRUE(contains(refusal(s, R"({"op":"extrude","edges":[{"frame":0,"side":1}]})"),
                       "not on the boundary: frame 1 shares it"));
  EXPECT_TRUE(contains(
      refusal(s, R"({"op":"extrude","edges":[{"frame":0,"side":0},{"frame":0,"side":0}]})"),
      "listed twice"));
  std::string path;
  try {
    parseFrameEdit(R"({"op":"extrude","edges":[{"frame":0,"side":4}]})", *s.frames());
  } catch (const ModelError& e) {
    path = e.jsonPath();
  }
  EXPECT_EQ(path, "$.edges[0].side");
}

TEST(Structure, DeleteThenAddFrameRestoresTheSharedEdges) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Grid, 3, 1)));
  const VertexFrameModel grid = *s.frames();
  applyJson(s, R"({"op":"delete-frames","frames":[1]})");
  EXPECT_EQ(s.frames()->frames.size(), 2u);
  EXPECT_EQ(sharedEdges(*s.frames()), 0u);
  // Only the middle vertices of its own sides went (its other sides are its neighbours').
  EXPECT_EQ(s.frames()->vertices.size(), grid.vertices.size() - 2);
  // The gap's corners, given clockwise: the frame is turned to face as its neighbours.
  const VertexFrameModel& m = *s.frames();
  const std::uint32_t a = m.frames[0].vertices[2], b = m.frames[1].vertices[0],
                      c = m.frames[1].vertices[6], d = m.frames[0].vertices[4];
  applyJson(s, fmt::format(R"({{"op":"add-frame","corners":[{},{},{},{}]}})", a, d, c, b));
  EXPECT_EQ(s.frames()->frames.size(), 3u);
  EXPECT_EQ(sharedEdges(*s.frames()), 2u);
  EXPECT_TRUE(facesOneWay(*s.frames()));
  EXPECT_LT(relativeGap(*s.frames()), kC0RelativeTolerance);
  EXPECT_EQ(s.frames()->vertices.size(), grid.vertices.size());  // two new middles
  EXPECT_TRUE(contains(refusal(s, R"({"op":"add-frame","corners":[0,1,1,2]})"), "given twice"));
  EXPECT_TRUE(contains(
      refusal(s, fmt::format(R"({{"op":"add-frame","corners":[{},{},{},{}]}})", a, d, c, b)),
      "would join 3 frames"));
}

TEST(Structure, DeleteKeepsSharedForcesOnTheFramesLeftAndOneFrame) {
  VertexFrameModel grid = newModel(NewModelOptions::Kind::Grid, 3, 1);
  grid.forces = {{Vec3(0, 0, 1), {0, 2}}, {Vec3(0, 0, 2), {1}}};
  ModelSession s(AnyModel(std::move(grid)));
  applyJson(s, R"({"op":"delete-frames","frames":[1]})");
  ASSERT_EQ(s.frames()->forces.size(), 1u);
  EXPECT_EQ(s.frames()->forces[0].frames, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_TRUE(
      contains(refusal(s, R"({"op":"delete-frames","frames":[0,1]})"), "at least one frame"));
  EXPECT_TRUE(contains(refusal(s, R"({"op":"delete-frames","frames":[0,0]})"), "listed twice"));
}

/// A curved 3 × 3 grid: its inner vertices lifted, so a split has a surface to follow.
VertexFrameModel curvedGrid() {
  VertexFrameModel m = newModel(NewModelOptions::Kind::Grid, 3, 3);
  for (Vec3& p : m.vertices) p.z() = 0.3 * std::sin(p.x()) * std::cos(0.7 * p.y());
  return m;
}

TEST(Structure, SplitCutsThroughTheNeighboursWithVerticesOnTheSurface) {
  const VertexFrameModel before = curvedGrid();
  ModelSession s{AnyModel(before)};
  const VertexFrameSurface old = solve(before);
  applyJson(s, R"({"op":"split-frame","frame":4,"parts":4})");  // the centre
  const VertexFrameModel& m = *s.frames();
  // The centre becomes 4, its row and column 2 each: 9 + 3 + 4 × 1.
  EXPECT_EQ(m.frames.size(), 16u);
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  EXPECT_TRUE(facesOneWay(m));
  // Every new vertex lies on the old surface: on the centre frame at u, v in quarters.
  const VertexFramePatch& centre = old.patches[4];
  for (std::size_t v = before.vertices.size(); v < m.vertices.size(); ++v) {
    double nearest = 1e300;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i)
        for (std::uint32_t k = 0; k < 9; ++k)
          nearest =
              std::min(nearest, (old.patches[k].position(i / 4.0, j / 4.0) - m.vertices[v]).norm());
    // A new vertex is computed from one patch's closed form: exact to rounding.
    EXPECT_LT(nearest, kC0RelativeTolerance) << "vertex " << v;
  }
  // The centre's first quarter is the old centre's [0, ½]²: its middle point moved little.
  const Vec3 was = centre.position(0.25, 0.25), now = solve(m).patches[4].position(0.5, 0.5);
  EXPECT_LT((was - now).norm(), 0.05) << "the split changed the shape by " << (was - now).norm();
}

/// The vertices no frame uses.
std::size_t unusedVertices(const VertexFrameModel& m) {
  std::vector<bool> used(m.vertices.size(), false);
  for (const Frame& f : m.frames)
    for (std::uint32_t v : f.vertices) used[v] = true;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
}

TEST(Structure, SplitAddsNoVertexThatNoFrameUses) {
  // A part's centre is no frame's vertex: a split must not add it (it would show as a
  // handle, be saved, and take a click meant for the part).
  for (const auto& [parts, vertices] : {std::pair{"\"parts\":4", 21u},
                                        {"\"parts\":2,\"across\":\"u\"", 13u},
                                        {"\"parts\":2,\"across\":\"v\"", 13u}}) {
    ModelSession s{AnyModel(newModel(NewModelOptions::Kind::Single, 1, 1))};
    applyJson(s, fmt::format(R"({{"op":"split-frame","frame":0,{}}})", parts));
    EXPECT_EQ(unusedVertices(*s.frames()), 0u) << parts;
    EXPECT_EQ(s.frames()->vertices.size(), vertices) << parts;
  }
  ModelSession grid{AnyModel(curvedGrid())};
  applyJson(grid, R"({"op":"split-frame","frame":4,"parts":4})");
  EXPECT_EQ(unusedVertices(*grid.frames()), 0u);
}

TEST(Structure, SplitSeveralFramesAtOnceKeepsEdgesSharedInOneUndoStep) {
  // Frames 0 (a corner) and 4 (the centre) of a 3 × 3 grid, each into 2 × 2: their loop cuts
  // run through columns 0 and 1 and rows 0 and 1. Frame (a, b) becomes (a < 2 ? 2 : 1) ×
  // (b < 2 ? 2 : 1) frames: 4 × 4 + 2 × 2 + 2 × 2 + 1 = 25.
  const VertexFrameModel before = curvedGrid();
  ModelSession s{AnyModel(before)};
  const std::string file = serializeModel(s.model());
  const VertexFrameSurface old = solve(before);
  applyJson(s, R"({"op":"split-frame","frames":[0,4],"parts":4})");
  const VertexFrameModel& m = *s.frames();
  EXPECT_EQ(m.frames.size(), 25u);
  // The lattice of a 5 × 5 grid of frames (11 × 11 points) less the 25 frame centres.
  EXPECT_EQ(m.vertices.size(), 11u * 11u - 25u);
  EXPECT_EQ(unusedVertices(m), 0u);
  // Only the outer boundary is a boundary: every inner edge is shared by two frames.
  EXPECT_EQ(boundaryEdges(m), 4u * 5u);
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  EXPECT_TRUE(facesOneWay(m));
  // The edit is one undo step, back to the file byte for byte.
  EXPECT_EQ(s.undoDepth(), 1u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), file);

  // Subdivide all: every frame into 2 × 2, the shape kept (new vertices on the old surface).
  applyJson(s, R"({"op":"split-frame","frames":[0,1,2,3,4,5,6,7,8],"parts":4})");
  const VertexFrameModel& all = *s.frames();
  EXPECT_EQ(all.frames.size(), 36u);
  EXPECT_EQ(all.vertices.size(), 13u * 13u - 36u);
  EXPECT_EQ(unusedVertices(all), 0u);
  EXPECT_LT(relativeGap(all), kC0RelativeTolerance);
  for (std::size_t v = before.vertices.size(); v < all.vertices.size(); ++v) {
    double nearest = 1e300;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i)
        for (const VertexFramePatch& p : old.patches)
          nearest = std::min(nearest, (p.position(i / 4.0, j / 4.0) - all.vertices[v]).norm());
    // A new vertex is computed from one patch's closed form: exact to rounding.
    EXPECT_LT(nearest, kC0RelativeTolerance) << "vertex " << v;
  }
  EXPECT_TRUE(
      contains(refusal(s, R"({"op":"split-frame","frames":[1,1],"parts":4})"), "listed twice"));
}

TEST(Structure, SplitInTwoOnATubeRunsAlongItAndKeepsForcesInsideAPart) {
  VertexFrameModel tube = newModel(NewModelOptions::Kind::Tube, 4, 3);
  tube.frames[0].forces = {{Vec3(0, 0, 1), {0.1, 0.4, 0.2, 0.9}}};
  ModelSession s(AnyModel(std::move(tube)));
  applyJson(s, R"({"op":"split-frame","frame":0,"parts":2,"across":"u"})");
  // A cut across u crosses v = 0 and v = 1: it runs along the tube (3 frames), not round it.
  EXPECT_EQ(s.frames()->frames.size(), 12u + 3u);
  EXPECT_EQ(boundaryEdges(*s.frames()), 2u * 5);
  EXPECT_LT(relativeGap(*s.frames()), kC0RelativeTolerance);
  const FrameForce& f = s.frames()->frames[0].forces.at(0);  // u in [0, ½] → [0, 1]
  EXPECT_DOUBLE_EQ(f.region.u0, 0.2);
  EXPECT_DOUBLE_EQ(f.region.u1, 0.8);
  s.undo();
  VertexFrameModel across = *s.frames();
  across.frames[0].forces = {{Vec3(0, 0, 1), {0.3, 0.7, 0.2, 0.9}}};
  ModelSession t{AnyModel(std::move(across))};
  EXPECT_TRUE(contains(refusal(t, R"({"op":"split-frame","frame":0,"parts":2,"across":"u"})"),
                       "through this force's region"));
}

TEST(Structure, MirrorFramesCopiesAcrossThePlaneAndWeldsTheSeam) {
  // One frame on x in [0, 1] with a force; mirrored across x = 0, the copy shares the three
  // vertices on the plane (P1, P8, P7), and the surface is the mirror image of the original.
  VertexFrameModel one = newModel(NewModelOptions::Kind::Single, 1, 1);
  for (Vec3& p : one.vertices) p.z() = 0.2 * p.x() * p.y();  // not flat, not symmetric in u
  one.frames[0].forces = {{Vec3(1, 0, 2), {0.1, 0.4, 0.2, 0.7}}};
  ModelSession s{AnyModel(one)};
  const std::string file = serializeModel(s.model());
  applyJson(s, R"({"op":"mirror-frames","frames":[0],"axis":"x"})");
  const VertexFrameModel& m = *s.frames();
  ASSERT_EQ(m.frames.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 8u + 5u);
  EXPECT_EQ(sharedEdges(m), 1u);
  EXPECT_EQ(boundaryEdges(m), 6u);
  EXPECT_TRUE(facesOneWay(m));
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  const FrameForce& f = m.frames[1].forces.at(0);  // f0 mirrored, u reversed
  EXPECT_EQ(f.f0, Vec3(-1, 0, 2));
  EXPECT_DOUBLE_EQ(f.region.u0, 0.6);
  EXPECT_DOUBLE_EQ(f.region.u1, 0.9);
  const VertexFrameSurface surface = solve(m);
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      Vec3 p = surface.patches[0].position(i / 4.0, j / 4.0);
      p.x() = -p.x();
      const Vec3 q = surface.patches[1].position(1.0 - i / 4.0, j / 4.0);
      // The copy's closed form is the original's with x negated: equal to rounding.
      EXPECT_LT((p - q).norm(), kC0RelativeTolerance) << i << ", " << j;
    }
  EXPECT_EQ(s.undoDepth(), 1u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), file);
  // Mirrored onto a copy already there, the seam would join three frames: refused.
  applyJson(s, R"({"op":"mirror-frames","frames":[0],"axis":"x"})");
  EXPECT_TRUE(
      contains(refusal(s, R"({"op":"mirror-frames","frames":[0],"axis":"x"})"), "3 frames"));
  EXPECT_TRUE(
      contains(refusal(s, R"({"op":"mirror-frames","frames":[0],"axis":"w"})"), "expected \"x\""));
}

TEST(Structure, MirrorFramesAcrossAnOffsetPlaneSharesItsVertices) {
  // The frame on x in [0, 1] mirrored across x = 1 (the plane through the centre of a model
  // of it and its copy to come): the three vertices on x = 1 are shared, every other copied
  // to (2 - x, y, z), and a force's f0 (a vector) turned, not moved with the plane.
  VertexFrameModel one = newModel(NewModelOptions::Kind::Single, 1, 1);
  for (Vec3& p : one.vertices) p.z() = 0.2 * p.x() * p.y();
  one.frames[0].forces = {{Vec3(1, 0, 2), {0.1, 0.4, 0.2, 0.7}}};
  ModelSession s{AnyModel(one)};
  applyJson(s, R"({"op":"mirror-frames","frames":[0],"axis":"x","at":1})");
  const VertexFrameModel& m = *s.frames();
  ASSERT_EQ(m.frames.size(), 2u);
  ASSERT_EQ(m.vertices.size(), 8u + 5u);
  EXPECT_EQ(sharedEdges(m), 1u);
  EXPECT_TRUE(facesOneWay(m));
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  for (std::size_t i = 0; i < 8; ++i) {
    const std::uint32_t v = one.frames[0].vertices[i];
    const Vec3 p = one.vertices[v];
    if (p.x() == 1.0) {
      // On the plane: the copy uses the original vertex itself.
      EXPECT_NE(std::find(m.frames[1].vertices.begin(), m.frames[1].vertices.end(), v),
                m.frames[1].vertices.end())
          << "vertex " << v << " on x = 1 is not shared";
    } else {
      const Vec3 image(2.0 - p.x(), p.y(), p.z());
      const bool found = std::any_of(m.vertices.begin() + 8, m.vertices.end(),
                                     [&](const Vec3& q) { return q == image; });
      EXPECT_TRUE(found) << "no copy of vertex " << v << " at x = " << image.x();
    }
  }
  for (std::size_t v = 8; v < m.vertices.size(); ++v) EXPECT_GT(m.vertices[v].x(), 1.0);
  EXPECT_EQ(m.frames[1].forces.at(0).f0, Vec3(-1, 0, 2));
  const VertexFrameSurface surface = solve(m);
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      Vec3 p = surface.patches[0].position(i / 4.0, j / 4.0);
      p.x() = 2.0 - p.x();
      const Vec3 q = surface.patches[1].position(1.0 - i / 4.0, j / 4.0);
      EXPECT_LT((p - q).norm(), kC0RelativeTolerance) << i << ", " << j;
    }
  // Across x = -0.5, away from the frame, no vertex is on the plane: the copy stands apart.
  ASSERT_TRUE(s.undo());
  applyJson(s, R"({"op":"mirror-frames","frames":[0],"axis":"x","at":-0.5})");
  EXPECT_EQ(s.frames()->vertices.size(), 16u);
  EXPECT_EQ(sharedEdges(*s.frames()), 0u);
  EXPECT_TRUE(contains(refusal(s, R"({"op":"mirror-frames","frames":[0],"axis":"x","at":"1"})"),
                       "expected a number"));
}

TEST(Structure, WeldEdgesClosesAStripIntoATube) {
  VertexFrameModel strip = newModel(NewModelOptions::Kind::Grid, 4, 1);
  ModelSession s{AnyModel(strip)};
  applyJson(s, R"({"op":"weld-edges","edges":[{"frame":0,"side":3},{"frame":3,"side":1}]})");
  const VertexFrameModel& m = *s.frames();
  EXPECT_EQ(m.vertices.size(), strip.vertices.size() - 3);
  EXPECT_EQ(sharedEdges(m), 4u);
  EXPECT_EQ(boundaryEdges(m), 8u);
  EXPECT_TRUE(facesOneWay(m));
  EXPECT_LT(relativeGap(m), kC0RelativeTolerance);
  // The kept vertices moved half way: P1 of frame 0 from x = 0 to 2 (x = 4 welded in).
  EXPECT_EQ(m.vertices[m.frames[0].vertices[0]], Vec3(2, 0, 0));
  EXPECT_TRUE(contains(
      refusal(s, R"({"op":"weld-edges","edges":[{"frame":0,"side":3},{"frame":0,"side":3}]})"),
      "not on the boundary"));
}

TEST(Structure, WeldVerticesJoinsTwoFramesAndRefusesFoldingOne) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Grid, 2, 1)));
  applyJson(s, R"({"op":"delete-frames","frames":[1]})");
  applyJson(s, R"({"op":"extrude","edges":[{"frame":0,"side":1}]})");
  EXPECT_TRUE(
      contains(refusal(s, R"({"op":"weld-vertices","vertices":[0,2]})"), "both on frame 0"));
  // Two separate frames joined at a corner: P3 of frame 0 and P1 of a copy placed beside it.
  VertexFrameModel two = newModel(NewModelOptions::Kind::Single, 1, 1);
  const std::uint32_t n = static_cast<std::uint32_t>(two.vertices.size());
  for (std::uint32_t v = 0; v < n; ++v) two.vertices.push_back(two.vertices[v] + Vec3(1.5, 0, 0));
  Frame copy = two.frames[0];
  for (std::uint32_t& v : copy.vertices) v += n;
  two.frames.push_back(copy);
  ModelSession t{AnyModel(two)};
  const std::uint32_t keep = two.frames[0].vertices[2], gone = copy.vertices[0];
  applyJson(t, fmt::format(R"({{"op":"weld-vertices","vertices":[{},{}]}})", keep, gone));
  EXPECT_EQ(t.frames()->vertices.size(), two.vertices.size() - 1);
  EXPECT_EQ(t.frames()->vertices[keep], Vec3(1.25, 0, 0));  // half way
  EXPECT_EQ(t.frames()->frames[1].vertices[0], keep);
  // Their other corners welded too: the side's ends are shared, its middles are not. The
  // refusal names frames and vertices as the page shows them, not the file's fields.
  const std::uint32_t keep2 = two.frames[0].vertices[4], gone2 = copy.vertices[6] - 1;
  std::string why;
  try {
    t.apply(
        parseFrameEdit(fmt::format(R"({{"op":"weld-vertices","vertices":[{},{}]}})", keep2, gone2),
                       *t.frames())
            .edit);
  } catch (const ModelError& e) {
    why = e.what();
  }
  EXPECT_TRUE(contains(why, "would meet at the two ends of a side")) << why;
  EXPECT_TRUE(contains(why, "weld the two whole edges")) << why;
  EXPECT_FALSE(contains(why, "$.")) << why;
  EXPECT_FALSE(contains(why, "P3-P4-P5")) << why;
}

TEST(Structure, FlipMirrorsTheFrameAndItsForcesAndTwiceGivesThemBack) {
  VertexFrameModel grid = newModel(NewModelOptions::Kind::Grid, 2, 1);
  grid.frames[0].forces = {{Vec3(0, 0, 1), {0.1, 0.3, 0.2, 0.9}}};
  ModelSession s{AnyModel(grid)};
  applyJson(s, R"({"op":"flip-frames","frames":[0]})");
  const Frame& f = s.frames()->frames[0];
  EXPECT_EQ(f.vertices[0], grid.frames[0].vertices[2]);
  EXPECT_DOUBLE_EQ(f.forces[0].region.u0, 0.7);
  EXPECT_FALSE(buildTopology(*s.frames()).flipped[0] == buildTopology(*s.frames()).flipped[1]);
  // The same surface, its u reversed.
  const VertexFrameSurface a = solve(grid), b = solve(*s.frames());
  EXPECT_LT((a.patches[0].position(0.3, 0.6) - b.patches[0].position(0.7, 0.6)).norm(),
            kC0RelativeTolerance);
  applyJson(s, R"({"op":"flip-frames","frames":[0]})");
  EXPECT_EQ(s.frames()->frames[0].vertices, grid.frames[0].vertices);
  // 1 - (1 - u) is u to within an ulp of 1.
  constexpr double kMirrorRounding = 1e-15;
  EXPECT_NEAR(s.frames()->frames[0].forces[0].region.u0, 0.1, kMirrorRounding);
  EXPECT_NEAR(s.frames()->frames[0].forces[0].region.u1, 0.3, kMirrorRounding);
}

TEST(Structure, UndoOfEveryStructureEditRestoresTheFileByteForByte) {
  const std::string edits[] = {
      R"({"op":"extrude","edges":[{"frame":0,"side":0},{"frame":1,"side":0}]})",
      R"({"op":"add-frame","corners":[14,16,30,28]})",
      R"({"op":"delete-frames","frames":[0]})",
      R"({"op":"split-frame","frame":1,"parts":4})",
      R"({"op":"weld-vertices","vertices":[0,28]})",
      R"({"op":"weld-edges","edges":[{"frame":0,"side":3},{"frame":2,"side":1}]})",
      R"({"op":"flip-frames","frames":[1,2]})",
  };
  for (const std::string& edit : edits) {
    VertexFrameModel m = curvedGrid();
    m.frames.erase(m.frames.begin() + 3, m.frames.end());  // a strip of 3, with loose vertices
    ModelSession s{AnyModel(m)};
    const std::string file = serializeModel(s.model());
    applyJson(s, edit);
    const std::string edited = serializeModel(s.model());
    ASSERT_NE(edited, file) << edit;
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(serializeModel(s.model()), file) << edit;
    // The structure came back with the model: it solves and tessellates as it did.
    EXPECT_EQ(s.solved().frames()->patches.size(), m.frames.size()) << edit;
    ASSERT_TRUE(s.redo());
    EXPECT_EQ(serializeModel(s.model()), edited) << edit;
    EXPECT_EQ(s.solved().frames()->patches.size(), s.frames()->frames.size()) << edit;
  }
}

TEST(Structure, MoveVerticesMovesASelectionInOneStep) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Single, 1, 1)));
  const std::string file = serializeModel(s.model());
  applyJson(s, R"({"op":"move-vertices","vertices":[0,2],"positions":[[0,0,1],[1,0,1]]})");
  EXPECT_EQ(s.frames()->vertices[0], Vec3(0, 0, 1));
  EXPECT_EQ(s.frames()->vertices[2], Vec3(1, 0, 1));
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(serializeModel(s.model()), file);
  std::string path;
  const auto problem = [&](std::string_view json) {
    try {
      parseFrameEdit(json, *s.frames());
    } catch (const ModelError& e) {
      path = e.jsonPath();
      return e.problem();
    }
    return std::string();
  };
  EXPECT_TRUE(
      contains(problem(R"({"op":"move-vertices","vertices":[0,0],"positions":[[0,0,1],[1,0,1]]})"),
               "listed twice"));
  EXPECT_EQ(path, "$.vertices[1]");
  EXPECT_TRUE(contains(
      problem(R"({"op":"move-vertices","vertices":[0,1],"positions":[[0,0,1],[1,0,1],[2,0,0]]})"),
      "expected 2 positions"));
}

TEST(Structure, AStructureEditEndsTheDragBeforeIt) {
  ModelSession s(AnyModel(newModel(NewModelOptions::Kind::Single, 1, 1)));
  s.apply(MoveVertex{0, Vec3(0, 0, 1)}, "drag");
  applyJson(s, R"({"op":"extrude","edges":[{"frame":0,"side":1}]})");
  s.apply(MoveVertex{0, Vec3(0, 0, 2)}, "drag");
  EXPECT_EQ(s.undoDepth(), 3u);
}

}  // namespace
}  // namespace pdesurf
