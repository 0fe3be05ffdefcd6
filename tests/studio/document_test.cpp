// Tests of the studio's open model file without HTTP (apps/studio/document.hpp): revisions,
// saving what the editor does not hold, the autosave journal and its recovery, and the
// refusals the routes answer with.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "document.hpp"
#include "http_error.hpp"
#include "journal.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "support/cli_run.hpp"

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using testing::readText;

/// A temporary root folder holding a copy of an example, removed afterwards.
class DocumentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        fs::temp_directory_path() /
        ("pdesurf-document-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    root_ = fs::canonical(root_);
    sandbox_ = RootSandbox(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path copyExample(const std::string& name) {
    const fs::path to = root_ / name;
    fs::copy_file(fs::path(PDESURF_SOURCE_DIR) / "examples" / name, to);
    return to;
  }

  fs::path root_;
  RootSandbox sandbox_;
};

/// Moves vertex 0 of a vertex-frame document by `dx` along x.
void nudge(Document& doc, double dx) {
  const VertexFrameModel& model = *doc.session().frames();
  MoveVertex move{0, model.vertices[0] + Vec3(dx, 0, 0)};
  doc.session().apply(move);
}

TEST_F(DocumentTest, RevisionAndDirtyFollowEditsUndoAndSave) {
  Document doc(sandbox_);
  doc.open(copyExample("mug.json"), "mug.json");
  EXPECT_EQ(doc.status()["dirty"], false);
  const std::uint64_t r0 = doc.revision();
  nudge(doc, 0.01);
  EXPECT_GT(doc.revision(), r0);
  EXPECT_EQ(doc.status()["dirty"], true);
  EXPECT_EQ(doc.status()["undo"], 1);
  ASSERT_TRUE(doc.session().undo());
  // Undo is a change too (the page redraws), so the revision grows and the model is dirty.
  EXPECT_GT(doc.revision(), r0);
  doc.save(doc.path());
  EXPECT_EQ(doc.status()["dirty"], false);
  EXPECT_EQ(doc.openedStatus()["path"], "mug.json");
}

TEST_F(DocumentTest, SaveKeepsFieldsTheEditorDoesNotHold) {
  const fs::path path = copyExample("mug.json");
  Json file = Json::parse(readText(path));
  file["description"] = "a mug, described";
  file["x-note"] = {{"by", "a test"}};
  std::ofstream(path, std::ios::binary) << file.dump(2);
  Document doc(sandbox_);
  doc.open(path, "mug.json");
  nudge(doc, 0.02);
  doc.save(path);
  const Json saved = Json::parse(readText(path));
  EXPECT_EQ(saved["description"], "a mug, described");
  EXPECT_EQ(saved["x-note"]["by"], "a test");
  // The edit itself is saved.
  EXPECT_NEAR(saved["vertices"][0][0].get<double>(), file["vertices"][0][0].get<double>() + 0.02,
              1e-12);
}

TEST_F(DocumentTest, SaveKeepsUnknownFieldsOfEveryTypeMatchedByIdentity) {
  // Each type's file fields are kept after an edit of its own through the one edit path (these
  // methods' parsers refuse unknown fields and hold "description"; vertex frames' below).
  for (const char* example :
       {"membrane.json", "vase-sections.json", "bspline-dome.json", "bspline-blend.json"}) {
    SCOPED_TRACE(example);
    const fs::path path = copyExample(example);
    const Json file = Json::parse(readText(path));
    Document doc(sandbox_);
    doc.open(path, example);
    const char* edit =
        std::string(example) == "bspline-blend.json"
            ? R"({"op": "transform-curve", "curve": "uMin", "translate": [0, 0, 0.01]})"
        : std::string(example) == "bspline-dome.json"
            ? R"({"op": "transform-curve", "curve": "vMax", "translate": [0, 0, 0.01]})"
            : R"({"op": "transform-curve", "curve": 1, "translate": [0, 0, 0.01]})";
    doc.session().apply(parseEdit(edit, doc.session().model()));
    const std::string edited = serializeModel(doc.session().model());
    doc.save(path);
    const std::string saved = readText(path);
    EXPECT_EQ(Json::parse(saved)["description"], file["description"]);
    // The kept fields change nothing of the model: it reads back as the edit made it.
    EXPECT_EQ(serializeModel(parseModel(saved, "saved")), edited);
  }
  // A frame's own field stays with its frame by identity: an extrusion adds frames (a match
  // by index alone needs as many frames as the file).
  const fs::path path = copyExample("grid-forces.json");
  Json file = Json::parse(readText(path));
  file["x-note"] = {{"by", "a test"}};
  file["frames"][1]["x-tag"] = "kept";
  std::ofstream(path, std::ios::binary) << file.dump(2);
  Document doc(sandbox_);
  doc.open(path, "grid-forces.json");
  // The first boundary side found (extrusion leaves the frames there as they are).
  const std::size_t frames = file["frames"].size();
  for (std::size_t k = 0; k < 4 * frames && doc.session().undoDepth() == 0; ++k) try {
      doc.session().apply(parseEdit(fmt::format(R"({{"op": "extrude", "edges": [{{"frame": {}, )"
                                                R"("side": {}}}]}})",
                                                k / 4, k % 4),
                                    doc.session().model()));
    } catch (const ModelError&) {
      // not a boundary side: the next
    }
  ASSERT_EQ(doc.session().undoDepth(), 1u);
  doc.save(path);
  const Json saved = Json::parse(readText(path));
  ASSERT_GT(saved["frames"].size(), file["frames"].size());
  EXPECT_EQ(saved["x-note"]["by"], "a test");
  EXPECT_EQ(saved["frames"][1].value("x-tag", ""), "kept");
  EXPECT_EQ(saved["frames"][0].count("x-tag"), 0u);
}

TEST_F(DocumentTest, AnAutosaveThatDiffersIsOfferedRecoveredAndDiscarded) {
  const fs::path path = copyExample("mug.json");
  const std::string original = readText(path);
  std::string edited;
  {
    Document doc(sandbox_);
    doc.open(path, "mug.json");
    nudge(doc, 0.03);
    doc.autosave();
    doc.flushJournal();
    edited = serializeModel(doc.session().model());
  }  // a crash: the edits were journalled, never saved
  ASSERT_TRUE(fs::exists(autosavePath(path)));
  EXPECT_EQ(readText(path), original);

  Document doc(sandbox_);
  doc.open(path, "mug.json");
  ASSERT_TRUE(doc.recovery());
  EXPECT_EQ(doc.openedStatus()["recovery"], true);
  // While a recovery is pending, the journal is not overwritten by later autosaves.
  nudge(doc, 0.5);
  doc.autosave();
  doc.flushJournal();
  EXPECT_EQ(serializeModel(parseModel(readText(autosavePath(path)), "journal")), edited);
  doc.recover();
  EXPECT_FALSE(doc.recovery());
  EXPECT_EQ(serializeModel(doc.session().model()), edited);
  EXPECT_THROW(doc.recover(), HttpError);  // nothing left to recover

  // Reopened with the same journal: discarding removes it and keeps the file as it was.
  Document again(sandbox_);
  again.open(path, "mug.json");
  ASSERT_TRUE(again.recovery());
  again.discardRecovery();
  EXPECT_FALSE(fs::exists(autosavePath(path)));
  EXPECT_EQ(readText(path), original);
  try {
    again.discardRecovery();
    FAIL() << "a second discard was accepted";
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status, 409);
  }
}

