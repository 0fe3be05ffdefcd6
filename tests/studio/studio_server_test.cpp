// Tests of the studio server (apps/studio): the server in-process on 127.0.0.1, a free
// port and a temporary root folder, talked to with httplib::Client (carrying the server's
// token, as the page does); the checks of who may ask ("Security" in apps/studio/README.md);
// and `pdesurf studio`, killed too.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"
#include "server.hpp"
#include "support/cli_run.hpp"
// After Eigen (through the pdesurf headers): httplib.h brings <resolv.h> and its `_res`.
#include <httplib.h>

extern char** environ;

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

using testing::readText;

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A 2×2 grid of frames over a 5×5 lattice of vertices (index j*5+i at (i, j, 0)).
std::string gridModel() {
  Json vertices = Json::array();
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) vertices.push_back({0.5 * i, 0.5 * j, 0.1 * ((i + j) % 2)});
  auto at = [](int i, int j) { return j * 5 + i; };
  Json frames = Json::array();
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      const int i = 2 * c, j = 2 * r;
      frames.push_back({{"vertices",
                         {at(i, j), at(i + 1, j), at(i + 2, j), at(i + 2, j + 1), at(i + 2, j + 2),
                          at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)}}});
    }
  return Json{
      {"type", "vertex-frames"}, {"name", "grid"}, {"vertices", vertices}, {"frames", frames}}
      .dump(2);
}

struct MeshData {
  std::uint32_t vertexCount = 0, triangleCount = 0, revision = 0, resolution = 0;
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> indices;
};

MeshData parseMesh(const std::string& body) {
  MeshData m;
  if (body.size() < 16) throw std::runtime_error("mesh body too short");
  std::uint32_t header[4];
  std::memcpy(header, body.data(), 16);
  m.vertexCount = header[0];
  m.triangleCount = header[1];
  m.revision = header[2];
  m.resolution = header[3];
  const std::size_t expected = 16 + 4 * (6 * std::size_t{m.vertexCount} + 3 * m.triangleCount);
  if (body.size() != expected) throw std::runtime_error("mesh body size mismatch");
  m.positions.resize(3 * m.vertexCount);
  m.normals.resize(3 * m.vertexCount);
  m.indices.resize(3 * m.triangleCount);
  const char* p = body.data() + 16;
  std::memcpy(m.positions.data(), p, 12 * m.vertexCount);
  p += 12 * m.vertexCount;
  std::memcpy(m.normals.data(), p, 12 * m.vertexCount);
  p += 12 * m.vertexCount;
  std::memcpy(m.indices.data(), p, 12 * m.triangleCount);
  return m;
}

class StudioServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "pdesurf-studio-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    root_ = fs::canonical(pattern);
    outside_ = root_.string() + "-outside";
    fs::create_directories(outside_);
    model_ = root_ / "grid.json";
    writeText(model_, gridModel());
    startServer();
  }

  void TearDown() override {
    client_.reset();
    server_.reset();
    std::error_code ignored;
    fs::remove_all(root_, ignored);
    fs::remove_all(outside_, ignored);
  }

  void startServer(bool requireToken = true) {
    client_.reset();
    server_.reset();
    StudioOptions options{root_.string(), "127.0.0.1", 0};
    options.requireToken = requireToken;
    server_ = std::make_unique<StudioServer>(model_.string(), options);
    port_ = server_->start();
    ASSERT_GT(port_, 0);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_connection_timeout(5);
    client_->set_read_timeout(20);
    client_->set_write_timeout(20);
    if (requireToken) client_->set_default_headers({{kTokenHeader, server_->token()}});
  }

  /// The server "crashes": gone without saving, its autosave left behind.
  void crashAndRestart() { startServer(); }

  httplib::Result post(const std::string& path, const std::string& body = "{}") {
    return client_->Post(path.c_str(), body, "application/json");
  }
  httplib::Result get(const std::string& path) { return client_->Get(path.c_str()); }

  static Json json(const httplib::Result& r) {
    if (!r) throw std::runtime_error("no response: " + httplib::to_string(r.error()));
    return Json::parse(r->body);
  }

  Json model() { return json(get("/api/model")); }

  MeshData mesh(const std::string& query = "") {
    auto r = get("/api/mesh" + query);
    if (!r || r->status != 200) throw std::runtime_error("mesh request failed");
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/octet-stream");
    EXPECT_TRUE(r->has_header("X-Solve-Ms"));
    EXPECT_TRUE(r->has_header("X-Tessellate-Ms"));
    EXPECT_TRUE(r->has_header("X-C0-Gap"));
    return parseMesh(r->body);
  }

  static std::string move(int vertex, double x, double y, double z, const std::string& group = {}) {
    Json e = {{"op", "move-vertex"}, {"vertex", vertex}, {"position", {x, y, z}}};
    if (!group.empty()) e["group"] = group;
    return e.dump();
  }

  /// The status and the error message of a request expected to fail.
  static std::pair<int, std::string> failure(const httplib::Result& r) {
    if (!r) return {-1, httplib::to_string(r.error())};
    const Json body = Json::parse(r->body, nullptr, false);
    if (body.is_discarded() || !body.contains("error") || !body["error"].is_string())
      return {r->status, "(no JSON error) " + r->body};
    return {r->status, body["error"].get<std::string>()};
  }

  fs::path root_, outside_, model_;
  std::unique_ptr<StudioServer> server_;
  std::unique_ptr<httplib::Client> client_;
  int port_ = 0;
};

TEST_F(StudioServerTest, ModelFetch) {
  const Json m = model();
  EXPECT_EQ(m["path"], "grid.json");
  EXPECT_EQ(m["revision"], 0);
  EXPECT_EQ(m["undo"], 0);
  EXPECT_EQ(m["redo"], 0);
  EXPECT_EQ(m["dirty"], false);
  EXPECT_EQ(m["recovery"], false);
  EXPECT_EQ(m["model"]["type"], "vertex-frames");
  EXPECT_EQ(m["model"]["vertices"].size(), 25u);
  EXPECT_EQ(m["model"]["frames"].size(), 4u);
  const auto page = get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("/api/model"), std::string::npos);
  const auto files = json(get("/api/files"));
  EXPECT_EQ(files["files"], Json::array({"grid.json"}));
}

TEST_F(StudioServerTest, EditChangesRevisionAndMesh) {
  const MeshData before = mesh("?resolution=9");
  EXPECT_EQ(before.resolution, 9u);
  EXPECT_EQ(before.revision, 0u);
  EXPECT_GT(before.vertexCount, 0u);
  EXPECT_GT(before.triangleCount, 0u);
  const auto r = post("/api/edit", move(12, 1.0, 1.0, 0.8));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const Json s = Json::parse(r->body);
  EXPECT_EQ(s["revision"], 1);
  EXPECT_EQ(s["undo"], 1);
  EXPECT_EQ(s["redo"], 0);
  EXPECT_EQ(model()["dirty"], true);
  const MeshData after = mesh("?resolution=9");
  EXPECT_EQ(after.revision, 1u);
  EXPECT_EQ(after.vertexCount, before.vertexCount);
  EXPECT_EQ(after.triangleCount, before.triangleCount);
  EXPECT_EQ(after.indices, before.indices);
  EXPECT_NE(after.positions, before.positions);
  // The default resolution, the local solver and a bad resolution.
  EXPECT_EQ(mesh().resolution, 16u);
  EXPECT_EQ(mesh("?solver=local&seed=3").vertexCount, mesh().vertexCount);
  for (const char* bad :
       {"?resolution=1", "?resolution=258", "?resolution=x", "?solver=magic", "?seed=4"}) {
    const auto [status, message] = failure(get(std::string("/api/mesh") + bad));
    EXPECT_EQ(status, 400) << bad;
    EXPECT_FALSE(message.empty());
  }
}

/// Applies a delta answer (X-Mesh-Base) to the mesh it was made against.
void applyDelta(MeshData& m, const std::string& body) {
  std::uint32_t header[5];
  ASSERT_GE(body.size(), sizeof header);
  std::memcpy(header, body.data(), sizeof header);
  ASSERT_EQ(header[0], m.vertexCount);
  ASSERT_EQ(header[1], m.triangleCount);
  m.revision = header[2];
  m.resolution = header[3];
  std::vector<std::uint32_t> runs(2 * std::size_t{header[4]});
  std::memcpy(runs.data(), body.data() + sizeof header, 4 * runs.size());
  std::size_t changed = 0;
  for (std::size_t r = 0; r < runs.size(); r += 2) {
    ASSERT_LE(std::size_t{runs[r]} + runs[r + 1], m.vertexCount);
    if (r > 0) ASSERT_GT(runs[r], runs[r - 2] + runs[r - 1]) << "runs overlap or touch";
    changed += runs[r + 1];
  }
  ASSERT_EQ(body.size(), sizeof header + 4 * runs.size() + 24 * changed);
  const char* p = body.data() + sizeof header + 4 * runs.size();
  for (auto* buffer : {&m.positions, &m.normals})
    for (std::size_t r = 0; r < runs.size(); r += 2) {
      std::memcpy(buffer->data() + 3 * std::size_t{runs[r]}, p, 12 * std::size_t{runs[r + 1]});
      p += 12 * std::size_t{runs[r + 1]};
    }
}

TEST_F(StudioServerTest, MeshDeltaAgainstTheClientsMeshGivesTheNewMesh) {
  auto r0 = get("/api/mesh?resolution=9");
  ASSERT_TRUE(r0 && r0->status == 200);
  EXPECT_FALSE(r0->has_header("X-Mesh-Base"));
  const std::string id0 = r0->get_header_value("X-Mesh-Id");
  ASSERT_FALSE(id0.empty());
  MeshData client = parseMesh(r0->body);

  ASSERT_EQ(post("/api/edit", move(0, -0.1, -0.2, 0.4))->status, 200);
  auto r1 = get("/api/mesh?resolution=9&base=" + id0);
  ASSERT_TRUE(r1 && r1->status == 200);
  ASSERT_EQ(r1->get_header_value("X-Mesh-Base"), id0);
  const std::string id1 = r1->get_header_value("X-Mesh-Id");
  EXPECT_NE(id1, id0);
  applyDelta(client, r1->body);
  EXPECT_LT(r1->body.size(), r0->body.size() / 2) << "a corner move changes a few patches";

  // The whole mesh of the same revision (no base) is what the delta made of the old one.
  auto full = get("/api/mesh?resolution=9");
  ASSERT_TRUE(full && full->status == 200);
  EXPECT_FALSE(full->has_header("X-Mesh-Base"));
  const MeshData expected = parseMesh(full->body);
  EXPECT_EQ(client.revision, 1u);
  EXPECT_EQ(client.positions, expected.positions);
  EXPECT_EQ(client.normals, expected.normals);
  EXPECT_EQ(client.indices, expected.indices);

  // A base that is not the last mesh sent (id1 was followed by `full`), or another
  // resolution, gets the whole mesh.
  auto stale = get("/api/mesh?resolution=9&base=" + id1);
  ASSERT_TRUE(stale && stale->status == 200);
  EXPECT_FALSE(stale->has_header("X-Mesh-Base"));
  EXPECT_EQ(parseMesh(stale->body).positions, expected.positions);
  auto other = get("/api/mesh?resolution=5&base=" + stale->get_header_value("X-Mesh-Id"));
  ASSERT_TRUE(other && other->status == 200);
  EXPECT_FALSE(other->has_header("X-Mesh-Base"));
  EXPECT_EQ(parseMesh(other->body).resolution, 5u);
  EXPECT_EQ(failure(get("/api/mesh?base=x")).first, 400);
  EXPECT_EQ(failure(get("/api/mesh?base=0")).first, 400);
}

