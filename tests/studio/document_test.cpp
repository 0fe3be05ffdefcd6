// Tests of the studio's open model file without HTTP (apps/studio/document.hpp): revisions,
// saving what the editor does not hold, the autosave journal and its recovery, and the
// refusals the routes answer with.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "document.hpp"
#include "http_error.hpp"
#include "journal.hpp"
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
  const Json view = doc.viewCurves();
  EXPECT_FALSE(view["curves"].empty());
}

}  // namespace
}  // namespace pdesurf::studio
