// The studio's open model file: its editing session, revision counter, the file's text as
// read and saved, saving, the autosave journal and its recovery. No HTTP here: the routes
// (routes_*.cpp) call it under the server's lock; tests/studio/document_test.cpp drives it
// directly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "journal.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/session.hpp"
#include "root_sandbox.hpp"

namespace pdesurf::studio {

class Document {
 public:
  /// Paths are answered relative to `sandbox`'s root (the sandbox outlives the document).
  explicit Document(const RootSandbox& sandbox) : sandbox_(sandbox) {}

  /// Loads a model file (ModelError naming it as `source` when it cannot be read or parsed,
  /// the open model unchanged) and starts a new session; notes whether an autosave beside it
  /// holds edits the file lacks.
  void open(const std::filesystem::path& path, const std::string& source);
  /// Writes the model to `path` atomically (HttpError 500 when it cannot; nothing changes
  /// then), makes it the document's file and removes the autosave journals.
  void save(const std::filesystem::path& path);
  /// Replaces the session with the autosaved model (HttpError 409 without a recovery).
  void recover();
  /// Removes the autosave journal (HttpError 409 without a recovery, 500 when it stays).
  void discardRecovery();
  /// Journals the current model beside its file (not while a recovery is pending: it would
  /// overwrite the edits it holds).
  void autosave();
  /// Waits until the journal is on disk.
  void flushJournal() { journal_.flush(); }

  ModelSession& session() { return *session_; }
  const ModelSession& session() const { return *session_; }
  /// Increases with every change, across the sessions of every model opened.
  std::uint64_t revision() const { return base_ + (session_ ? session_->revision() : 0); }
  const std::filesystem::path& path() const { return path_; }
  bool recovery() const { return recovery_; }

  /// {revision, undo, redo, dirty}.
  nlohmann::json status() const;
  /// status() with the path and whether an autosave offers recovery (open, new).
  nlohmann::json openedStatus() const;
  /// HttpError 409 unless the model has vertex frames (the routes of frames need them).
  void requireEditable() const;
  /// The current model as its file says when it is the model read or saved last (so an
  /// untransformed view-only model is shown, saved and copied exactly as written), else as
  /// serializeModel writes it. A model with editable parts is always written by
  /// serializeModel.
  std::string modelText() const;
  /// What GET /api/model serves of a model without editable parts besides the model itself
  /// (apps/studio/README.md): "view" (its overlay: {"curves", "spines"} as polylines),
  /// "handles" (SurfaceMethod::handles: {"points": [{"kind", its reference, "p"}...],
  /// "curves": [{"ref", "label", "centre", "vectors"}...], "tangentDraw"}), "settings"
  /// (SurfaceMethod::settings: {"edits", "overlay", "operator"?}) and "dragAdvice". Computed
  /// once per revision (every edit, undo, redo and load is a new one).
  const nlohmann::json& shapeParts();

 private:
  void replaceSession(AnyModel model, const std::string& source);

  const RootSandbox& sandbox_;
  std::filesystem::path path_;
  std::unique_ptr<ModelSession> session_;
  std::uint64_t base_ = 0;
  std::uint64_t savedRevision_ = 0;
  bool recovery_ = false;
  bool opened_ = false;
  std::string fileText_;     ///< the model's file as read or saved last
  std::string fileModel_;    ///< serializeModel of that file's model
  std::string openedText_;   ///< the model's file as opened
  std::string openedModel_;  ///< serializeModel of the model as opened
  Journal journal_;
  nlohmann::json shapeParts_;  ///< shapeParts() of revision shapeRevision_ (null: none)
  std::uint64_t shapeRevision_ = 0;
};

}  // namespace pdesurf::studio