TEST_F(StudioServerTest, ReleaseAfterAPreviewIsADeltaAgainstTheLastFullResolutionMesh) {
  // The page holds the chosen resolution (9) and, during a gesture, a preview (5); each is
  // the base of deltas at its resolution, so the release needs no whole mesh.
  auto full0 = get("/api/mesh?resolution=9");
  ASSERT_TRUE(full0 && full0->status == 200);
  const std::string fullId = full0->get_header_value("X-Mesh-Id");
  MeshData client = parseMesh(full0->body);

  ASSERT_EQ(post("/api/edit", move(0, -0.1, -0.2, 0.4))->status, 200);
  auto preview0 = get("/api/mesh?resolution=5&base=" + fullId);  // another resolution: whole
  ASSERT_TRUE(preview0 && preview0->status == 200);
  EXPECT_FALSE(preview0->has_header("X-Mesh-Base"));
  const std::string previewId = preview0->get_header_value("X-Mesh-Id");
  ASSERT_EQ(post("/api/edit", move(0, -0.2, -0.3, 0.5))->status, 200);
  auto preview1 = get("/api/mesh?resolution=5&base=" + previewId);
  ASSERT_TRUE(preview1 && preview1->status == 200);
  EXPECT_EQ(preview1->get_header_value("X-Mesh-Base"), previewId);

  // The release: a delta against the last mesh at 9, carrying that mesh's id.
  auto release = get("/api/mesh?resolution=9&base=" + fullId);
  ASSERT_TRUE(release && release->status == 200);
  ASSERT_EQ(release->get_header_value("X-Mesh-Base"), fullId);
  EXPECT_LT(release->body.size(), full0->body.size() / 2) << "a corner move changes a few patches";
  applyDelta(client, release->body);
  const MeshData expected = parseMesh(get("/api/mesh?resolution=9")->body);
  EXPECT_EQ(client.revision, 2u);
  EXPECT_EQ(client.positions, expected.positions);
  EXPECT_EQ(client.normals, expected.normals);

  // A base of the other resolution, or one that is no longer the last at its own, gets the
  // whole mesh: no delta is ever made against a mesh the client may not hold.
  for (const std::string& wrong : {previewId, fullId}) {
    auto answer = get("/api/mesh?resolution=9&base=" + wrong);
    ASSERT_TRUE(answer && answer->status == 200);
    EXPECT_FALSE(answer->has_header("X-Mesh-Base")) << "base " << wrong;
  }
  // A third resolution takes the least recently used slot (5's): 9 keeps its base.
  const std::string last9 = get("/api/mesh?resolution=9")->get_header_value("X-Mesh-Id");
  ASSERT_EQ(get("/api/mesh?resolution=7")->status, 200);
  EXPECT_EQ(get("/api/mesh?resolution=9&base=" + last9)->get_header_value("X-Mesh-Base"), last9);
}

TEST_F(StudioServerTest, AnEditCanAnswerWithTheMeshAfterIt) {
  auto r0 = get("/api/mesh?resolution=9");
  ASSERT_TRUE(r0 && r0->status == 200);
  const std::string id0 = r0->get_header_value("X-Mesh-Id");
  MeshData client = parseMesh(r0->body);

  // One round trip: the edit's status in X-Status, the mesh after it (a delta) as the body.
  auto r1 = post("/api/edit?mesh=1&resolution=9&base=" + id0, move(0, -0.1, -0.2, 0.4));
  ASSERT_TRUE(r1 && r1->status == 200) << (r1 ? r1->body : "");
  const Json status = Json::parse(r1->get_header_value("X-Status"));
  EXPECT_EQ(status["revision"], 1);
  EXPECT_EQ(status["undo"], 1);
  ASSERT_EQ(r1->get_header_value("X-Mesh-Base"), id0);
  applyDelta(client, r1->body);
  const MeshData expected = parseMesh(get("/api/mesh?resolution=9")->body);
  EXPECT_EQ(client.revision, 1u);
  EXPECT_EQ(client.positions, expected.positions);
  EXPECT_EQ(client.normals, expected.normals);

  // A bad mesh parameter is refused before the edit is applied: nothing changes.
  for (const char* bad : {"?mesh=1&resolution=1", "?mesh=1&solver=magic", "?mesh=2"}) {
    const auto [code, message] =
        failure(post(std::string("/api/edit") + bad, move(0, 0.3, 0.3, 0.3)));
    EXPECT_EQ(code, 400) << bad;
    EXPECT_FALSE(message.empty()) << bad;
  }
  EXPECT_EQ(model()["revision"], 1);
}

TEST_F(StudioServerTest, CurvatureHasTwoValuesForEveryVertexOfTheMesh) {
  ASSERT_EQ(post("/api/edit", move(12, 1.0, 1.0, 0.8))->status, 200);  // bend the flat grid
  const MeshData mesh = parseMesh(get("/api/mesh?resolution=9")->body);
  const auto r = get("/api/curvature?resolution=9");
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_EQ(r->get_header_value("X-Revision"), "1");
  ASSERT_EQ(r->body.size(), 8 * std::size_t{mesh.vertexCount});
  std::vector<float> values(2 * mesh.vertexCount);
  std::memcpy(values.data(), r->body.data(), r->body.size());
  float largest = 0;
  for (float x : values) {
    ASSERT_TRUE(std::isfinite(x));
    largest = std::max(largest, std::abs(x));
  }
  EXPECT_GT(largest, 0.0f) << "the moved vertex bends the surface";
  EXPECT_EQ(failure(get("/api/curvature?resolution=1")).first, 400);
}

TEST_F(StudioServerTest, DragUndoesInOneStep) {
  const Json original = model()["model"];
  for (int i = 0; i < 10; ++i) {
    const auto r = post("/api/edit", move(12, 1.0, 1.0, 0.1 * i, "drag-1"));
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
  }
  ASSERT_EQ(json(post("/api/end-group"))["undo"], 1);
  const Json dragged = model();
  EXPECT_EQ(dragged["revision"], 10);
  EXPECT_EQ(dragged["undo"], 1);
  auto undone = json(post("/api/undo"));
  EXPECT_EQ(undone["undo"], 0);
  EXPECT_EQ(undone["redo"], 1);
  EXPECT_EQ(model()["model"], original);
  auto redone = json(post("/api/redo"));
  EXPECT_EQ(redone["undo"], 1);
  EXPECT_EQ(redone["redo"], 0);
  EXPECT_EQ(model()["model"], dragged["model"]);
}

TEST_F(StudioServerTest, UndoWithNothingIsAConflict) {
  auto [status, message] = failure(post("/api/undo"));
  EXPECT_EQ(status, 409);
  EXPECT_EQ(message, "nothing to undo");
  std::tie(status, message) = failure(post("/api/redo"));
  EXPECT_EQ(status, 409);
  EXPECT_EQ(message, "nothing to redo");
}

// The modeller: a new model file, structure edits through /api/edit, save, reopen, undo.
TEST_F(StudioServerTest, NewModelThenStructureEditsSaveReopenAndUndoByteForByte) {
  auto r = post("/api/new", R"({"path": "made/l.json", "kind": "single"})");
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json(r)["path"], "made/l.json");
  const std::string fresh = readText(root_ / "made/l.json");
  EXPECT_EQ(model()["model"]["frames"].size(), 1u);
  EXPECT_EQ(failure(post("/api/new", R"({"path": "made/l.json", "kind": "grid"})")).first, 409);
  const auto [status, message] =
      failure(post("/api/new", R"({"path": "t.json", "kind": "tube", "u": 2})"));
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("$.u"), std::string::npos) << message;

  ASSERT_EQ(post("/api/edit", R"({"op":"extrude","edges":[{"frame":0,"side":1}]})")->status, 200);
  ASSERT_EQ(post("/api/edit", R"({"op":"extrude","edges":[{"frame":1,"side":2}]})")->status, 200);
  // A refused structure edit says why and changes nothing.
  const Json before = model();
  const auto [refused, why] =
      failure(post("/api/edit", R"({"op":"extrude","edges":[{"frame":0,"side":1}]})"));
  EXPECT_EQ(refused, 400);
  EXPECT_NE(why.find("not on the boundary"), std::string::npos) << why;
  EXPECT_EQ(model()["revision"], before["revision"]);

  // The mesh's triangles name their frames: all three are on the surface.
  const MeshData m = mesh("?resolution=9");
  auto ids = get("/api/patch-ids?resolution=9");
  ASSERT_EQ(ids->status, 200);
  ASSERT_EQ(ids->body.size(), 4 * m.triangleCount);
  std::vector<std::uint32_t> patch(m.triangleCount);
  std::memcpy(patch.data(), ids->body.data(), ids->body.size());
  EXPECT_EQ(std::set<std::uint32_t>(patch.begin(), patch.end()),
            (std::set<std::uint32_t>{0, 1, 2}));

  ASSERT_EQ(post("/api/save")->status, 200);
  ASSERT_EQ(post("/api/open", R"({"path": "made/l.json"})")->status, 200);
  const Json reopened = model()["model"];
  EXPECT_EQ(reopened["frames"].size(), 3u);
  // At rounding level: the L's bounding box diagonal is √8 < 3.
  EXPECT_LT(std::stod(get("/api/mesh")->get_header_value("X-C0-Gap")), 3 * kC0RelativeTolerance);

  // Deleting the two extruded frames gives the new file back, byte for byte (their vertices
  // go with them); undoing that gives the saved L-shape back, byte for byte.
  const std::string three = readText(root_ / "made/l.json");
  ASSERT_EQ(post("/api/edit", R"({"op":"delete-frames","frames":[1,2]})")->status, 200);
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_EQ(readText(root_ / "made/l.json"), fresh);
  ASSERT_EQ(post("/api/undo")->status, 200);
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_EQ(readText(root_ / "made/l.json"), three);
}

