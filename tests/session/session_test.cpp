// Editing sessions and edit parsing.
#include <gtest/gtest.h>

#include <optional>
#include <random>

#include <nlohmann/json.hpp>

#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/examples.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

VertexFrameModel grid() {
  std::mt19937 rng(41);
  testing::LatticeOptions o;
  o.rows = 2;
  o.cols = 2;
  o.randomOrientation = true;
  return testing::latticeModel(o, rng);
}

std::string problemOf(std::string_view json, const VertexFrameModel& m,
                      std::string* path = nullptr) {
  try {
    parseFrameEdit(json, m);
  } catch (const ModelError& e) {
    if (path) *path = e.jsonPath();
    return e.problem();
  }
  return "";
}

TEST(Edits, ParseEveryKind) {
  const VertexFrameModel m = grid();
  auto move =
      parseFrameEdit(R"({"op":"move-vertex","vertex":3,"position":[1,2,3],"group":"g"})", m);
  EXPECT_EQ(move.group, "g");
  EXPECT_EQ(std::get<MoveVertex>(move.edit).position, Vec3(1, 2, 3));
  auto params = parseFrameEdit(R"({"op":"set-parameters","frames":[0,2],"a2":[2,2,2]})", m);
  EXPECT_FALSE(std::get<SetParameters>(params.edit).a1.has_value());
  EXPECT_EQ(*std::get<SetParameters>(params.edit).a2, Vec3(2, 2, 2));
  auto forces = parseFrameEdit(
      R"({"op":"set-forces","frame":1,"forces":[{"f0":[0,0,1],"region":[0.2,0.4,0.1,0.9]}]})", m);
  EXPECT_EQ(std::get<SetFrameForces>(forces.edit).forces.at(0).region.u1, 0.4);
  auto shared =
      parseFrameEdit(R"({"op":"set-shared-forces","forces":[{"f0":[0,0,-1],"frames":[0,3]}]})", m);
  EXPECT_EQ(std::get<SetSharedForces>(shared.edit).forces.at(0).frames.size(), 2u);
}

TEST(Edits, InvalidOnesNameTheirJsonPath) {
  VertexFrameModel m = grid();
  std::string path;
  EXPECT_NE(problemOf(R"({"op":"move-vertex","vertex":99,"position":[1,2,3]})", m, &path)
                .find("out of range"),
            std::string::npos);
  EXPECT_EQ(path, "$.vertex");
  EXPECT_NE(problemOf(R"({"op":"move-vertex","vertex":1,"position":[1,"x",3]})", m, &path)
                .find("expected a number"),
            std::string::npos);
  EXPECT_EQ(path, "$.position[1]");
  EXPECT_NE(problemOf(R"({"op":"move-vertex","vertex":1,"position":[1,1e999,3]})", m, &path)
                .find("not finite"),
            std::string::npos);
  EXPECT_NE(problemOf(R"({"op":"spin"})", m, &path).find("unknown edit"), std::string::npos);
  EXPECT_EQ(path, "$.op");
  EXPECT_NE(problemOf(R"({"op":"set-parameters","frames":[0]})", m).find("needs"),
            std::string::npos);
  EXPECT_NE(
      problemOf(R"({"op":"set-forces","frame":0,"forces":[{"f0":[1,0,0],"region":[0.5,0.2,0,1]}]})",
                m, &path)
          .find("inverted"),
      std::string::npos);
  EXPECT_EQ(path, "$.forces[0].region");
  EXPECT_NE(problemOf("{\"op\":", m).find("malformed JSON"), std::string::npos);
  // New a1, a2 that leave an existing force without a solution are refused.
  m.frames[1].forces.push_back({Vec3(0, 0, 1), Region{}});
  EXPECT_NE(
      problemOf(R"({"op":"set-parameters","frames":[1],"a1":[1,1,-1]})", m).find("no solution"),
      std::string::npos);
  m.forces.push_back({Vec3(1, 0, 0), {2}});
  EXPECT_NE(
      problemOf(R"({"op":"set-parameters","frames":[2],"a2":[-1,1,1]})", m).find("no solution"),
      std::string::npos);
}

TEST(Session, AppliesEditsAndSolvesTheEditedModel) {
  const VertexFrameModel m = grid();
  ModelSession s(m);
  const Vec3 before = s.solved().frames()->patches[0].position(0.5, 0.5);
  const std::uint32_t v = m.frames[0].vertices[4];
  s.apply(MoveVertex{v, m.vertices[v] + Vec3(0, 0, 1)});
  EXPECT_EQ(s.frames()->vertices[v], m.vertices[v] + Vec3(0, 0, 1));
  EXPECT_EQ(s.revision(), 1u);
  const Vec3 after = s.solved().frames()->patches[0].position(0.5, 0.5);
  EXPECT_GT((after - before).norm(), 1e-3);
  // The session's solve equals a fresh solve of its model.
  const VertexFrameSurface fresh = solve(*s.frames());
  for (std::size_t k = 0; k < m.frames.size(); ++k)
    for (int i = 0; i < 10; ++i)
      EXPECT_EQ(s.solved().frames()->patches[k].c[i], fresh.patches[k].c[i]);
}