TEST_F(DocumentTest, AJournalEqualToTheFileIsNoRecovery) {
  const fs::path path = copyExample("mug.json");
  std::ofstream(autosavePath(path), std::ios::binary) << readText(path);
  Document doc(sandbox_);
  doc.open(path, "mug.json");
  EXPECT_FALSE(doc.recovery());
}

TEST_F(DocumentTest, AFailedOpenKeepsTheOpenModel) {
  const fs::path good = copyExample("mug.json");
  const fs::path bad = root_ / "bad.json";
  std::ofstream(bad, std::ios::binary) << "{\"type\": \"vertex-frames\", \"vertices\": [";
  Document doc(sandbox_);
  doc.open(good, "mug.json");
  nudge(doc, 0.04);
  const std::string before = serializeModel(doc.session().model());
  const std::uint64_t revision = doc.revision();
  EXPECT_THROW(doc.open(bad, "bad.json"), ModelError);
  EXPECT_EQ(serializeModel(doc.session().model()), before);
  EXPECT_EQ(doc.revision(), revision);
  EXPECT_EQ(doc.path(), good);
}

TEST_F(DocumentTest, ViewOnlyModelsRefuseFrameRoutesAndKeepTheirFileText) {
  const fs::path path = copyExample("membrane.json");
  Document doc(sandbox_);
  doc.open(path, "membrane.json");
  try {
    doc.requireEditable();
    FAIL() << "a spectral model passed requireEditable";
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status, 409);
    EXPECT_NE(e.message.find("no vertex frames"), std::string::npos) << e.message;
  }
  // Untransformed, the model is shown and saved exactly as its file was written.
  EXPECT_EQ(doc.modelText(), readText(path));
  const Json view = doc.shapeParts()["view"];
  EXPECT_FALSE(view["curves"].empty());
}

}  // namespace
}  // namespace pdesurf::studio