TEST_F(StudioServerTest, InvalidEditsAreRefusedWithTheirJsonPath) {
  const Json original = model();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {move(25, 0, 0, 0), "$.vertex"},
      {R"({"op": "move-vertex", "vertex": "3", "position": [0, 0, 0]})", "$.vertex"},
      {R"({"op": "move-vertex", "vertex": 3, "position": [0, 0]})", "$.position"},
      {R"({"op": "set-parameters", "frames": [7], "a1": [1, 1, 1]})", "$.frames[0]"},
      {R"({"op": "move-vertex", "vertex": 3, "position": [0, 0, )", "malformed JSON"},
      {R"([1, 2])", "$"},
      {R"({"op": 5})", "$.op"},
  };
  for (const auto& [body, expected] : cases) {
    const auto [status, message] = failure(post("/api/edit", body));
    EXPECT_EQ(status, 400) << body;
    EXPECT_NE(message.find(expected), std::string::npos) << body << " -> " << message;
  }
  const Json now = model();
  EXPECT_EQ(now["model"], original["model"]);
  EXPECT_EQ(now["revision"], original["revision"]);
  server_->flushJournal();
  EXPECT_FALSE(fs::exists(root_ / "grid.json.autosave"));
}

TEST_F(StudioServerTest, PathsOutsideTheRootAreForbidden) {
  writeText(outside_ / "x.json", gridModel());
  writeText(outside_ / "x.glb", "not a mesh");
  fs::create_symlink(outside_, root_ / "link");
  fs::create_symlink(outside_ / "x.json", root_ / "x-link.json");
  fs::create_symlink(outside_ / "x.glb", root_ / "x-link.glb");
  for (const std::string& path :
       {std::string("../x.json"), std::string("/etc/passwd"), std::string("sub/../../x.json"),
        (outside_ / "x.json").string(), std::string("link/x.json"), std::string("x-link.json")}) {
    const std::string body = Json{{"path", path}}.dump();
    EXPECT_EQ(failure(post("/api/open", body)).first, 403) << path;
    EXPECT_EQ(failure(post("/api/save-as", body)).first, 403) << path;
  }
  for (const std::string& path :
       {std::string("../x.glb"), std::string("/etc/x.glb"), (outside_ / "x.glb").string(),
        std::string("link/y.glb"), std::string("x-link.glb"), std::string("out/../../x.glb")}) {
    const std::string body = Json{{"path", path}}.dump();
    EXPECT_EQ(failure(post("/api/export", body)).first, 403) << path;
  }
  // Nothing was written outside, and the model is still served.
  EXPECT_EQ(std::distance(fs::directory_iterator(outside_), fs::directory_iterator()), 2);
  EXPECT_EQ(readText(outside_ / "x.glb"), "not a mesh");
  EXPECT_EQ(model()["path"], "grid.json");
}

TEST_F(StudioServerTest, BadRequestBodies) {
  EXPECT_EQ(failure(post("/api/open", "{")).first, 400);
  EXPECT_EQ(failure(post("/api/open", R"({"path": 3})")).first, 400);
  EXPECT_EQ(failure(post("/api/open", R"({"name": "x"})")).first, 400);
  EXPECT_EQ(failure(post("/api/open", R"({"path": "missing.json"})")).first, 404);
  writeText(root_ / "broken.json", R"({"type": "vertex-frames", "vertices": 3})");
  const auto [status, message] = failure(post("/api/open", R"({"path": "broken.json"})"));
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("$.vertices"), std::string::npos) << message;
  EXPECT_EQ(model()["path"], "grid.json");
  EXPECT_EQ(failure(post("/api/export", R"({"path": "out/x.xyz"})")).first, 400);
  EXPECT_EQ(failure(get("/api/nowhere")).first, 404);
  EXPECT_EQ(failure(post("/api/nowhere")).first, 404);
}

TEST_F(StudioServerTest, OversizedBodyIsRefused) {
  const std::string big(2 << 20, ' ');
  const auto [status, message] = failure(post("/api/edit", big));
  EXPECT_EQ(status, 413) << message;
  EXPECT_EQ(model()["revision"], 0);
}

TEST_F(StudioServerTest, BurstOfBadRequests) {
  const std::string big(2 << 20, 'x');
  for (int i = 0; i < 200; ++i) {
    switch (i % 4) {
      case 0:
        ASSERT_EQ(failure(post("/api/edit", "{\"op\": [")).first, 400) << i;
        break;
      case 1:
        ASSERT_EQ(failure(post("/api/edit", big)).first, 413) << i;
        break;
      case 2:
        ASSERT_EQ(failure(post("/api/open", R"({"path": "../../etc/passwd"})")).first, 403) << i;
        break;
      default:
        ASSERT_EQ(failure(post("/api/edit", move(99, 0, 0, 0))).first, 400) << i;
    }
  }
  const auto r = post("/api/edit", move(0, 0, 0, 1));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(mesh().revision, 1u);
}

