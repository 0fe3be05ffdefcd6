// The studio server (server.hpp). Every handler takes one lock: edits, solves and file
// writes are serialised, so the HTTP threads never see a half-applied change.
#include "server.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "access_guard.hpp"
#include "http_error.hpp"
#include "journal.hpp"
#include "mesh_wire.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/session.hpp"
#include "root_sandbox.hpp"
// After Eigen: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers.
#include <httplib.h>

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxBody = 1 << 20;
constexpr std::uint32_t kMinResolution = 2, kMaxMeshResolution = 257, kMaxExportResolution = 4097;
constexpr std::uint32_t kDefaultMeshResolution = 16, kDefaultExportResolution = 33;
/// Resolutions whose last mesh the server keeps as a delta base: a gesture's preview and the
/// chosen resolution (web/src/preview.ts).
constexpr std::size_t kMeshSlots = 2;
/// The spine points a spectral model shows to drag (GET /api/model's view.spineHandles).
constexpr std::uint32_t kSpineHandles = 9;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void sendJson(httplib::Response& res, const Json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

/// The request body as a JSON object (400 otherwise).
Json bodyObject(const httplib::Request& req) {
  Json doc = Json::parse(req.body, nullptr, false);
  if (doc.is_discarded()) fail(400, "$: malformed JSON");
  if (!doc.is_object()) fail(400, fmt::format("$: expected an object, found {}", doc.type_name()));
  return doc;
}

std::string stringMember(const Json& doc, const std::string& name) {
  auto it = doc.find(name);
  if (it == doc.end()) fail(400, fmt::format("$: missing \"{}\"", name));
  if (!it->is_string())
    fail(400, fmt::format("$.{}: expected a string, found {}", name, it->type_name()));
  return it->get<std::string>();
}

/// A whole non-negative decimal number in [lo, hi] (400 naming `what` otherwise).
std::uint32_t parseUint(const std::string& text, std::uint32_t lo, std::uint32_t hi,
                        const std::string& what) {
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi)
    fail(400, fmt::format("{}: expected a whole number from {} to {}, found \"{}\"", what, lo, hi,
                          text));
  return value;
}

// The built front-end of this source tree, web/dist (`make build` makes it). The build may
// define PDESURF_WEB_DIR_DEFAULT; otherwise it is found from this file's path.
#ifndef PDESURF_WEB_DIR_DEFAULT
#define PDESURF_WEB_DIR_DEFAULT ""
#endif

constexpr const char* kIndexPage = R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>pdesurf studio</title></head>
<body>
<h1>pdesurf studio</h1>
<p>The studio's web front-end is not built here (<code>make build</code> builds web/dist; <code>PDESURF_WEB_DIR</code> names another folder). The server's JSON API:</p>
<ul>
<li>GET /api/model: the model, its path, revision, undo and redo depths, dirty, recovery</li>
<li>POST /api/new (a new model file), /api/edit (an edit), /api/transform (move, turn, scale the model), /api/end-group, /api/undo, /api/redo</li>
<li>GET /api/mesh?resolution=N&amp;solver=global|local&amp;seed=K: the surface as binary buffers</li>
<li>GET /api/files; POST /api/open, /api/save, /api/save-as, /api/export {"path": ...}</li>
<li>POST /api/recover, /api/discard-recovery: the autosave journal</li>
</ul>
</body></html>
)";

}  // namespace

std::string defaultWebDir() {
  if (const char* env = std::getenv("PDESURF_WEB_DIR"); env && *env) return env;
  if (*PDESURF_WEB_DIR_DEFAULT) return PDESURF_WEB_DIR_DEFAULT;
  return (fs::path(__FILE__).parent_path().parent_path().parent_path() / "web" / "dist").string();
}

class StudioServer::Impl {
 public:
  Impl(const std::string& modelPath, StudioOptions options)
      : options_(std::move(options)), access_(options_.requireToken) {
    std::error_code ec;
    fs::path model = fs::absolute(modelPath, ec);
    if (!fs::exists(model, ec) || fs::is_directory(model, ec))
      throw ModelError(modelPath, "", "cannot open the file for reading");
    model = fs::canonical(model, ec);
    const fs::path root = options_.root.empty() ? model.parent_path() : fs::path(options_.root);
    if (!fs::is_directory(root, ec))
      throw StudioError(fmt::format("--root {}: not a folder", root.string()));
    sandbox_ = RootSandbox(fs::canonical(root, ec));
    if (ec) throw StudioError(fmt::format("--root {}: {}", root.string(), ec.message()));
    if (!sandbox_.inside(model))
      throw StudioError(fmt::format("{}: the model is outside the root folder {}", modelPath,
                                    sandbox_.root().string()));
    openModel(model, modelPath);
    routes();
  }