TEST(Session, ADragIsOneUndoStepAndRedoRestoresIt) {
  const VertexFrameModel m = grid();
  ModelSession s(m);
  const std::uint32_t v = 4;
  for (int i = 1; i <= 10; ++i)
    s.apply(MoveVertex{v, m.vertices[v] + Vec3(0, 0, 0.1 * i)}, "drag-1");
  s.endGroup();
  s.apply(SetParameters{{0}, Vec3(2, 2, 2), std::nullopt}, "slider");
  EXPECT_EQ(s.undoDepth(), 2u);
  const VertexFrameModel dragged = *s.frames();
  ASSERT_TRUE(s.undo());  // the slider
  EXPECT_EQ(s.frames()->frames[0].a1, Vec3::Ones());
  EXPECT_EQ(s.frames()->vertices[v], dragged.vertices[v]);
  ASSERT_TRUE(s.undo());  // the whole drag
  EXPECT_EQ(s.frames()->vertices[v], m.vertices[v]);
  EXPECT_FALSE(s.undo());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.frames()->vertices[v], dragged.vertices[v]);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.frames()->frames[0].a1, Vec3(2, 2, 2));
  EXPECT_FALSE(s.redo());
  // A new edit after an undo drops the redo history.
  ASSERT_TRUE(s.undo());
  s.apply(MoveVertex{0, Vec3(9, 9, 9)});
  EXPECT_EQ(s.redoDepth(), 0u);
}

TEST(Session, ForcesAndSharedForcesTakeEffect) {
  const VertexFrameModel m = grid();
  ModelSession s(m);
  const Vec3 flat = s.solved().frames()->patches[3].position(0.5, 0.5);
  s.apply(SetSharedForces{{SharedForce{Vec3(0, 0, -5), {3}}}});
  const double expected = 5.0 / (M_PI * M_PI * 2.0);  // -f0/(π²(a1+a2)) at the centre
  EXPECT_NEAR((s.solved().frames()->patches[3].position(0.5, 0.5) - flat).z(), expected, 1e-12);
  s.apply(SetFrameForces{3, {FrameForce{Vec3(0, 0, -5), Region{}}}});
  EXPECT_NEAR((s.solved().frames()->patches[3].position(0.5, 0.5) - flat).z(), 2 * expected, 1e-12);
}

}  // namespace
}  // namespace pdesurf

namespace pdesurf {
namespace {

TEST(ModelSession, EveryExampleTakesAnEditThroughOnePathAndUndoesIt) {
  // The first of these edits each example's method takes (a vertex, a curve by index or by
  // name, a net's corner): parsed by parseEdit and applied by apply, whatever the type.
  const char* const kEdits[] = {
      R"({"op": "move-vertex", "vertex": 0, "position": [0.5, 0.5, 0.5]})",
      R"({"op": "transform-curve", "curve": 0, "translate": [0, 0, 0.05]})",
      R"({"op": "transform-curve", "curve": "uMin", "translate": [0, 0, 0.05]})",
      R"({"op": "transform-curve", "curve": "start", "translate": [0, 0, 0.05]})"};
  for (const std::string& file : testing::exampleFiles()) {
    SCOPED_TRACE(file);
    ModelSession s(loadModel(file), file);
    const std::string before = serializeModel(s.model());
    std::vector<std::string> edits(std::begin(kEdits), std::end(kEdits));
    // A net's corner P[0][0] lifted a little.
    if (const auto doc = nlohmann::json::parse(before); doc.contains("net")) {
      auto p = doc["net"][0][0];
      p[2] = p[2].get<double>() + 0.05;
      edits.push_back(R"({"op": "move-control-points", "points": [[0, 0]], "positions": [)" +
                      p.dump() + "]}");
    }
    std::optional<ModelEdit> edit;
    for (const std::string& json : edits) {
      try {
        edit = parseEdit(json, s.model());
        break;
      } catch (const ModelError&) {
        // not this method's, or not this form's: the next
      }
    }
    ASSERT_TRUE(edit.has_value()) << modelTypeName(s.model());
    s.apply(*edit);
    const std::string after = serializeModel(s.model());
    EXPECT_NE(after, before);
    EXPECT_EQ(s.undoDepth(), 1u);
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(serializeModel(s.model()), before);
    ASSERT_TRUE(s.redo());
    EXPECT_EQ(serializeModel(s.model()), after);
  }
}

}  // namespace
}  // namespace pdesurf
