// The studio server (server.hpp): the HTTP server's lifetime, limits, error answers and the
// access checks before routing. The routes are in routes_*.cpp (routes.hpp), the open model
// file in document.cpp, the page's meshes in mesh_slots.cpp.
#include "server.hpp"

#include <pthread.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "access_guard.hpp"
#include "document.hpp"
#include "mesh_slots.hpp"
#include "root_sandbox.hpp"
#include "routes.hpp"

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxBody = 1 << 20;

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
    document_.open(model, modelPath);
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
  void flushJournal() { document_.flushJournal(); }
  std::string url() const {
    return fmt::format("http://{}:{}/{}", urlHost(options_.host), port_,
                       access_.token().empty() ? "" : "?token=" + access_.token());
  }
  const std::string& token() const { return access_.token(); }
  std::string root() const { return sandbox_.root().string(); }
  std::string webDir() const { return webDir_.string(); }
  std::string modelPath() const {
    std::lock_guard lock(mutex_);
    return document_.path().string();
  }

 private:
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

  /// The server's limits, error answers and headers, the access checks before routing, the
  /// page's files, and the routes (routes.hpp).
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

    addModelRoutes(studio_);
    addSurfaceRoutes(studio_);
    addFileRoutes(studio_);
  }

  StudioOptions options_;
  AccessGuard access_;   // the token, and the Host and Origin values naming this server
  RootSandbox sandbox_;  // every path of a request resolves inside its root
  fs::path webDir_;
  httplib::Server server_;
  std::thread thread_;
  int port_ = -1;

  mutable std::mutex mutex_;  // held by every route (Studio::guarded)
  Document document_{sandbox_};
  MeshSlots meshes_;
  const Studio studio_{server_, document_, meshes_, sandbox_, access_, mutex_};
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
  } catch (const Error& e) {
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