  ~Impl() { stop(); }

  int start() {
    if (thread_.joinable()) return port_;
    if (options_.port == 0) {
      port_ = server_.bind_to_any_port(options_.host);
    } else {
      port_ = server_.bind_to_port(options_.host, options_.port) ? options_.port : -1;
    }
    if (port_ < 0)
      throw StudioError(fmt::format("cannot listen on {}:{}", options_.host, options_.port));
    access_.bind(options_.host, port_);
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    // stop() before the server runs would be lost: wait until it does.
    for (int i = 0; i < 5000 && !server_.is_running(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return port_;
  }

  void stop() {
    if (!thread_.joinable()) return;
    server_.stop();
    thread_.join();
  }

  int port() const { return port_; }
  void flushJournal() { journal_.flush(); }
  std::string url() const {
    return fmt::format("http://{}:{}/{}", urlHost(options_.host), port_,
                       access_.token().empty() ? "" : "?token=" + access_.token());
  }
  const std::string& token() const { return access_.token(); }
  std::string root() const { return sandbox_.root().string(); }
  std::string webDir() const { return webDir_.string(); }
  std::string modelPath() const {
    std::lock_guard lock(mutex_);
    return path_.string();
  }

 private:
  // ------------------------------------------------------------------------------------
  // The session

  std::uint64_t revision() const { return base_ + (session_ ? session_->revision() : 0); }

  Json status() const {
    return {{"revision", revision()},
            {"undo", session_->undoDepth()},
            {"redo", session_->redoDepth()},
            {"dirty", revision() != savedRevision_}};
  }

  /// The routes of vertex frames (their edits, boundaries, patch ids, curvature) need a
  /// vertex-frame model; the other types take shape edits (session.hpp: ShapeEdit) and
  /// whole-model transforms.
  void requireEditable() const {
    if (!session_->editable())
      fail(409, fmt::format("{} models have no vertex frames: this is for vertex-frame models "
                            "(their curves take shape edits, the whole model POST /api/transform)",
                            modelTypeName(session_->model())));
  }

  /// The open model, whatever its type (a copy: for the journal).
  AnyModel currentModel() const { return session_->model(); }

  /// Replaces the session with `model` (solving one without editable parts first: it throws
  /// ModelError before anything changes); the revision keeps increasing across sessions.
  void replaceSession(AnyModel model, const std::string& source) {
    const std::uint64_t next = opened_ ? revision() + 1 : 0;
    session_ = std::make_unique<ModelSession>(std::move(model), source);
    base_ = next;
    opened_ = true;
  }

  /// Loads a model file (throws ModelError, naming it as `source`) and starts a new session.
  void openModel(const fs::path& path, const std::string& source) {
    journal_.cancel();  // the journal read below must not change underneath
    const std::string fileText = readFile(path);
    replaceSession(parseModel(fileText, source), source);  // a type it cannot open throws
    const std::string text = serializeModel(currentModel());
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

  /// A model file a request names (save as, new): inside the root, ending in .json.
  fs::path modelFilePath(const std::string& requested) const {
    const fs::path path = sandbox_.resolve(requested);
    if (path.extension() != ".json")
      fail(400, fmt::format("{}: a model file ends in .json", requested));
    return path;
  }

  /// The status after a model was opened (open, new): with its path and whether an autosave
  /// offers recovery.
  Json openedStatus() const {
    Json out = status();
    out["path"] = sandbox_.relative(path_);
    out["recovery"] = recovery_;
    return out;
  }

  /// The current model as its file says when it is the model read or saved last (so an
  /// untransformed view-only model is shown, saved and copied exactly as written), else as
  /// serializeModel writes it. A model with editable parts is always written by
  /// serializeModel.
  std::string modelText() const {
    std::string text = serializeModel(session_->model());
    if (session_->editable()) return text;
    if (text == fileModel_) return fileText_;
    // Shape edits undone after a save: the model as opened is written as its file was.
    return text == openedModel_ ? openedText_ : text;
  }

  /// What the frame view draws for a view-only model (overlay()): polylines as JSON.
  Json viewCurves() {
    const ModelOverlay view = overlay(session_->solved());
    const auto lines = [](const std::vector<std::vector<Vec3>>& polylines) {
      Json out = Json::array();
      for (const std::vector<Vec3>& polyline : polylines) {
        Json line = Json::array();
        for (const Vec3& q : polyline) line.push_back({q.x(), q.y(), q.z()});
        out.push_back(std::move(line));
      }
      return out;
    };
    Json out = {{"curves", lines(view.curves)}, {"spines", lines(view.spines)}};
    // A spectral model's spine points to drag (as `pdesurf spine --count` places them).
    const SpineHandles spine = spineHandles(session_->solved(), kSpineHandles);
    if (!spine.u.empty())
      out["spineHandles"] = {{"u", spine.u}, {"points", lines({spine.points})[0]}};
    return out;
  }

  /// The page's meshes at one resolution: the tessellator that makes them (a drag keeps its
  /// layout, so only positions and normals are rewritten) and the last one sent, the base of
  /// the next delta at this resolution. A gesture's preview and the chosen resolution each
  /// keep a slot, so the release comes back as a delta against the last full-resolution mesh.
  struct MeshSlot {
    std::uint32_t resolution = 0;  // 0: unused
    ModelTessellator tessellator;
    Mesh sent;
    std::uint64_t sentLayout = 0;  // the tessellator's layout of `sent`
    std::uint64_t sentId = 0;      // X-Mesh-Id of `sent`
    std::uint64_t used = 0;        // when it last served (the least recent is reused)
  };

  /// The slot of `resolution`, else the least recently used one, emptied for it.
  MeshSlot& meshSlot(std::uint32_t resolution) {
    MeshSlot* pick = &meshSlots_.front();
    for (MeshSlot& slot : meshSlots_) {
      if (slot.resolution == resolution) {
        pick = &slot;
        break;
      }
      if (slot.used < pick->used) pick = &slot;
    }
    if (pick->resolution != resolution) {
      *pick = MeshSlot{};
      pick->resolution = resolution;
    }
    pick->used = ++meshClock_;
    return *pick;
  }

  /// The surface mesh of whatever model is open, for the page, through the slot's
  /// ModelTessellator.
  const Mesh& meshOf(MeshSlot& slot, const SolveOptions& options, double& solveMs, double& tessMs,
                     double& gap) {
    auto t0 = Clock::now();
    const SolvedModel& solved = session_->solved(options);  // view-only: solved when changed
    solveMs = msSince(t0);
    t0 = Clock::now();
    const Mesh& mesh = slot.tessellator.tessellate(solved, {slot.resolution});
    tessMs = msSince(t0);
    gap = largestC0Gap(solved);
    return mesh;
  }

  /// A mesh for a file (export), leaving the page's tessellation cache alone.
  Mesh exportMesh(std::uint32_t resolution) { return tessellate(session_->solved(), {resolution}); }

  /// The CAD format a path names (.step .stp .iges .igs), if any.
  static std::optional<CadFormat> cadFormatOf(const fs::path& path) {
    try {
      return cadFormatFromPath(path.string());
    } catch (const CadError&) {
      return std::nullopt;
    }
  }

  /// Writes the open model as B-spline faces to a STEP or IGES file, as `pdesurf export`
  /// does with its default tolerance (a face that misses it is written as its finest fit;
  /// the answer counts such faces); what it wrote, for the page.
  Json exportCad(const fs::path& path, CadFormat format) {
    NurbsExportOptions options;
    options.keepBest = true;
    const NurbsModel nurbs = toNurbs(session_->solved(), options);
    CadExportReport report;
    try {
      report = writeCad(nurbs, path.string(), format);
    } catch (const CadError& e) {
      fail(500, e.what());
    }
    return {
        {"path", sandbox_.relative(path)},      {"faces", nurbs.faces.size()},
        {"exactFaces", nurbs.exactCount()},     {"facesOverTolerance", nurbs.overToleranceCount()},
        {"maxDeviation", nurbs.maxDeviation()}, {"shells", report.shells}};
  }

  /// The journal: the current model beside its file after every change. A pending
  /// recovery is never overwritten (recover or discard it first).
  void autosave() {
    if (recovery_) return;
    journal_.write(autosavePath(path_), currentModel());
  }

  void saveTo(const fs::path& path) {
    try {
      // An untransformed view-only model is saved as its file was (save as: a copy).
      // Fields the editor does not hold ("description", ...) are kept from a vertex-frame
      // model's file (keepUnknownFields knows that type's fields; the other types are saved
      // as their files were unless transformed).
      const std::string text =
          session_->frames() ? keepUnknownFields(modelText(), fileText_) : modelText();
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

  /// A binary answer computed for this revision (X-Revision: the page matches it to its mesh).
  void sendBinary(httplib::Response& res, std::string bytes) const {
    res.set_content(std::move(bytes), "application/octet-stream");
    res.set_header("X-Revision", std::to_string(revision() & 0xffffffffu));
  }

  /// The bytes of `count` values at `data`, as they lie in memory.
  template <class T>
  static std::string bytesOf(const T* data, std::size_t count) {
    return {reinterpret_cast<const char*>(data), sizeof(T) * count};
  }

  /// What a mesh request asks for (GET /api/mesh, or an edit with `?mesh=1`).
  struct MeshRequest {
    std::uint32_t resolution = kDefaultMeshResolution;
    std::uint64_t base = 0;  // X-Mesh-Id of the client's mesh at this resolution, 0: none
    SolveOptions options;
  };

  /// Reads a mesh request's parameters (400 naming the bad one), before anything changes.
  MeshRequest meshRequest(const httplib::Request& req) const {
    MeshRequest m;
    if (req.has_param("resolution"))
      m.resolution = parseUint(req.get_param_value("resolution"), kMinResolution,
                               kMaxMeshResolution, "resolution");
    if (req.has_param("base"))
      m.base = parseUint(req.get_param_value("base"), 1, std::numeric_limits<std::uint32_t>::max(),
                         "base");
    m.options = solveOptions(req);
    return m;
  }

  /// Answers with the surface mesh of the open model: whole, or, when `base` is the last
  /// mesh sent at this resolution and only positions and normals changed, a delta against it.
  void sendMesh(const MeshRequest& request, httplib::Response& res) {
    const auto [resolution, base, options] = request;
    double solveMs = 0, tessMs = 0, gap = 0;
    MeshSlot& slot = meshSlot(resolution);
    const Mesh& mesh = meshOf(slot, options, solveMs, tessMs, gap);
    // Same triangles: the tessellator's layout says so (for vertex frames
    // without comparing the index buffers: the drag's hot path).
    const std::uint64_t layout = slot.tessellator.layoutVersion();
    const bool delta = base != 0 && base == slot.sentId && layout == slot.sentLayout;
    res.set_content(delta ? encodeMeshDelta(slot.sent, mesh, revision(), resolution)
                          : encodeMesh(mesh, revision(), resolution),
                    "application/octet-stream");
    slot.sent = mesh;  // what the client now has (copies reuse sent's buffers)
    slot.sentLayout = layout;
    slot.sentId = ++meshCounter_;
    if (delta) res.set_header("X-Mesh-Base", std::to_string(base));
    res.set_header("X-Mesh-Id", std::to_string(slot.sentId));
    res.set_header("X-Solve-Ms", fmt::format("{:.3f}", solveMs));
    res.set_header("X-Tessellate-Ms", fmt::format("{:.3f}", tessMs));
    res.set_header("X-C0-Gap", fmt::format("{}", gap));
  }

  SolveOptions solveOptions(const httplib::Request& req) const {
    SolveOptions o;
    if (req.has_param("solver")) {
      const std::string s = req.get_param_value("solver");
      if (s == "local")
        o.solver = Solver::Local;
      else if (s != "global")
        fail(400, fmt::format("solver: expected \"global\" or \"local\", found \"{}\"", s));
    }
    if (req.has_param("seed") && session_->editable()) {
      const auto frames = static_cast<std::uint32_t>(session_->frames()->frames.size());
      o.seedFrame = parseUint(req.get_param_value("seed"), 0, frames - 1, "seed");
    }
    return o;
  }

  // ------------------------------------------------------------------------------------
  // Routes

  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

  /// Refuses what AccessGuard::refusal refuses (the body is read by now), locks, and turns
  /// HttpError, ModelError and other exceptions into JSON errors.
  Handler guarded(Handler handler) {
    return [this, handler](const httplib::Request& req, httplib::Response& res) {
      try {
        if (const std::optional<HttpError> refused = access_.refusal(req))
          fail(refused->status, refused->message);
        std::lock_guard lock(mutex_);
        handler(req, res);
      } catch (const HttpError& e) {
        sendJson(res, {{"error", e.message}}, e.status);
      } catch (const ModelError& e) {
        sendJson(res, {{"error", e.what()}}, 400);
      } catch (const std::exception& e) {
        sendJson(res, {{"error", e.what()}}, 500);
      }
    };
  }

  /// The front-end: files under the web folder answer GET before any route (so /api/...
  /// is never shadowed: the folder has no api/). Without a built front-end, `/` is the
  /// placeholder page.
  void mountWebDir() {
    std::error_code ec;
    const fs::path web =
        options_.webDir.empty() ? fs::path(defaultWebDir()) : fs::path(options_.webDir);
    if (fs::is_regular_file(web / "index.html", ec) &&
        server_.set_mount_point("/", fs::canonical(web, ec).string())) {
      webDir_ = fs::canonical(web, ec);
      for (const auto& [ext, type] : {std::pair{"html", "text/html; charset=utf-8"},
                                      {"js", "text/javascript"},
                                      {"mjs", "text/javascript"},
                                      {"css", "text/css"},
                                      {"svg", "image/svg+xml"},
                                      {"json", "application/json"},
                                      {"wasm", "application/wasm"},
                                      {"png", "image/png"},
                                      {"ico", "image/x-icon"},
                                      {"map", "application/json"}})
        server_.set_file_extension_and_mimetype_mapping(ext, type);
    }
  }

  void routes() {
    server_.set_payload_max_length(kMaxBody);
    server_.set_read_timeout(10);
    server_.set_write_timeout(10);
    server_.set_error_handler(
        httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
          if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
          std::string message = fmt::format("HTTP status {}", res.status);
          if (res.status == 400) message = "bad request";
          if (res.status == 404) message = "no such route";
          if (res.status == 405) message = "method not allowed";
          if (res.status == 413) message = fmt::format("request body over {} bytes", kMaxBody);
          sendJson(res, {{"error", message}}, res.status);
          return httplib::Server::HandlerResponse::Handled;
        }));
    server_.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
          sendJson(res, {{"error", "internal error"}}, 500);
        });
    // The checks of AccessGuard::refusal run before the page's files and the routes. A request with
    // a body for the API is checked by guarded() instead, once its body is read: answering before
    // would leave the body unread, and the kernel would reset the connection (the answer lost) when
    // it closes. Any other request with a body is an attacker's or a mistake: refused, and the
    // connection closed.
    server_.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      const bool body =
          req.has_header("Transfer-Encoding") ||
          std::strtoull(req.get_header_value("Content-Length").c_str(), nullptr, 10) > 0;
      if (body && req.path.starts_with("/api/")) return httplib::Server::HandlerResponse::Unhandled;
      const std::optional<HttpError> refused = access_.refusal(req);
      if (!refused) return httplib::Server::HandlerResponse::Unhandled;
      sendJson(res, {{"error", refused->message}}, refused->status);
      if (body) res.set_header("Connection", "close");
      return httplib::Server::HandlerResponse::Handled;
    });
    // No other page may frame the studio (clickjacking), sniff its answers as another type,
    // or learn the page's address (and token) from a Referer.
    server_.set_default_headers({{"X-Frame-Options", "DENY"},
                                 {"Content-Security-Policy", "frame-ancestors 'none'"},
                                 {"X-Content-Type-Options", "nosniff"},
                                 {"Referrer-Policy", "no-referrer"}});

