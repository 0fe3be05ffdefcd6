// The studio server: a thin HTTP layer (cpp-httplib) over pdesurf::ModelSession. It serves
// one model at a time from a root folder, applies edits, undo and redo, streams meshes,
// saves atomically and keeps an autosave journal beside the model (`MODEL.autosave`).
// The JSON API is listed in apps/studio/README.md, and what each request must carry (its
// Host, Origin, Content-Type and the per-launch token) under "Security" there.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace pdesurf::studio {

struct StudioOptions {
  /// The folder every path of a request must resolve inside; empty: the model's folder.
  std::string root;
  std::string host = "127.0.0.1";
  /// 0 picks a free port.
  int port = 8080;
  /// The built web front-end (index.html and assets/), served at `/`. Empty: the
  /// environment variable PDESURF_WEB_DIR, else the source tree's web/dist compiled in.
  /// When the folder has no index.html, `/` is a placeholder page.
  std::string webDir;
  /// API requests must carry the per-launch token (header X-Pdesurf-Token). false
  /// (`--no-token`) is for tests only and unsafe: every local program, of any user, may then
  /// read and change the models (the Host, Origin and Content-Type checks stay on).
  bool requireToken = true;
};

/// The header that carries the per-launch token.
inline constexpr const char* kTokenHeader = "X-Pdesurf-Token";

/// The folder the front-end is served from when StudioOptions::webDir is empty.
std::string defaultWebDir();

/// The studio cannot start: a root that is not a folder, a model outside the root, a port
/// that cannot be bound. (An invalid model throws ModelError.)
class StudioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StudioServer {
 public:
  /// Loads the model (throws ModelError when it is missing or invalid, StudioError when it
  /// lies outside the root). Nothing listens until start().
  StudioServer(const std::string& modelPath, StudioOptions options = {});
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  /// Binds options.host:options.port and serves on a background thread; returns the port.
  /// Throws StudioError when the port cannot be bound.
  int start();
  /// Stops serving and joins the thread (also done by the destructor).
  void stop();

  int port() const;
  /// The page's address with the token: "http://HOST:PORT/?token=TOKEN" ("[HOST]" for an
  /// IPv6 address; without "?token=" when no token is required).
  std::string url() const;
  /// The per-launch token: 48 hex digits (192 bits from getrandom(2)) drawn when the server
  /// is made, or empty when options.requireToken is false.
  std::string token() const;
  /// The canonical root folder and the current model's file (absolute).
  std::string root() const;
  std::string modelPath() const;
  /// The folder of the front-end served at `/`, or empty when it is not built.
  std::string webDir() const;
  /// Waits until the autosave journal holds every accepted change (it is written on its
  /// own thread, so edits never wait for the disk; the destructor waits too).
  void flushJournal();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// `pdesurf studio`: starts the server, prints
/// "pdesurf studio: http://HOST:PORT/?token=TOKEN (model: PATH, root: DIR)" and serves until SIGINT
/// or SIGTERM. Returns the exit status: 0 after a signal, 1 when the model is missing or invalid or
/// the server cannot start (the message goes to stderr).
int runStudio(const std::string& modelPath, const StudioOptions& options);

}  // namespace pdesurf::studio