TEST_F(StudioServerTest, SaveThenReopenGivesTheSameModel) {
  ASSERT_EQ(post("/api/edit", move(12, 1.0, 1.0, 0.7))->status, 200);
  ASSERT_EQ(
      post("/api/edit", R"({"op": "set-parameters", "frames": [0, 3], "a1": [2, 2, 2]})")->status,
      200);
  server_->flushJournal();
  ASSERT_TRUE(fs::exists(root_ / "grid.json.autosave"));
  const Json edited = model();
  const auto saved = post("/api/save");
  ASSERT_TRUE(saved);
  ASSERT_EQ(saved->status, 200) << saved->body;
  EXPECT_EQ(Json::parse(saved->body)["dirty"], false);
  EXPECT_FALSE(fs::exists(root_ / "grid.json.autosave"));
  for (const auto& entry : fs::directory_iterator(root_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << entry.path().filename();
  const std::string text = readText(model_);
  EXPECT_EQ(serializeVertexFrameModel(parseVertexFrameModel(text, "saved")),
            serializeVertexFrameModel(parseVertexFrameModel(edited["model"].dump(), "edited")));

  // Save-as into a new folder inside the root, then re-open the first file.
  const auto as = post("/api/save-as", R"({"path": "copies/grid2.json"})");
  ASSERT_TRUE(as);
  ASSERT_EQ(as->status, 200) << as->body;
  EXPECT_EQ(model()["path"], "copies/grid2.json");
  EXPECT_EQ(readText(root_ / "copies/grid2.json"), text);
  EXPECT_EQ(json(get("/api/files"))["files"], Json::array({"copies/grid2.json", "grid.json"}));
  const auto opened = post("/api/open", R"({"path": "grid.json"})");
  ASSERT_EQ(opened->status, 200) << opened->body;
  const Json reopened = model();
  EXPECT_EQ(reopened["path"], "grid.json");
  EXPECT_EQ(reopened["dirty"], false);
  EXPECT_EQ(reopened["undo"], 0);
  EXPECT_GT(reopened["revision"].get<int>(), edited["revision"].get<int>());
  EXPECT_EQ(reopened["model"].dump(), edited["model"].dump());
}

TEST_F(StudioServerTest, SaveKeepsTheFieldsTheEditorDoesNotHold) {
  // A file with a description, a tool's own top-level field and a frame's own field.
  Json file = Json::parse(gridModel());
  file["description"] = "a 2x2 grid";
  file["x-tool"] = {{"version", 3}, {"layers", {"a", "b"}}};
  file["frames"][1]["label"] = "corner";
  file["frames"][2]["a1"] = {2, 2, 2};
  writeText(root_ / "described.json", file.dump(2));
  ASSERT_EQ(post("/api/open", R"({"path": "described.json"})")->status, 200);
  ASSERT_EQ(post("/api/edit", move(12, 1.0, 1.0, 0.7))->status, 200);
  // An edit back to a default value (a1 = 1, which the writer omits) must not bring the
  // file's old value back: only fields the editor does not hold are kept.
  ASSERT_EQ(
      post("/api/edit", R"({"op": "set-parameters", "frames": [2], "a1": [1, 1, 1]})")->status,
      200);
  const Json edited = model();
  ASSERT_EQ(post("/api/save")->status, 200);
  const Json saved = Json::parse(readText(root_ / "described.json"));
  EXPECT_EQ(saved["description"], "a 2x2 grid");
  EXPECT_EQ(saved["x-tool"], file["x-tool"]);
  EXPECT_EQ(saved["frames"][1]["label"], "corner");
  EXPECT_FALSE(saved["frames"][2].contains("a1"));
  EXPECT_EQ(saved["vertices"][12], Json::array({1.0, 1.0, 0.7}));
  // The model is the edited one.
  EXPECT_EQ(serializeVertexFrameModel(parseVertexFrameModel(saved.dump(), "saved")),
            serializeVertexFrameModel(parseVertexFrameModel(edited["model"].dump(), "edited")));
  // Saved again (and as a copy), the fields stay.
  ASSERT_EQ(post("/api/edit", move(12, 1.0, 1.0, 0.6))->status, 200);
  ASSERT_EQ(post("/api/save-as", R"({"path": "copy.json"})")->status, 200);
  const Json copy = Json::parse(readText(root_ / "copy.json"));
  EXPECT_EQ(copy["description"], "a 2x2 grid");
  EXPECT_EQ(copy["frames"][1]["label"], "corner");
}

TEST_F(StudioServerTest, ExportWritesStepAndIges) {
  const auto step = post("/api/export", R"({"path": "out/grid.step"})");
  ASSERT_TRUE(step);
  ASSERT_EQ(step->status, 200) << step->body;
  const Json report = Json::parse(step->body);
  EXPECT_EQ(report["path"], "out/grid.step");
  const std::string text = readText(root_ / "out/grid.step");
  ASSERT_EQ(text.rfind("ISO-10303-21;", 0), 0u) << text.substr(0, 40);
  std::size_t faces = 0;
  for (std::size_t at = text.find("ADVANCED_FACE"); at != std::string::npos;
       at = text.find("ADVANCED_FACE", at + 1))
    ++faces;
  EXPECT_EQ(faces, report["faces"].get<std::size_t>());
  EXPECT_GE(faces, 4u);  // at least one face per frame
  const auto iges = post("/api/export", R"({"path": "grid.igs"})");
  ASSERT_EQ(iges->status, 200) << iges->body;
  const std::string igs = readText(root_ / "grid.igs");
  ASSERT_GT(igs.size(), 80u);
  EXPECT_EQ(igs[72], 'S');  // the start section's letter in column 73
}

TEST_F(StudioServerTest, BoundariesAreThePatchesEdgeCurves) {
  const auto r = get("/api/boundaries?samples=5");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  // The grid: 4 frames, 4 sides of 5 points each.
  ASSERT_EQ(r->body.size(), 4u * 4 * 5 * 3 * sizeof(float));
  std::vector<float> xyz(r->body.size() / sizeof(float));
  std::memcpy(xyz.data(), r->body.data(), r->body.size());
  const Json m = model()["model"];
  const auto point = [&](std::size_t patch, int side, int i) {
    const std::size_t k = 3 * ((patch * 4 + side) * 5 + i);
    return Vec3(xyz[k], xyz[k + 1], xyz[k + 2]);
  };
  const auto vertex = [&](int v) {
    return Vec3(m["vertices"][v][0].get<double>(), m["vertices"][v][1].get<double>(),
                m["vertices"][v][2].get<double>());
  };
  // Each side is a closed loop's quarter: it ends where the next side starts, and the
  // loop's four corners are the frame's corner vertices (P1, P3, P5, P7), in some order.
  constexpr double kFloatTolerance = 1e-6;  // float32 rounding of coordinates near 1
  for (std::size_t f = 0; f < 4; ++f) {
    std::vector<Vec3> corners;
    for (int side = 0; side < 4; ++side) {
      EXPECT_LT((point(f, side, 4) - point(f, (side + 1) % 4, 0)).norm(), kFloatTolerance);
      corners.push_back(point(f, side, 0));
    }
    for (int c : {0, 2, 4, 6}) {
      const Vec3 p = vertex(m["frames"][f]["vertices"][c].get<int>());
      double nearest = 1e9;
      for (const Vec3& q : corners) nearest = std::min(nearest, (p - q).norm());
      EXPECT_LT(nearest, kFloatTolerance) << "frame " << f << " corner " << c;
    }
  }
  EXPECT_EQ(failure(get("/api/boundaries?samples=1")).first, 400);
}

TEST_F(StudioServerTest, PatchPointsAndTheirParametersRoundTrip) {
  // S(u, v) of frame 3, then the parameters of those points: the same (u, v).
  const auto points =
      post("/api/patch-points", R"({"frame": 3, "uv": [[0.2, 0.7], [1, 0], [0.5, 0.5]]})");
  ASSERT_EQ(points->status, 200) << points->body;
  const Json p = Json::parse(points->body)["points"];
  ASSERT_EQ(p.size(), 3u);
  const auto uv = post("/api/patch-uv", Json{{"frame", 3}, {"points", p}}.dump());
  ASSERT_EQ(uv->status, 200) << uv->body;
  const Json back = Json::parse(uv->body)["uv"];
  constexpr double kParameterTolerance = 1e-7;  // Gauss-Newton ends far below it
  const double expected[3][2] = {{0.2, 0.7}, {1, 0}, {0.5, 0.5}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 2; ++c)
      EXPECT_NEAR(back[i][c].get<double>(), expected[i][c], kParameterTolerance) << i << " " << c;
  // Frame 3 spans x, y in [1, 2] (the grid's upper right frame): its corner (1, 0) is there.
  EXPECT_NEAR(p[1][0].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(p[1][1].get<double>(), 1.0, 1e-12);

  const std::pair<std::string, std::string> bad[] = {
      {R"({"frame": 4, "uv": [[0, 0]]})", "$.frame"},
      {R"({"frame": 0, "uv": [[0, 1.5]]})", "$.uv[0][1]"},
      {R"({"frame": 0, "uv": []})", "$.uv"},
      {R"({"frame": 0, "points": [[0, 0]]})", "$.points[0]"},
  };
  for (const auto& [body, path] : bad) {
    const bool withPoints = body.find("points") != std::string::npos;
    const auto [status, message] =
        failure(post(withPoints ? "/api/patch-uv" : "/api/patch-points", body));
    EXPECT_EQ(status, 400) << body;
    EXPECT_NE(message.find(path), std::string::npos) << message;
  }
}

TEST_F(StudioServerTest, AutosaveRecoversAfterACrash) {
  ASSERT_EQ(post("/api/edit", move(12, 1.0, 1.0, 0.9))->status, 200);
  ASSERT_EQ(post("/api/edit", move(6, 0.5, 0.5, -0.4))->status, 200);
  const Json edited = model()["model"];
  server_->flushJournal();
  ASSERT_TRUE(fs::exists(root_ / "grid.json.autosave"));
  crashAndRestart();
  Json m = model();
  EXPECT_EQ(m["recovery"], true);
  EXPECT_NE(m["model"], edited);
  // An edit before deciding leaves the journal alone.
  ASSERT_EQ(post("/api/edit", move(0, 0, 0, 0.3))->status, 200);
  const auto r = post("/api/recover");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  m = model();
  EXPECT_EQ(m["recovery"], false);
  EXPECT_EQ(m["dirty"], true);
  EXPECT_EQ(m["model"], edited);
  EXPECT_EQ(failure(post("/api/recover")).first, 409);

  // Discarding: another crash, then the journal goes.
  crashAndRestart();
  EXPECT_EQ(model()["recovery"], true);
  ASSERT_EQ(post("/api/discard-recovery")->status, 200);
  EXPECT_FALSE(fs::exists(root_ / "grid.json.autosave"));
  EXPECT_EQ(model()["recovery"], false);
  crashAndRestart();
  EXPECT_EQ(model()["recovery"], false);
}

TEST_F(StudioServerTest, SpectralModelsAreShownExportedAndCopiedAndRefuseVertexEdits) {
  const std::string tube = R"({"type": "spectral", "name": "tube", "operator": "ugail", "N": 1,
    "modes": 2, "conditions": [
      {"u": 0, "curve": {"fourier": {"a0": [0, 0, 0], "a": [[1, 0, 0]], "b": [[0, 1, 0]]}}},
      {"u": 1, "curve": {"fourier": {"a0": [0, 0, 1], "a": [[0.5, 0, 0]], "b": [[0, 0.5, 0]]}}}]})";
  writeText(root_ / "tube.json", tube);
  const auto opened = post("/api/open", R"({"path": "tube.json"})");
  ASSERT_EQ(opened->status, 200) << opened->body;
  const Json m = model();
  EXPECT_EQ(m["hasEditableParts"], false);
  EXPECT_EQ(m["model"]["type"], "spectral");
  EXPECT_EQ(m["view"]["curves"].size(), 2u);  // the two position curves
  EXPECT_EQ(m["view"]["spines"].size(), 1u);
  // The first curve is the unit circle at z = 0.
  for (const Json& p : m["view"]["curves"][0])
    EXPECT_NEAR(std::hypot(p[0].get<double>(), p[1].get<double>()), 1.0, 1e-12);

  const MeshData mesh = this->mesh("?resolution=5");
  EXPECT_EQ(mesh.vertexCount, 5u * 16u);  // 5 rows, 4(5 − 1) columns, the seam shared
  EXPECT_EQ(mesh.revision, m["revision"].get<std::uint32_t>());

  // A vertex edit is refused, naming the edits this type takes (tests/session/
  // shape_edits_test.cpp tests them); ending a group is harmless.
  const auto [status, message] = failure(post("/api/edit", move(0, 0, 0, 0)));
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("edits vertex-frame models; a spectral model takes"), std::string::npos)
      << message;
  EXPECT_EQ(post("/api/end-group")->status, 200);
  EXPECT_EQ(failure(post("/api/undo")), std::pair(409, std::string("nothing to undo")));
  EXPECT_EQ(failure(post("/api/redo")), std::pair(409, std::string("nothing to redo")));
  const auto exported = post("/api/export", R"({"path": "tube.obj", "resolution": 5})");
  ASSERT_EQ(exported->status, 200) << exported->body;
  EXPECT_EQ(readMesh((root_ / "tube.obj").string()).vertexCount(), mesh.vertexCount);
  const auto copied = post("/api/save-as", R"({"path": "copies/tube2.json"})");
  ASSERT_EQ(copied->status, 200) << copied->body;
  EXPECT_EQ(readText(root_ / "copies/tube2.json"), tube);
  server_->flushJournal();
  EXPECT_FALSE(fs::exists(root_ / "tube.json.autosave"));

  // Back to a vertex-frame model: editable again, revisions still increasing.
  ASSERT_EQ(post("/api/open", R"({"path": "grid.json"})")->status, 200);
  const Json g = model();
  EXPECT_EQ(g["hasEditableParts"], true);
  EXPECT_GT(g["revision"].get<int>(), m["revision"].get<int>());
  EXPECT_EQ(post("/api/edit", move(0, 0, 0, 0.2))->status, 200);
}

/// The bounding box of a mesh's positions: min x, y, z then max x, y, z.
std::array<double, 6> meshBox(const MeshData& m) {
  std::array<double, 6> box = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    box[i % 3] = std::min<double>(box[i % 3], m.positions[i]);
    box[3 + i % 3] = std::max<double>(box[3 + i % 3], m.positions[i]);
  }
  return box;
}

