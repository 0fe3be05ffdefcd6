// The studio's open model file (document.hpp).
#include "document.hpp"

#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "http_error.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Json polylines(const std::vector<std::vector<Vec3>>& lines) {
  Json out = Json::array();
  for (const std::vector<Vec3>& polyline : lines) {
    Json line = Json::array();
    for (const Vec3& q : polyline) line.push_back({q.x(), q.y(), q.z()});
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

Json Document::status() const {
  return {{"revision", revision()},
          {"undo", session_->undoDepth()},
          {"redo", session_->redoDepth()},
          {"dirty", revision() != savedRevision_}};
}

Json Document::openedStatus() const {
  Json out = status();
  out["path"] = sandbox_.relative(path_);
  out["recovery"] = recovery_;
  return out;
}

void Document::requireEditable() const {
  if (!session_->hasEditableParts())
    fail(409, fmt::format("{} models have no vertex frames: this is for vertex-frame models "
                          "(their edits are POST /api/edit's, the whole model POST /api/transform)",
                          modelTypeName(session_->model())));
}

void Document::replaceSession(AnyModel model, const std::string& source) {
  const std::uint64_t next = opened_ ? revision() + 1 : 0;
  session_ = std::make_unique<ModelSession>(std::move(model), source);
  base_ = next;
  opened_ = true;
  shapeParts_ = nullptr;  // another model: its parts are computed when asked for
}

void Document::open(const fs::path& path, const std::string& source) {
  journal_.cancel();  // the journal read below must not change underneath
  const std::string fileText = readFile(path);
  replaceSession(parseModel(fileText, source), source);  // a type it cannot open throws
  const std::string text = serializeModel(session_->model());
  path_ = path;
  fileText_ = fileText;
  fileModel_ = text;
  openedText_ = fileText;
  openedModel_ = text;
  savedRevision_ = revision();
  // An autosave that differs from the file holds edits a crash left unsaved.
  recovery_ = false;
  std::error_code ec;
  if (fs::exists(autosavePath(path_), ec)) {
    try {
      const AnyModel saved =
          parseModel(readFile(autosavePath(path_)), autosavePath(path_).filename().string());
      recovery_ = serializeModel(saved) != text;
    } catch (const std::exception&) {
      recovery_ = false;  // an unreadable journal is no recovery
    }
  }
}

std::string Document::modelText() const {
  std::string text = serializeModel(session_->model());
  if (session_->hasEditableParts()) return text;
  if (text == fileModel_) return fileText_;
  // Shape edits undone after a save: the model as opened is written as its file was.
  return text == openedModel_ ? openedText_ : text;
}

namespace {

/// SurfaceMethod::handles as GET /api/model's "handles".
Json handlesJson(const ModelHandles& handles) {
  const auto ref = [](const CurveRef& r) { return r.name.empty() ? Json(r.index) : Json(r.name); };
  const auto xyz = [](const Vec3& p) { return Json::array({p.x(), p.y(), p.z()}); };
  Json points = Json::array();
  for (const ModelHandle& h : handles.points) {
    Json j;
    switch (h.kind) {
      case ModelHandle::Kind::CurvePoint:
        j = {{"kind", "curve"}, {"curve", ref(h.curve)}, {"point", h.index}};
        break;
      case ModelHandle::Kind::Tangent:
        j = {{"kind", "tangent"}, {"curve", ref(h.curve)}, {"point", h.index}};
        j["base"] = xyz(h.base);
        if (h.mean) j["mean"] = true;
        break;
      case ModelHandle::Kind::ControlPoint:
        j = {{"kind", "control"}, {"i", h.index}, {"j", h.column}};
        break;
      case ModelHandle::Kind::SpinePoint:
        j = {{"kind", "spine"}, {"index", h.index}, {"u", h.u}};
        break;
    }
    j["p"] = xyz(h.position);
    points.push_back(std::move(j));
  }
  Json curves = Json::array();
  for (const HandleCurve& c : handles.curves)
    curves.push_back({{"ref", ref(c.ref)},
                      {"label", c.label},
                      {"centre", xyz(c.centre)},
                      {"vectors", c.vectors}});
  return {
      {"points", std::move(points)}, {"curves", std::move(curves)}, {"tangentDraw", kTangentDraw}};
}

/// SurfaceMethod::settings as GET /api/model's "settings".
Json settingsJson(const ModelSettings& settings) {
  Json out = {{"edits", settings.edits}, {"overlay", settings.overlay}};
  if (const auto& op = settings.op) {
    // set-operator's fields, as that edit names them (edit_io.hpp).
    Json j = {{"a", op->a}, {"modes", op->modes}, {"remainder", op->remainder}};
    if (op->kind) j["operator"] = *op->kind == OperatorKind::Fu ? "fu" : "ugail";
    if (op->power) j["N"] = *op->power;
    if (op->method) j["method"] = chainMethodName(*op->method);
    out["operator"] = std::move(j);
  }
  return out;
}

}  // namespace

const Json& Document::shapeParts() {
  if (shapeRevision_ == revision() && !shapeParts_.is_null()) return shapeParts_;
  const AnyModel& model = session_->model();
  const SolvedModel& solved = session_->solved();
  const ModelOverlay view = overlay(solved);
  shapeParts_ = {{"view", {{"curves", polylines(view.curves)}, {"spines", polylines(view.spines)}}},
                 {"handles", handlesJson(model.method().handles(solved))},
                 {"settings", settingsJson(model.method().settings(model))},
                 {"dragAdvice", dragAdvice(model)}};
  shapeRevision_ = revision();
  return shapeParts_;
}

void Document::autosave() {
  if (recovery_) return;
  journal_.write(autosavePath(path_), session_->model());
}

void Document::save(const fs::path& path) {
  try {
    // A model as its file holds it is saved as the file was (save as: a copy); else the
    // fields of the file the model's method does not hold ("description", a frame's or a
    // tool's own fields) are kept, matched by identity (keepUnknownFields), for every type.
    std::string text = modelText();
    if (text != fileText_) text = keepUnknownFields(text, fileText_);
    writeFileAtomically(path.string(), text);
    fileText_ = text;
    fileModel_ = serializeModel(session_->model());
  } catch (const std::exception& e) {
    fail(500, e.what());
  }
  journal_.cancel();
  std::error_code ec;
  fs::remove(autosavePath(path), ec);
  if (path != path_) fs::remove(autosavePath(path_), ec);
  path_ = path;
  savedRevision_ = revision();
  recovery_ = false;
}

void Document::recover() {
  if (!recovery_) fail(409, "no autosave to recover");
  const fs::path journal = autosavePath(path_);
  replaceSession(parseModel(readFile(journal), sandbox_.relative(journal)),
                 sandbox_.relative(journal));
  recovery_ = false;  // the journal now matches the session
}

void Document::discardRecovery() {
  if (!recovery_) fail(409, "no autosave to discard");
  std::error_code ec;
  fs::remove(autosavePath(path_), ec);
  if (ec) fail(500, fmt::format("cannot remove the autosave: {}", ec.message()));
  recovery_ = false;
}

}  // namespace pdesurf::studio