    mountWebDir();
    server_.Get("/", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(kIndexPage, "text/html; charset=utf-8");
    });

    server_.Get("/api/model", guarded([this](const httplib::Request&, httplib::Response& res) {
                  Json out = status();
                  out["path"] = sandbox_.relative(path_);
                  out["recovery"] = recovery_;
                  out["editable"] = session_->editable();
                  out["model"] = Json::parse(modelText());
                  if (!session_->editable()) out["view"] = viewCurves();
                  sendJson(res, out);
                }));

    server_.Post(
        "/api/edit", guarded([this](const httplib::Request& req, httplib::Response& res) {
          // Spectral, cross-section and B-spline PDE models take shape edits (session.hpp).
          std::optional<GroupedShapeEdit> shape;
          if (!session_->editable() && takesShapeEdits(session_->model()))
            shape = parseShapeEdit(req.body, session_->model());
          else
            requireEditable();
          const GroupedEdit edit = shape ? GroupedEdit{} : parseEdit(req.body, *session_->frames());
          // `?mesh=1` (and the mesh's parameters): the mesh after the edit, with the
          // status in X-Status: one round trip for a drag step instead of two.
          std::optional<MeshRequest> mesh;
          if (req.has_param("mesh")) {
            if (req.get_param_value("mesh") != "1")
              fail(400, fmt::format("mesh: expected 1, found \"{}\"", req.get_param_value("mesh")));
            mesh = meshRequest(req);
          }
          if (shape)
            session_->apply(shape->edit, shape->group);
          else
            session_->apply(edit.edit, edit.group);
          autosave();
          if (mesh) {
            sendMesh(*mesh, res);
            res.set_header("X-Status", status().dump());
          } else {
            sendJson(res, status());
          }
        }));

    // Moves, turns or scales the whole model, of any type: one undo step.
    server_.Post("/api/transform",
                 guarded([this](const httplib::Request& req, httplib::Response& res) {
                   session_->transform(parseTransform(req.body));
                   autosave();
                   sendJson(res, status());
                 }));

    server_.Post("/api/end-group", guarded([this](const httplib::Request&, httplib::Response& res) {
                   if (!takesShapeEdits(session_->model())) requireEditable();
                   session_->endGroup();
                   sendJson(res, status());
                 }));

    server_.Post("/api/undo", guarded([this](const httplib::Request&, httplib::Response& res) {
                   if (!session_->undo()) fail(409, "nothing to undo");
                   autosave();
                   sendJson(res, status());
                 }));

    server_.Post("/api/redo", guarded([this](const httplib::Request&, httplib::Response& res) {
                   if (!session_->redo()) fail(409, "nothing to redo");
                   autosave();
                   sendJson(res, status());
                 }));

    server_.Get("/api/mesh", guarded([this](const httplib::Request& req, httplib::Response& res) {
                  sendMesh(meshRequest(req), res);
                }));

    // The true boundary curves of every patch (the surface view's frame overlay): float32
    // [patch][side v=0, u=1, v=1, u=0][sample][xyz], `samples` points per side.
    server_.Get(
        "/api/boundaries", guarded([this](const httplib::Request& req, httplib::Response& res) {
          requireEditable();
          std::uint32_t samples = kDefaultMeshResolution + 1;
          if (req.has_param("samples"))
            samples = parseUint(req.get_param_value("samples"), kMinResolution, kMaxMeshResolution,
                                "samples");
          sendBinary(res, boundaryCurves(*session_->solved(solveOptions(req)).frames(), samples));
        }));

    // The patch (frame) of every triangle of the mesh at `resolution` (uint32 each, as
    // GET /api/mesh lays it out for this revision): the page picks frames on the surface.
    server_.Get(
        "/api/patch-ids", guarded([this](const httplib::Request& req, httplib::Response& res) {
          requireEditable();
          const MeshRequest request = meshRequest(req);
          const Mesh mesh = tessellate(session_->solved(request.options), {request.resolution});
          sendBinary(res, bytesOf(mesh.patchIds.data(), mesh.patchIds.size()));
        }));
    // Points of one patch and their parameters (edit_io.hpp: PatchQuery), solved as the
    // query's solver says: the page places force regions on the surface with them.
    const auto patchRoute = [this](bool withPoints) {
      return guarded([this, withPoints](const httplib::Request& req, httplib::Response& res) {
        requireEditable();
        const VertexFrameSurface& surface = *session_->solved(solveOptions(req)).frames();
        const PatchQuery q = parsePatchQuery(req.body, surface.patches.size(), withPoints);
        const VertexFramePatch& patch = surface.patches[q.frame];
        Json out = Json::array();
        for (const Vec3& p : q.points) {
          const auto [u, v] = nearestParameters(patch, p);
          out.push_back({u, v});
        }
        for (const auto& [u, v] : q.uv) {
          const Vec3 p = patch.evaluate(u, v).p;
          out.push_back({p.x(), p.y(), p.z()});
        }
        sendJson(res, {{withPoints ? "uv" : "points", out}});
      });
    };
    server_.Post("/api/patch-uv", patchRoute(true));
    server_.Post("/api/patch-points", patchRoute(false));
    // The analytic mean and Gaussian curvature at every vertex of the mesh GET /api/mesh
    // gives for the same parameters: float32 [vertex][H, K] (analysis.hpp: meshCurvatures).
    server_.Get(
        "/api/curvature", guarded([this](const httplib::Request& req, httplib::Response& res) {
          requireEditable();
          const MeshRequest request = meshRequest(req);
          const VertexFrameSurface& surface = *session_->solved(request.options).frames();
          const Mesh mesh = tessellate(surface, {request.resolution});
          const std::vector<float> values = meshCurvatures(surface, mesh, request.resolution);
          sendBinary(res, bytesOf(values.data(), values.size()));
        }));

    server_.Get("/api/files", guarded([this](const httplib::Request&, httplib::Response& res) {
                  std::vector<std::string> files;
                  std::error_code ec;
                  fs::recursive_directory_iterator it(
                      sandbox_.root(), fs::directory_options::skip_permission_denied, ec);
                  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
                    if (it->path().extension() == ".json" && it->is_regular_file(ec))
                      files.push_back(sandbox_.relative(it->path()));
                  std::sort(files.begin(), files.end());
                  sendJson(res, {{"files", files}});
                }));

    server_.Post("/api/open", guarded([this](const httplib::Request& req, httplib::Response& res) {
                   const std::string requested = stringMember(bodyObject(req), "path");
                   const fs::path path = sandbox_.resolve(requested);
                   std::error_code ec;
                   if (!fs::exists(path, ec)) fail(404, fmt::format("{}: no such file", requested));
                   if (!fs::is_regular_file(path, ec))
                     fail(400, fmt::format("{}: not a file", requested));
                   openModel(path, sandbox_.relative(path));
                   sendJson(res, openedStatus());
                 }));

    server_.Post("/api/save", guarded([this](const httplib::Request&, httplib::Response& res) {
                   saveTo(path_);
                   Json out = status();
                   out["path"] = sandbox_.relative(path_);
                   sendJson(res, out);
                 }));

    server_.Post("/api/save-as",
                 guarded([this](const httplib::Request& req, httplib::Response& res) {
                   const std::string requested = stringMember(bodyObject(req), "path");
                   const fs::path path = modelFilePath(requested);
                   std::error_code ec;
                   if (fs::is_directory(path, ec))
                     fail(400, fmt::format("{}: is a folder", requested));
                   sandbox_.makeParent(path);
                   saveTo(path);
                   Json out = status();
                   out["path"] = sandbox_.relative(path_);
                   sendJson(res, out);
                 }));

    // A new vertex-frame model (newFrameModel) written to a new file and opened.
    server_.Post("/api/new", guarded([this](const httplib::Request& req, httplib::Response& res) {
                   const std::string requested = stringMember(bodyObject(req), "path");
                   const NewModelOptions options = parseNewModel(req.body);
                   const fs::path path = modelFilePath(requested);
                   std::error_code ec;
                   if (fs::exists(path, ec))
                     fail(409, fmt::format("{}: exists already (choose another name)", requested));
                   sandbox_.makeParent(path);
                   try {
                     writeFileAtomically(path.string(),
                                         serializeModel(AnyModel(newFrameModel(options))));
                   } catch (const std::exception& e) {
                     fail(500, e.what());
                   }
                   openModel(path, sandbox_.relative(path));
                   sendJson(res, openedStatus());
                 }));

    server_.Post("/api/export",
                 guarded([this](const httplib::Request& req, httplib::Response& res) {
                   const Json body = bodyObject(req);
                   const std::string requested = stringMember(body, "path");
                   const fs::path path = sandbox_.resolve(requested);
                   const std::optional<CadFormat> cad = cadFormatOf(path);
                   try {
                     if (!cad) meshFormatFromPath(path.string());
                   } catch (const MeshIoError&) {
                     fail(400, fmt::format("{}: unknown format (known: .obj .ply .stl .glb .off "
                                           ".step .stp .iges .igs)",
                                           requested));
                   }
                   std::uint32_t resolution = kDefaultExportResolution;
                   if (auto it = body.find("resolution"); it != body.end()) {
                     if (!it->is_number_unsigned() || it->get<std::uint64_t>() < kMinResolution ||
                         it->get<std::uint64_t>() > kMaxExportResolution)
                       fail(400, fmt::format("$.resolution: expected a whole number from {} to {}",
                                             kMinResolution, kMaxExportResolution));
                     resolution = it->get<std::uint32_t>();
                   }
                   std::error_code ec;
                   if (fs::is_directory(path, ec))
                     fail(400, fmt::format("{}: is a folder", requested));
                   sandbox_.makeParent(path);
                   if (cad) return sendJson(res, exportCad(path, *cad));
                   const Mesh mesh = exportMesh(resolution);
                   try {
                     writeMesh(mesh, path.string());
                   } catch (const MeshIoError& e) {
                     fail(500, e.what());
                   }
                   sendJson(res, {{"path", sandbox_.relative(path)},
                                  {"vertices", mesh.vertexCount()},
                                  {"triangles", mesh.triangleCount()}});
                 }));

    server_.Post("/api/recover", guarded([this](const httplib::Request&, httplib::Response& res) {
                   if (!recovery_) fail(409, "no autosave to recover");
                   const fs::path journal = autosavePath(path_);
                   replaceSession(parseModel(readFile(journal), sandbox_.relative(journal)),
                                  sandbox_.relative(journal));
                   recovery_ = false;  // the journal now matches the session
                   sendJson(res, status());
                 }));

    server_.Post("/api/discard-recovery",
                 guarded([this](const httplib::Request&, httplib::Response& res) {
                   if (!recovery_) fail(409, "no autosave to discard");
                   std::error_code ec;
                   fs::remove(autosavePath(path_), ec);
                   if (ec) fail(500, fmt::format("cannot remove the autosave: {}", ec.message()));
                   recovery_ = false;
                   sendJson(res, status());
                 }));
  }

  /// The four sides of each patch of `surface` (its parameter square's edges, in the
  /// order v = 0, u = 1, v = 1, u = 0), `samples` points each, as little-endian float32.
  static std::string boundaryCurves(const VertexFrameSurface& surface, std::uint32_t samples) {
    std::vector<float> out;
    out.reserve(std::size_t{12} * samples * surface.patches.size());
    for (const VertexFramePatch& patch : surface.patches)
      for (int side = 0; side < 4; ++side)
        for (std::uint32_t i = 0; i < samples; ++i) {
          const double t = static_cast<double>(i) / (samples - 1);
          const double u = side == 0 ? t : side == 1 ? 1.0 : side == 2 ? 1.0 - t : 0.0;
          const double v = side == 0 ? 0.0 : side == 1 ? t : side == 2 ? 1.0 : 1.0 - t;
          const Vec3 p = patch.position(u, v);
          for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(p[c]));
        }
    return std::string(reinterpret_cast<const char*>(out.data()), 4 * out.size());
  }

  StudioOptions options_;
  AccessGuard access_;   // the token, and the Host and Origin values naming this server
  RootSandbox sandbox_;  // every path of a request resolves inside its root
  fs::path webDir_;
  httplib::Server server_;
  std::thread thread_;
  int port_ = -1;

  mutable std::mutex mutex_;
  fs::path path_;
  std::unique_ptr<ModelSession> session_;
  std::uint64_t base_ = 0;
  std::uint64_t savedRevision_ = 0;
  bool recovery_ = false;
  // The page's meshes (GET /api/mesh), one slot per resolution it last asked for; mesh ids
  // are never reused while the server runs, so a client's `base` names exactly one mesh,
  // across resolutions and opened models too.
  std::array<MeshSlot, kMeshSlots> meshSlots_;
  std::uint64_t meshClock_ = 0;
  std::string fileText_;     ///< the model's file as read or saved last
  std::string fileModel_;    ///< serializeModel of that file's model
  std::string openedText_;   ///< the model's file as opened
  std::string openedModel_;  ///< serializeModel of the model as opened
  bool opened_ = false;
  Journal journal_;
  std::uint64_t meshCounter_ = 0;
};