TEST_F(StudioServerTest, TransformMovesTheModelAndUndoesRedoesAndSaves) {
  const Json original = model()["model"];
  const MeshData before = mesh("?resolution=5");
  const auto r = post("/api/transform", R"({"translate": [1, 2, 3]})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const Json st = Json::parse(r->body);
  EXPECT_EQ(st["revision"], 1);
  EXPECT_EQ(st["undo"], 1);
  EXPECT_EQ(st["dirty"], true);
  Json m = model();
  EXPECT_EQ(m["model"]["vertices"][6], Json({1.5, 2.5, 3}));  // (0.5, 0.5, 0) moved
  const MeshData after = mesh("?resolution=5");
  ASSERT_EQ(after.positions.size(), before.positions.size());
  for (std::size_t i = 0; i < after.positions.size(); ++i)
    EXPECT_NEAR(after.positions[i], before.positions[i] + 1.0 + i % 3, 1e-5);

  // Scale 2 about the grid's centre, then a quarter turn about z through it: one step each.
  ASSERT_EQ(post("/api/transform", R"({"scale": 2, "center": [2, 3, 3]})")->status, 200);
  ASSERT_EQ(post("/api/transform",
                 R"({"rotate": {"axis": [0, 0, 1], "degrees": 90, "center": [2, 3, 3]}})")
                ->status,
            200);
  m = model();
  EXPECT_EQ(m["undo"], 3);
  const Json v = m["model"]["vertices"][0];  // (0, 0, 0) → (1, 2, 3) → (0, 1, 3) → (4, 1, 3)
  EXPECT_NEAR(v[0].get<double>(), 4, 1e-12);
  EXPECT_NEAR(v[1].get<double>(), 1, 1e-12);
  EXPECT_NEAR(v[2].get<double>(), 3, 1e-12);
  server_->flushJournal();
  EXPECT_EQ(readText(root_ / "grid.json.autosave"),
            serializeVertexFrameModel(parseVertexFrameModel(m["model"].dump(), "model")));

  for (int i = 0; i < 3; ++i) ASSERT_EQ(post("/api/undo")->status, 200);
  EXPECT_EQ(model()["model"], original);
  ASSERT_EQ(post("/api/redo")->status, 200);
  EXPECT_EQ(model()["model"]["vertices"][6], Json({1.5, 2.5, 3}));
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_EQ(parseVertexFrameModel(readText(model_), "saved").vertices[6], Vec3(1.5, 2.5, 3));
  EXPECT_EQ(model()["dirty"], false);
}

TEST_F(StudioServerTest, BadTransformsAreRefusedNamingTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"scale": 0})", "$.scale: scale 0 is not a finite number above 0"},
      {R"({"scale": -1, "center": [0, 0, 0]})", "$.scale"},
      {R"({"scale": "big"})", "$.scale: expected a number, found a string"},
      {R"({"translate": [1, "2", 3]})", "$.translate[1]: expected a number"},
      {R"({"rotate": {"axis": [0, 0, 0], "degrees": 45}})", "$.rotate.axis"},
      {R"({"rotate": {"axis": [0, 0, 1]}})", "$.rotate: missing required field \"degrees\""},
      {R"({})", "$: a transform needs"},
      {R"({"translate": [1, 2, 3)", "malformed JSON"},
  };
  for (const auto& [body, message] : cases) {
    const auto [status, error] = failure(post("/api/transform", body));
    EXPECT_EQ(status, 400) << body;
    EXPECT_NE(error.find(message), std::string::npos) << body << " gave " << error;
  }
  EXPECT_EQ(model()["revision"], 0);
  EXPECT_EQ(model()["undo"], 0);
}

TEST_F(StudioServerTest, SpectralModelsAreTransformedUndoneSavedAndJournaled) {
  const std::string tube = R"({"type": "spectral", "name": "tube", "operator": "ugail", "N": 1,
    "modes": 2, "conditions": [
      {"u": 0, "curve": {"fourier": {"a0": [0, 0, 0], "a": [[1, 0, 0]], "b": [[0, 1, 0]]}}},
      {"u": 1, "curve": {"fourier": {"a0": [0, 0, 1], "a": [[0.5, 0, 0]], "b": [[0, 0.5, 0]]}}}]})";
  writeText(root_ / "tube.json", tube);
  ASSERT_EQ(post("/api/open", R"({"path": "tube.json"})")->status, 200);
  const Json opened = model();
  const MeshData before = mesh("?resolution=5");
  const auto r = post("/api/transform", R"({"translate": [0, 0, 2], "scale": 3})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  Json m = model();
  EXPECT_EQ(m["hasEditableParts"], false);
  EXPECT_EQ(m["undo"], 1);
  EXPECT_EQ(m["dirty"], true);
  EXPECT_EQ(m["model"]["conditions"][1]["curve"]["fourier"]["a0"], Json({0, 0, 5}));
  EXPECT_EQ(m["model"]["conditions"][1]["curve"]["fourier"]["a"][0], Json({1.5, 0, 0}));
  for (const Json& p : m["view"]["curves"][0])  // the unit circle, now radius 3 at z = 2
    EXPECT_NEAR(std::hypot(p[0].get<double>(), p[1].get<double>()), 3.0, 1e-12);
  const MeshData after = mesh("?resolution=5");
  ASSERT_EQ(after.positions.size(), before.positions.size());
  for (std::size_t i = 0; i < after.positions.size(); ++i)
    EXPECT_NEAR(after.positions[i], 3 * before.positions[i] + (i % 3 == 2 ? 2 : 0), 1e-5);
  const auto box = meshBox(after);
  EXPECT_NEAR(box[2], 2, 1e-6);
  EXPECT_NEAR(box[5], 5, 1e-6);

  // Vertex edits stay refused; undo and redo work.
  EXPECT_EQ(failure(post("/api/edit", move(0, 0, 0, 0))).first, 400);
  ASSERT_EQ(post("/api/undo")->status, 200);
  EXPECT_EQ(model()["model"], opened["model"]);
  ASSERT_EQ(post("/api/redo")->status, 200);
  m = model();
  EXPECT_EQ(m["model"]["conditions"][1]["curve"]["fourier"]["a0"], Json({0, 0, 5}));

  // The journal holds the transformed model; a crash offers it back.
  server_->flushJournal();
  ASSERT_TRUE(fs::exists(root_ / "tube.json.autosave"));
  EXPECT_EQ(Json::parse(readText(root_ / "tube.json.autosave")), m["model"]);
  model_ = root_ / "tube.json";
  crashAndRestart();
  EXPECT_EQ(model()["recovery"], true);
  ASSERT_EQ(post("/api/recover")->status, 200);
  EXPECT_EQ(model()["model"], m["model"]);
  EXPECT_EQ(model()["undo"], 0);

  // Save writes the transformed model; it reads back as a spectral model of that shape.
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_FALSE(fs::exists(root_ / "tube.json.autosave"));
  const AnyModel saved = parseModel(readText(root_ / "tube.json"), "saved");
  ASSERT_TRUE(saved.is<SpectralModel>());
  EXPECT_EQ(Json::parse(readText(root_ / "tube.json")), m["model"]);
  EXPECT_EQ(model()["dirty"], false);
}

TEST_F(StudioServerTest, ShapeEditsAreCheckedUndoneAndSavedByteForByte) {
  // A spectral model's curves through POST /api/edit (session.hpp: ShapeEdit): applied with
  // the mesh, refused with the reason (nothing changed), undone to the file as opened.
  const fs::path source = fs::path(PDESURF_SOURCE_DIR) / "docs" / "model-format" / "tube.json";
  fs::copy_file(source, root_ / "tube.json");
  const std::string original = readText(root_ / "tube.json");
  ASSERT_EQ(post("/api/open", R"({"path": "tube.json"})")->status, 200);
  const Json opened = model();
  // The handles its method exposes (SurfaceMethod::handles): nine spine points at their u (as
  // `pdesurf spine --count 9`), the Fourier tangent's mean tip drawn from its curve's a0.
  const Json& handles = opened["handles"];
  std::size_t spine = 0, means = 0;
  for (const Json& h : handles["points"]) {
    spine += h["kind"] == "spine" && h.contains("u");
    means += h["kind"] == "tangent" && h.value("mean", false);
  }
  EXPECT_EQ(spine, 9u);
  EXPECT_GE(means, 1u);
  EXPECT_EQ(handles["tangentDraw"], kTangentDraw);
  EXPECT_EQ(handles["curves"].size(), opened["model"]["conditions"].size());
  const auto moved = post("/api/edit?mesh=1&resolution=5",
                          R"({"op": "transform-curve", "curve": 2, "translate": [0, 0, 1]})");
  ASSERT_EQ(moved->status, 200) << moved->body;
  EXPECT_TRUE(moved->has_header("X-Status"));
  EXPECT_EQ(model()["model"]["conditions"][2]["curve"]["fourier"]["a0"], Json({0, 0, 2}));
  const auto revision = model()["revision"];
  const auto [status, message] = failure(post("/api/edit", R"({"op": "set-operator", "N": 3})"));
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("$.conditions"), std::string::npos) << message;
  EXPECT_EQ(model()["revision"], revision);
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_EQ(Json::parse(readText(root_ / "tube.json"))["conditions"][2]["curve"]["fourier"]["a0"],
            Json({0, 0, 2}));
  ASSERT_EQ(post("/api/undo")->status, 200);
  ASSERT_EQ(post("/api/save")->status, 200);
  EXPECT_EQ(readText(root_ / "tube.json"), original);
}

TEST_F(StudioServerTest, EachMethodsSettingsAreItsFilesOwnAndFollowEditsUndoAndLoads) {
  // GET /api/model's "type" and "settings" (SurfaceMethod::settings), which the page's panels
  // show instead of reading the model file: for one example of each method, checked against
  // the example file's own JSON.
  const fs::path examples = fs::path(PDESURF_SOURCE_DIR) / "examples";
  const auto open = [&](const std::string& name) {
    fs::copy_file(examples / name, root_ / name, fs::copy_options::overwrite_existing);
    EXPECT_EQ(post("/api/open", Json{{"path", name}}.dump())->status, 200);
    return Json::parse(readText(examples / name));
  };
  const auto takes = [](const Json& settings, const char* op) {
    const Json& edits = settings["edits"];
    return std::find(edits.begin(), edits.end(), Json(op)) != edits.end();
  };
  // A vertex-frame model: its type, its editable parts read by the page, no settings.
  EXPECT_EQ(model()["type"], "vertex-frames");
  EXPECT_FALSE(model().contains("settings"));

  // A spectral model: the file's operator, N, a, modes and remainder; the spine moved by name.
  Json file = open("membrane.json");
  Json m = model();
  EXPECT_EQ(m["type"], file["type"]);
  Json op = m["settings"]["operator"];
  for (const char* field : {"operator", "N", "a", "modes", "remainder"})
    EXPECT_EQ(op[field], file[field]) << field;
  EXPECT_FALSE(op.contains("method"));
  EXPECT_TRUE(takes(m["settings"], "set-operator"));
  EXPECT_TRUE(takes(m["settings"], "move-spine-point"));
  EXPECT_FALSE(takes(m["settings"], "add-section"));
  EXPECT_EQ(m["settings"]["overlay"], "Curves and spine");
  // Served once per revision: an edit, its undo and a load are new revisions.
  ASSERT_EQ(post("/api/edit", R"({"op": "set-operator", "a": 2.5})")->status, 200);
  EXPECT_EQ(model()["settings"]["operator"]["a"], 2.5);
  ASSERT_EQ(post("/api/undo")->status, 200);
  EXPECT_EQ(model()["settings"]["operator"]["a"], file["a"]);
  ASSERT_EQ(post("/api/redo")->status, 200);
  EXPECT_EQ(model()["settings"]["operator"]["a"], 2.5);

  // A chain: its a, modes, remainder and method; sections; no operator kind or N.
  file = open("vase-sections.json");
  m = model();
  EXPECT_EQ(m["type"], file["type"]);
  op = m["settings"]["operator"];
  for (const char* field : {"a", "modes", "remainder", "method"})
    EXPECT_EQ(op[field], file[field]) << field;
  EXPECT_FALSE(op.contains("operator"));
  EXPECT_FALSE(op.contains("N"));
  EXPECT_TRUE(takes(m["settings"], "add-section"));
  EXPECT_TRUE(takes(m["settings"], "remove-section"));
  EXPECT_EQ(m["settings"]["overlay"], "Curves and spine");

  // A B-spline PDE net: no operator to set; its control points; control nets drawn.
  file = open("bspline-wave.json");
  m = model();
  EXPECT_EQ(m["type"], file["type"]);
  EXPECT_FALSE(m["settings"].contains("operator"));
  EXPECT_TRUE(takes(m["settings"], "move-control-points"));
  EXPECT_FALSE(takes(m["settings"], "set-operator"));
  EXPECT_EQ(m["settings"]["overlay"], "Control nets");
}

