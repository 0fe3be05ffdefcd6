// The studio's autosave journal (journal.hpp).
#include "journal.hpp"

#include <cstdio>
#include <exception>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf::studio {

std::filesystem::path autosavePath(const std::filesystem::path& model) {
  return std::filesystem::path(model.string() + ".autosave");
}

Journal::Journal() : thread_([this] { run(); }) {}

Journal::~Journal() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();  // run() writes what is pending before it returns
}

void Journal::write(std::filesystem::path path, AnyModel model) {
  {
    std::lock_guard lock(mutex_);
    pending_.emplace(Job{std::move(path), std::move(model)});
  }
  wake_.notify_all();
}

void Journal::cancel() {
  std::unique_lock lock(mutex_);
  pending_.reset();
  idle_.wait(lock, [this] { return !busy_; });
}

void Journal::flush() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !busy_ && !pending_; });
}

void Journal::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || pending_; });
    if (!pending_) return;  // stopping, nothing left to write
    Job job = std::move(*pending_);
    pending_.reset();
    busy_ = true;
    lock.unlock();
    try {
      writeFileAtomically(job.path.string(), serializeModel(job.model));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pdesurf studio: autosave: %s\n", e.what());
    }
    lock.lock();
    busy_ = false;
    idle_.notify_all();
  }
}

}  // namespace pdesurf::studio