StudioServer::StudioServer(const std::string& modelPath, StudioOptions options)
    : impl_(std::make_unique<Impl>(modelPath, std::move(options))) {}
StudioServer::~StudioServer() = default;
int StudioServer::start() { return impl_->start(); }
void StudioServer::stop() { impl_->stop(); }
int StudioServer::port() const { return impl_->port(); }
std::string StudioServer::url() const { return impl_->url(); }
std::string StudioServer::token() const { return impl_->token(); }
std::string StudioServer::root() const { return impl_->root(); }
std::string StudioServer::modelPath() const { return impl_->modelPath(); }
std::string StudioServer::webDir() const { return impl_->webDir(); }
void StudioServer::flushJournal() { impl_->flushJournal(); }

int runStudio(const std::string& modelPath, const StudioOptions& options) {
  // SIGINT and SIGTERM are taken by sigwait below: blocked before any server thread
  // starts, so every thread inherits the mask and none is interrupted.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::optional<StudioServer> server;
  try {
    server.emplace(modelPath, options);
    server->start();
  } catch (const ModelError& e) {
    std::fprintf(stderr, "pdesurf: %s\n", e.what());
    return 1;
  } catch (const StudioError& e) {
    std::fprintf(stderr, "pdesurf: %s\n", e.what());
    return 1;
  }
  if (!options.requireToken)
    std::fprintf(stderr,
                 "pdesurf studio: --no-token: UNSAFE, for tests only: every program of every "
                 "user of this machine may read and change the models\n");
  std::printf("pdesurf studio: %s (model: %s, root: %s)\n", server->url().c_str(),
              server->modelPath().c_str(), server->root().c_str());
  std::fflush(stdout);
  int received = 0;
  while (sigwait(&signals, &received) != 0) {
  }
  server->stop();
  return 0;
}

}  // namespace pdesurf::studio