TEST_F(StudioServerTest, ASpineDragNamesThePointAndHoldsTheOthers) {
  // move-spine-point: the page names the spine handle and where it goes; the server gives the
  // file's "spine" one edit through the handles (as GET /api/model lists them), the dragged
  // one moved, the others held; a drag's steps are absolute (one edit, one undo step).
  fs::copy_file(fs::path(PDESURF_SOURCE_DIR) / "examples" / "membrane.json",
                root_ / "membrane.json");
  ASSERT_EQ(post("/api/open", R"({"path": "membrane.json"})")->status, 200);
  ASSERT_FALSE(model()["model"].contains("spine"));
  std::vector<Json> spine;
  const Json opened = model();
  for (const Json& h : opened["handles"]["points"])
    if (h["kind"] == "spine") spine.push_back(h);
  ASSERT_EQ(spine.size(), 9u);
  const auto step = [&](int index, const Json& to) {
    return post(
        "/api/edit",
        Json{
            {"op", "move-spine-point"}, {"index", index}, {"position", to}, {"group", "spine-drag"}}
            .dump());
  };
  const auto offset = [&](int index, double dz) {
    Json p = spine[index]["p"];
    p[2] = p[2].get<double>() + dz;
    return p;
  };
  ASSERT_EQ(step(4, offset(4, 0.1))->status, 200);
  ASSERT_EQ(step(4, offset(4, 0.3))->status, 200);
  ASSERT_EQ(post("/api/end-group")->status, 200);
  const auto expectSpine = [&](const std::map<int, Json>& moved) {
    const Json edits = model()["model"]["spine"];
    ASSERT_EQ(edits.size(), 1u);
    for (std::size_t k = 0; k < spine.size(); ++k) {
      EXPECT_EQ(edits[0]["u"][k], spine[k]["u"]);
      const auto it = moved.find(static_cast<int>(k));
      EXPECT_EQ(edits[0]["moved"][k], it == moved.end() ? spine[k]["p"] : it->second) << k;
    }
  };
  expectSpine({{4, offset(4, 0.3)}});
  EXPECT_EQ(model()["undo"], 1);
  // Another handle dragged: the same edit (the handles are at the same u) takes it too.
  ASSERT_EQ(step(6, offset(6, -0.2))->status, 200);
  ASSERT_EQ(post("/api/end-group")->status, 200);
  expectSpine({{4, offset(4, 0.3)}, {6, offset(6, -0.2)}});
  const auto [status, message] = failure(step(9, offset(0, 0)));
  EXPECT_EQ(status, 400);
  EXPECT_NE(message.find("$.index"), std::string::npos) << message;
  ASSERT_EQ(post("/api/undo")->status, 200);
  ASSERT_EQ(post("/api/undo")->status, 200);
  EXPECT_FALSE(model()["model"].contains("spine"));
}

TEST_F(StudioServerTest, BSplineModelsAreShownTransformedAndSaved) {
  // Example 5 (a closed blend): the studio shows its control nets and its surface, moves it,
  // and saves a file that reads back as the moved model.
  fs::copy_file(fs::path(PDESURF_SOURCE_DIR) / "examples" / "bspline-tube.json",
                root_ / "tube.json");
  ASSERT_EQ(post("/api/open", R"({"path": "tube.json"})")->status, 200);
  Json m = model();
  EXPECT_EQ(m["model"]["type"], "bspline-pde");
  EXPECT_EQ(m["hasEditableParts"], false);
  // Two pieces of 7 × 7 control points: 7 rows and 7 columns each.
  EXPECT_EQ(m["view"]["curves"].size(), 2u * 14u);
  const MeshData before = mesh("?resolution=9");
  ASSERT_GT(before.positions.size(), 0u);
  EXPECT_EQ(failure(post("/api/edit", move(0, 0, 0, 0))).first, 400);

  ASSERT_EQ(post("/api/transform", R"({"translate": [1, 0, 0]})")->status, 200);
  const MeshData after = mesh("?resolution=9");
  ASSERT_EQ(after.positions.size(), before.positions.size());
  for (std::size_t i = 0; i < after.positions.size(); ++i)
    EXPECT_NEAR(after.positions[i], before.positions[i] + (i % 3 == 0 ? 1 : 0), 1e-5);
  ASSERT_EQ(post("/api/save")->status, 200);
  const AnyModel saved = parseModel(readText(root_ / "tube.json"), "saved");
  const auto& tube = saved.get<BSplinePdeModel>();
  EXPECT_EQ(tube.form, BSplinePdeModel::Form::ClosedBlend);
  const BSplinePdeModel original =
      (loadModel((fs::path(PDESURF_SOURCE_DIR) / "examples" / "bspline-tube.json").string()))
          .get<BSplinePdeModel>();
  for (std::size_t c = 0; c < 2; ++c)
    for (std::size_t k = 0; k < tube.curves[c].points.size(); ++k)
      EXPECT_LT((tube.curves[c].points[k] - original.curves[c].points[k] - Vec3(1, 0, 0)).norm(),
                1e-15);
  ASSERT_EQ(post("/api/undo")->status, 200);
  EXPECT_EQ(model()["dirty"], true);  // the file on disk holds the moved model now
}

TEST_F(StudioServerTest, ExportWritesAReadableMesh) {
  const auto r = post("/api/export", R"({"path": "out/x.glb", "resolution": 9})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const Mesh written = readMesh((root_ / "out/x.glb").string());
  const MeshData served = mesh("?resolution=9");
  EXPECT_EQ(written.vertexCount(), served.vertexCount);
  EXPECT_EQ(written.triangleCount(), served.triangleCount);
  for (const char* ext : {"obj", "stl", "ply"}) {
    const auto e = post("/api/export", Json{{"path", std::string("x.") + ext}}.dump());
    ASSERT_TRUE(e);
    EXPECT_EQ(e->status, 200) << ext << e->body;
    EXPECT_TRUE(fs::exists(root_ / (std::string("x.") + ext)));
  }
  EXPECT_EQ(failure(post("/api/export", R"({"path": "x.glb", "resolution": 1})")).first, 400);
}

// ---------------------------------------------------------------------------------------
// Who may ask: Host, Origin, Content-Type and the token (apps/studio/README.md, "Security")

/// Everything a refused request could have changed: the model's file, every file under the
/// root (the autosave included), and the session as GET /api/model reports it.
struct Snapshot {
  std::map<std::string, std::string> files;
  Json session;
  bool operator==(const Snapshot&) const = default;
};

/// The answer and the status of a request sent exactly as given: only these headers (httplib
/// adds Host unless it is given, and Content-Length), no token unless it is among them.
httplib::Result rawRequest(int port, const std::string& method, const std::string& path,
                           const httplib::Headers& headers, const std::string& body = {}) {
  httplib::Client client("127.0.0.1", port);
  client.set_connection_timeout(5);
  client.set_read_timeout(20);
  if (method == "GET") return client.Get(path.c_str(), headers);
  // An empty content type: httplib sends none (a test gives it among the headers).
  if (method == "POST") return client.Post(path.c_str(), headers, body, "");
  if (method == "PUT") return client.Put(path.c_str(), headers, body, "");
  return client.Delete(path.c_str(), headers, body, "");
}

/// What a whole-server test sends on each POST route: a body the route accepts in the
/// grid fixture's state (with a pending autosave, so recover works).
const std::vector<std::pair<std::string, std::string>>& postRoutes() {
  static const std::vector<std::pair<std::string, std::string>> routes = {
      {"/api/recover", "{}"},
      {"/api/edit", R"({"op": "move-vertex", "vertex": 12, "position": [1, 1, 0.5]})"},
      {"/api/end-group", "{}"},
      {"/api/transform", R"({"scale": 3})"},
      {"/api/undo", "{}"},
      {"/api/redo", "{}"},
      {"/api/export", R"({"path": "attack.obj", "resolution": 3})"},
      {"/api/save-as", R"({"path": "attack.json"})"},
      {"/api/save", "{}"},
      {"/api/open", R"({"path": "grid.json"})"},
      {"/api/discard-recovery", "{}"},
  };
  return routes;
}

/// Writes `bytes` to a new connection to 127.0.0.1:port and reads the answer until the
/// server closes (at most `timeout`). Bytes that are not a `whole` request are followed by
/// the end of the sending side (else the server waits for the rest); a whole one says
/// `Connection: close` (httplib drops a request whose sender has ended).
std::string sendRawBytes(int port, const std::string& bytes, bool whole,
                         std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return "(no socket)";
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    for (std::size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    if (!whole) ::shutdown(fd, SHUT_WR);
    const auto end = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      pollfd p{fd, POLLIN, 0};
      if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
      char buf[4096];
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n <= 0) break;
      answer.append(buf, static_cast<std::size_t>(n));
    }
  }
  ::close(fd);
  return answer;
}

/// The status of a raw HTTP answer, or 0 when the server closed without one.
int rawStatus(const std::string& answer) {
  if (answer.rfind("HTTP/1.1 ", 0) != 0 || answer.size() < 12) return 0;
  return std::atoi(answer.substr(9, 3).c_str());
}

class StudioSecurityTest : public StudioServerTest {
 protected:
  void SetUp() override {
    StudioServerTest::SetUp();
    offerRecovery();
  }

  /// Opens grid.json with a journal that differs from it, so that recover and discard have
  /// work to do.
  void offerRecovery() {
    Json moved = Json::parse(gridModel());
    moved["vertices"][12] = {1, 1, 0.9};
    writeText(root_ / "grid.json.autosave", moved.dump(2));
    ASSERT_EQ(post("/api/open", R"({"path": "grid.json"})")->status, 200);
    ASSERT_EQ(model()["recovery"], true);
  }

  std::string authority() const { return "127.0.0.1:" + std::to_string(port_); }
  /// The headers of the studio's page: its Host, its Origin, the token, JSON.
  httplib::Headers page() const {
    return {{"Host", authority()},
            {"Origin", "http://" + authority()},
            {kTokenHeader, server_->token()},
            {"Content-Type", "application/json"}};
  }
  static httplib::Headers with(httplib::Headers headers, const std::string& name,
                               const std::string& value) {
    headers.erase(name);
    if (!value.empty()) headers.emplace(name, value);
    return headers;
  }

