// The studio's autosave journal (`MODEL.autosave` beside the model), written off the request
// path.
#pragma once

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "pdesurf/model.hpp"

namespace pdesurf::studio {

/// Writes the autosave journal on its own thread, so an edit's answer never waits for the
/// serialisation and the disk. Only the latest model matters: a snapshot still pending when
/// a newer one arrives is replaced. Writes are atomic (temporary file, then rename).
class Journal {
 public:
  Journal();
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Writes `model` to `path` soon, in place of any write still pending.
  void write(std::filesystem::path path, AnyModel model);

  /// Drops a pending write and waits for one in progress: afterwards no journal file is
  /// written until the next write() (call before removing or reading a journal).
  void cancel();

  /// Waits until every write asked for is on disk.
  void flush();

 private:
  struct Job {
    std::filesystem::path path;
    AnyModel model;
  };

  void run();

  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::optional<Job> pending_;
  bool busy_ = false;
  bool stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

/// The journal of a model file: `MODEL.autosave` beside it.
std::filesystem::path autosavePath(const std::filesystem::path& model);

}  // namespace pdesurf::studio
