// The buffered writer behind writeFileAtomically (include/pdesurf/atomic_file.hpp), for
// writers that produce a file piece by piece (the mesh formats).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "pdesurf/atomic_file.hpp"

namespace pdesurf::detail {

/// Buffers a file's bytes and hands them to a temporary file beside the target in chunks;
/// commit() syncs it and renames it over the target, with the permission rule of
/// writeFileAtomically. Destroyed without commit(), it removes the temporary file.
/// Every failure throws FileError naming the target.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::string path);
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  ~AtomicFileWriter();

  /// Where fmt::format_to appends text; call checkpoint() after each record.
  fmt::appender out() { return fmt::appender(buffer_); }

  /// Appends raw bytes (call checkpoint() after each record).
  void append(const void* data, std::size_t size) {
    const char* begin = static_cast<const char*>(data);
    buffer_.append(begin, begin + size);
  }

  /// Hands the buffer to the file once it holds a chunk.
  void checkpoint() {
    if (buffer_.size() >= kChunk) flush();
  }

  /// Writes what is left, makes it durable and renames the temporary file over the target.
  void commit();

  const std::string& path() const { return path_; }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;

  void flush();
  [[noreturn]] void failErrno(std::string_view what) const;

  std::string path_;
  std::string tempPath_;
  int fd_ = -1;
  bool committed_ = false;
  fmt::memory_buffer buffer_;
};

}  // namespace pdesurf::detail