  Snapshot snapshot() {
    server_->flushJournal();
    Snapshot s;
    for (const auto& entry : fs::recursive_directory_iterator(root_))
      if (entry.is_regular_file())
        s.files[fs::relative(entry.path(), root_).generic_string()] = readText(entry.path());
    s.session = model();
    return s;
  }

  /// Sends every POST route with `headers`: each is refused with `status` and a message
  /// containing `reason`, and nothing changes.
  void expectEveryPostRefused(const httplib::Headers& headers, int status,
                              const std::string& reason) {
    const Snapshot before = snapshot();
    for (const auto& [route, body] : postRoutes()) {
      const auto [got, message] = failure(rawRequest(port_, "POST", route, headers, body));
      EXPECT_EQ(got, status) << route << ": " << message;
      EXPECT_NE(message.find(reason), std::string::npos) << route << ": " << message;
    }
    EXPECT_EQ(snapshot(), before);
  }

  /// Every POST route with `headers`: each succeeds.
  void expectEveryPostServed(const httplib::Headers& headers) {
    offerRecovery();
    const Snapshot before = snapshot();
    for (const auto& [route, body] : postRoutes()) {
      if (route == "/api/discard-recovery") offerRecovery();  // save-as took the first one
      const auto r = rawRequest(port_, "POST", route, headers, body);
      ASSERT_TRUE(r) << route;
      EXPECT_EQ(r->status, 200) << route << ": " << r->body;
    }
    EXPECT_NE(snapshot(), before);
    EXPECT_TRUE(fs::exists(root_ / "attack.json"));
    EXPECT_TRUE(fs::exists(root_ / "attack.obj"));
  }
};

TEST_F(StudioSecurityTest, TheTokenIsRandomHexInThePrintedUrl) {
  const std::string token = server_->token();
  EXPECT_EQ(token.size(), 48u);  // 192 bits
  EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
  EXPECT_EQ(server_->url(), "http://" + authority() + "/?token=" + token);
  StudioServer other(model_.string(), StudioOptions{root_.string(), "127.0.0.1", 0});
  EXPECT_NE(other.token(), token);
  EXPECT_EQ(other.token().size(), token.size());
}

TEST_F(StudioSecurityTest, AForeignHostIsRefusedBeforeAnyHandler) {
  const std::string port = std::to_string(port_);
  const Snapshot before = snapshot();
  // DNS rebinding: another name, or another port, for this address.
  for (const std::string& host :
       {"evil.example:" + port, std::string("evil.example"),
        "127.0.0.1:" + std::to_string(port_ + 1), std::string("127.0.0.1"),
        "localhost.evil.example:" + port, "127.0.0.1:" + port + ".evil", "[::1]:" + port}) {
    const httplib::Headers headers = with(page(), "Host", host);
    for (const auto& [method, route] :
         std::vector<std::pair<std::string, std::string>>{{"GET", "/"},
                                                          {"GET", "/api/model"},
                                                          {"GET", "/api/mesh"},
                                                          {"GET", "/api/files"},
                                                          {"POST", "/api/transform"},
                                                          {"POST", "/api/save"}}) {
      const auto [status, message] =
          failure(rawRequest(port_, method, route, headers, R"({"scale": 3})"));
      EXPECT_EQ(status, 403) << host << " " << route << ": " << message;
      EXPECT_NE(message.find("Host"), std::string::npos) << message;
    }
  }
  // No Host at all (HTTP/1.0 style), or two.
  for (const std::string& hosts : {std::string(""), "Host: " + authority() + "\r\nHost: evil\r\n"})
    EXPECT_EQ(rawStatus(sendRawBytes(port_,
                                     "GET /api/model HTTP/1.1\r\nConnection: close\r\n" + hosts +
                                         kTokenHeader + ": " + server_->token() + "\r\n\r\n",
                                     true)),
              403)
        << hosts;
  EXPECT_EQ(snapshot(), before);
  // The names of this address: as bound, and localhost (any case).
  for (const std::string& host : {authority(), "localhost:" + port, "LocalHost:" + port}) {
    const auto r = rawRequest(port_, "GET", "/api/model", with(page(), "Host", host));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << host << ": " << r->body;
  }
}

TEST_F(StudioSecurityTest, AForeignOriginIsRefusedOnEveryPostRoute) {
  for (const std::string& origin :
       {std::string("http://evil.example"), std::string("null"),
        "http://127.0.0.1:" + std::to_string(port_ + 1), "https://" + authority(),
        "http://localhost.evil.example:" + std::to_string(port_), "http://" + authority() + ".x"})
    expectEveryPostRefused(with(page(), "Origin", origin), 403, "Origin");
  // Reading is refused to another page too.
  const auto [status, message] = failure(
      rawRequest(port_, "GET", "/api/model", with(page(), "Origin", "http://evil.example")));
  EXPECT_EQ(status, 403) << message;
  // The page's own origin, under either name, and no Origin at all (a program) are served.
  expectEveryPostServed(page());
  expectEveryPostServed(with(page(), "Origin", "http://localhost:" + std::to_string(port_)));
  expectEveryPostServed(with(page(), "Origin", ""));
}

TEST_F(StudioSecurityTest, APostMustDeclareAJsonBody) {
  // A form or a "simple" fetch() of another page sends these without a preflight.
  for (const std::string& type :
       {std::string("text/plain"), std::string("text/plain;charset=UTF-8"),
        std::string("application/x-www-form-urlencoded"), std::string("application/jsonx"),
        std::string("text/plain; application/json")})
    expectEveryPostRefused(with(page(), "Content-Type", type), 415, "Content-Type");
  // A multipart body httplib parses itself, before any handler: "{}" is none (400).
  expectEveryPostRefused(with(page(), "Content-Type", "multipart/form-data; boundary=x"), 400,
                         "bad request");
  // No Content-Type at all (httplib's client always sends one: a request of bytes).
  const Snapshot before = snapshot();
  for (const auto& [route, body] : postRoutes())
    EXPECT_EQ(rawStatus(sendRawBytes(
                  port_,
                  "POST " + route + " HTTP/1.1\r\nHost: " + authority() +
                      "\r\nConnection: close\r\n" + kTokenHeader + ": " + server_->token() +
                      "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body,
                  true)),
              415)
        << route;
  EXPECT_EQ(snapshot(), before);
  expectEveryPostServed(with(page(), "Content-Type", "Application/JSON; charset=utf-8"));
}

TEST_F(StudioSecurityTest, EveryApiRequestNeedsTheToken) {
  std::string flipped = server_->token();
  flipped.back() = flipped.back() == '0' ? '1' : '0';
  std::string upper = server_->token();
  for (char& c : upper) c = static_cast<char>(std::toupper(c));
  const std::string sameLength(server_->token().size(), '0');
  for (const std::string& token : {std::string(""), sameLength, flipped, server_->token().substr(1),
                                   server_->token() + "0", upper, std::string("null")}) {
    if (token == server_->token()) continue;  // an all-digit token upper-cased
    expectEveryPostRefused(with(page(), kTokenHeader, token), 403, kTokenHeader);
    for (const char* route : {"/api/model", "/api/mesh?resolution=3", "/api/files"}) {
      const auto [status, message] =
          failure(rawRequest(port_, "GET", route, with(page(), kTokenHeader, token)));
      EXPECT_EQ(status, 403) << route << " with \"" << token << "\": " << message;
    }
  }
  // The right token twice with a wrong one: refused (one header, one value).
  httplib::Headers twice = page();
  twice.emplace(kTokenHeader, sameLength);
  expectEveryPostRefused(twice, 403, kTokenHeader);
  // The page itself is served without the token (its address carries it to the script).
  const auto index = rawRequest(port_, "GET", "/", with(page(), kTokenHeader, ""));
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->get_header_value("X-Frame-Options"), "DENY");
  expectEveryPostServed(page());
}

TEST_F(StudioSecurityTest, WithoutATokenHostOriginAndJsonAreStillChecked) {
  startServer(false);
  EXPECT_EQ(server_->token(), "");
  EXPECT_EQ(server_->url(), "http://" + authority() + "/");
  const httplib::Headers noToken = with(page(), kTokenHeader, "");
  const auto r = rawRequest(port_, "GET", "/api/model", noToken);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  expectEveryPostRefused(with(noToken, "Host", "evil.example:" + std::to_string(port_)), 403,
                         "Host");
  expectEveryPostRefused(with(noToken, "Origin", "http://evil.example"), 403, "Origin");
  expectEveryPostRefused(with(noToken, "Content-Type", "text/plain"), 415, "Content-Type");
}

TEST_F(StudioServerTest, OnIpv6LoopbackTheHostIsItsBracketedAddressOrLocalhost) {
  StudioServer v6(model_.string(), StudioOptions{root_.string(), "::1", 0});
  int port = 0;
  try {
    port = v6.start();
  } catch (const StudioError& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  const std::string p = std::to_string(port);
  EXPECT_EQ(v6.url(), "http://[::1]:" + p + "/?token=" + v6.token());
  httplib::Client client("::1", port);
  client.set_connection_timeout(5);
  const auto ask = [&](const std::string& host) {
    const auto r = client.Get("/api/model", {{"Host", host}, {kTokenHeader, v6.token()}});
    return r ? r->status : -1;
  };
  EXPECT_EQ(ask("[::1]:" + p), 200);
  EXPECT_EQ(ask("localhost:" + p), 200);
  EXPECT_EQ(ask("127.0.0.1:" + p), 403);
  EXPECT_EQ(ask("evil.example:" + p), 403);
}

TEST_F(StudioSecurityTest, FifteenHundredGarbageRequestsChangeNothing) {
  constexpr int kRequests = 1500;
  const Snapshot before = snapshot();
  const std::string port = std::to_string(port_);
  const std::string big(2 << 20, 'x');
  std::uint32_t random = 12345;  // a fixed LCG: the same garbage every run
  const auto next = [&random] { return random = random * 1664525u + 1013904223u; };
  std::map<int, int> statuses;
  for (int i = 0; i < kRequests; ++i) {
    int status = 0;
    switch (i % 15) {
      case 0: {  // bytes that are not HTTP at all
        std::string bytes(64 + next() % 512, '\0');
        for (char& c : bytes) c = static_cast<char>(next() >> 24);
        status = rawStatus(sendRawBytes(port_, bytes, false));
        break;
      }
      case 1:  // a request line and headers broken off
        status = rawStatus(sendRawBytes(
            port_, "POST /api/save HTTP/1.1\r\nHost: " + authority() + "\r\nContent-Le", false));
        break;
      case 2:  // a header line of 64 KiB
        status = rawStatus(
            sendRawBytes(port_,
                         "GET /api/model HTTP/1.1\r\nConnection: close\r\nHost: " + authority() +
                             "\r\nX: " + std::string(64 << 10, 'a') + "\r\n\r\n",
                         false));  // refused after its headers: not whole
        break;
      case 3:
        status =
            failure(rawRequest(port_, "POST", "/api/transform",
                               with(page(), "Host", "evil.example:" + port), R"({"scale": 3})"))
                .first;
        break;
      case 4:
        status = failure(rawRequest(port_, "POST", "/api/save",
                                    with(page(), "Origin", "http://evil.example"), "{}"))
                     .first;
        break;
      case 5:
        status = failure(rawRequest(port_, "POST", "/api/edit",
                                    with(page(), "Content-Type", "text/plain"), move(12, 0, 0, 5)))
                     .first;
        break;
      case 6:
        status = failure(rawRequest(port_, "POST", "/api/discard-recovery",
                                    with(page(), kTokenHeader, std::to_string(next())), "{}"))
                     .first;
        break;
      case 7:  // the right headers, a body over the limit
        status = (i % 75 == 7) ? failure(rawRequest(port_, "POST", "/api/edit", page(), big)).first
                               : failure(rawRequest(port_, "POST", "/api/edit", page(),
                                                    big.substr(0, 1 + next() % 4096)))
                                     .first;
        break;
      case 8:
        status = failure(rawRequest(port_, "POST", "/api/edit", page(), "{\"op\": [")).first;
        break;
      case 9:
        status = failure(rawRequest(port_, "POST", "/api/open", page(),
                                    R"({"path": "../../etc/passwd"})"))
                     .first;
        break;
      case 10:
        status = failure(rawRequest(port_, "POST", "/api/edit", page(), move(99, 0, 0, 0))).first;
        break;
      case 11:
        status = failure(rawRequest(port_, "GET", "/api/mesh?resolution=" + std::to_string(next()),
                                    page()))
                     .first;
        break;
      case 12:
        status = failure(rawRequest(port_, "DELETE", "/api/model", page(), "{}")).first;
        break;
      case 13:
        status = failure(rawRequest(port_, "GET", "/../../etc/passwd", page())).first;
        break;
      default:
        status =
            failure(rawRequest(port_, "POST", "/api/save-as", page(), R"({"path": "/tmp/x.json"})"))
                .first;
    }
    ++statuses[status];
    ASSERT_NE(status, 200) << "request " << i << " was served";
    ASSERT_NE(status, -1) << "request " << i << ": the server did not answer";
  }
  EXPECT_EQ(snapshot(), before);
  // Refused for each reason: Host, Origin, token (403), JSON (415), then the handlers' own.
  EXPECT_GT(statuses[403], 0);
  EXPECT_GT(statuses[415], 0);
  EXPECT_GT(statuses[413], 0);
  EXPECT_GT(statuses[400], 0);
  // Still serving.
  const auto r = post("/api/edit", move(0, 0, 0, 1));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(mesh().revision, before.session["revision"].get<std::uint32_t>() + 1);
}

// ---------------------------------------------------------------------------------------
// `pdesurf studio`

struct Child {
  pid_t pid = -1;
  int out = -1;  ///< read end of its stdout
};

Child spawnCli(const std::vector<std::string>& args, const std::string& errFile) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addopen(&actions, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  std::vector<std::string> all = {PDESURF_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  Child child;
  const int rc = ::posix_spawn(&child.pid, PDESURF_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    throw std::runtime_error("posix_spawn failed");
  }
  child.out = fds[0];
  return child;
}

/// The first line of the child's stdout, waiting at most `timeout`.
std::string readLine(int fd, std::chrono::milliseconds timeout) {
  std::string line;
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (line.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    char buf[256];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    line.append(buf, static_cast<std::size_t>(n));
  }
  return line.substr(0, line.find('\n'));
}

/// The exit status, or -1 (after SIGKILL) when the child has not exited within `timeout`.
int waitExit(pid_t pid, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (::waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

class StudioCliTest : public StudioServerTest {};

TEST_F(StudioCliTest, MissingModelExitsOne) {
  const std::string err = (root_ / "err.txt").string();
  Child child = spawnCli({"studio", (root_ / "missing.json").string(), "--port", "0"}, err);
  EXPECT_EQ(waitExit(child.pid, std::chrono::seconds(10)), 1);
  ::close(child.out);
  const std::string message = readText(err);
  EXPECT_NE(message.find("missing.json"), std::string::npos) << message;
}

/// The port and the token of the URL `pdesurf studio` printed on its first line (0 and ""
/// when the line is not "pdesurf studio: http://127.0.0.1:PORT/?token=TOKEN (model: ...").
std::pair<int, std::string> printedAddress(const std::string& line) {
  static const std::regex url(
      R"(^pdesurf studio: http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]{48}) \(model: )");
  std::smatch m;
  if (!std::regex_search(line, m, url)) return {0, ""};
  return {std::stoi(m[1]), m[2]};
}

/// The status of GET /api/model from the studio on `port` with `token`.
int modelStatus(int port, const std::string& token) {
  httplib::Client client("127.0.0.1", port);
  client.set_connection_timeout(5);
  client.set_read_timeout(10);
  const auto r = client.Get("/api/model", {{kTokenHeader, token}});
  return r ? r->status : -1;
}

TEST_F(StudioCliTest, ServesUntilSigterm) {
  const std::string err = (outside_ / "err.txt").string();
  Child child = spawnCli({"studio", model_.string(), "--port", "0"}, err);
  const std::string line = readLine(child.out, std::chrono::seconds(10));
  EXPECT_NE(line.find("(model: " + model_.string() + ", root: " + root_.string() + ")"),
            std::string::npos)
      << line;
  const auto [port, token] = printedAddress(line);
  EXPECT_GT(port, 0) << line;
  if (port > 0) {
    EXPECT_EQ(modelStatus(port, token), 200);
    EXPECT_EQ(modelStatus(port, ""), 403);
  }
  ::kill(child.pid, SIGTERM);
  EXPECT_EQ(waitExit(child.pid, std::chrono::seconds(10)), 0) << readText(err);
  ::close(child.out);
}

TEST_F(StudioCliTest, NoTokenIsAnnouncedAsUnsafe) {
  const std::string err = (outside_ / "err.txt").string();
  Child child = spawnCli({"studio", model_.string(), "--port", "0", "--no-token"}, err);
  const std::string line = readLine(child.out, std::chrono::seconds(10));
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(line, m, std::regex(R"(^pdesurf studio: http://127\.0\.0\.1:(\d+)/ )")))
      << line;
  EXPECT_EQ(modelStatus(std::stoi(m[1]), ""), 200);
  ::kill(child.pid, SIGTERM);
  EXPECT_EQ(waitExit(child.pid, std::chrono::seconds(10)), 0);
  ::close(child.out);
  EXPECT_NE(readText(err).find("--no-token: UNSAFE"), std::string::npos) << readText(err);
}

TEST_F(StudioCliTest, KilledMidEditTheFileIsIntactAndTheJournalOffersTheEdits) {
  // `pdesurf studio`, its checks on, receives a stream of edits (a drag) and is killed with
  // SIGKILL among them: the model's file is byte for byte what it was, the journal is a
  // whole model holding one of the positions sent, and the next launch (a new token; the
  // old one refused) offers it back.
  const std::string original = readText(model_);
  const std::string err = (outside_ / "err.txt").string();
  Child child = spawnCli({"studio", model_.string(), "--port", "0"}, err);
  const auto [port, token] = printedAddress(readLine(child.out, std::chrono::seconds(10)));
  ASSERT_GT(port, 0);
  constexpr int kEdits = 100000;  // more than are answered before the kill
  const auto z = [](int i) { return 0.001 * (i + 1); };
  std::atomic<int> answered{0};
  std::thread drag([&, port = port, token = token] {
    httplib::Client client("127.0.0.1", port);
    client.set_connection_timeout(2);
    client.set_read_timeout(2);
    client.set_default_headers({{kTokenHeader, token}});
    for (int i = 0; i < kEdits; ++i) {
      const auto r = client.Post("/api/edit", move(12, 1, 1, z(i), "drag"), "application/json");
      if (!r || r->status != 200) return;  // killed
      answered = i + 1;
    }
  });
  // Killed once the journal holds some edits and more are in flight.
  const fs::path journal = root_ / "grid.json.autosave";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((answered < 50 || !fs::exists(journal)) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(child.pid, SIGKILL);
  drag.join();
  EXPECT_EQ(waitExit(child.pid, std::chrono::seconds(10)), -2);  // killed by a signal
  ::close(child.out);
  ASSERT_GE(answered.load(), 50) << readText(err);

  EXPECT_EQ(readText(model_), original);
  ASSERT_TRUE(fs::exists(journal));
  const auto saved = parseVertexFrameModel(readText(journal), "grid.json.autosave");
  const double journaled = saved.vertices[12].z();
  int sent = -1;
  for (int i = 0; i <= answered && sent < 0; ++i)  // the edit in flight may be in it too
    if (std::abs(journaled - z(i)) < 1e-12) sent = i;
  EXPECT_GE(sent, 0) << "the journal holds z = " << journaled << ", never sent";

  Child again = spawnCli({"studio", model_.string(), "--port", "0"}, err);
  const auto [port2, token2] = printedAddress(readLine(again.out, std::chrono::seconds(10)));
  ASSERT_GT(port2, 0);
  EXPECT_NE(token2, token);
  EXPECT_EQ(modelStatus(port2, token), 403);
  httplib::Client client("127.0.0.1", port2);
  client.set_connection_timeout(5);
  client.set_read_timeout(10);
  client.set_default_headers({{kTokenHeader, token2}});
  const auto before = client.Get("/api/model");
  ASSERT_TRUE(before && before->status == 200);
  EXPECT_EQ(Json::parse(before->body)["recovery"], true);
  const auto recovered = client.Post("/api/recover", "{}", "application/json");
  ASSERT_TRUE(recovered && recovered->status == 200);
  const auto after = client.Get("/api/model");
  ASSERT_TRUE(after && after->status == 200);
  EXPECT_DOUBLE_EQ(Json::parse(after->body)["model"]["vertices"][12][2].get<double>(), journaled);
  ::kill(again.pid, SIGTERM);
  EXPECT_EQ(waitExit(again.pid, std::chrono::seconds(10)), 0) << readText(err);
  ::close(again.out);
  EXPECT_EQ(readText(model_), original);
}

}  // namespace
}  // namespace pdesurf::studio
