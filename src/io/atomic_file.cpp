// Whole-or-nothing file writes (include/pdesurf/atomic_file.hpp, src/io/atomic_file.hpp).
#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <random>
#include <system_error>
#include <utility>

namespace pdesurf {
namespace detail {
namespace {

std::string errnoText(int error) { return std::generic_category().message(error); }

/// The hidden temporary file beside `path`: "DIR/.NAME.tmp-" (the caller adds a suffix).
std::string temporaryPrefix(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  const std::size_t nameStart = slash == std::string::npos ? 0 : slash + 1;
  return path.substr(0, nameStart) + "." + path.substr(nameStart) + ".tmp-";
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  // Like mkstemp, but through open(2) with mode 0666 so that the umask applies as it does to
  // any new file (mkstemp's files are private, 0600); commit() gives a replaced file's mode.
  static constexpr std::string_view kAlphabet =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  const std::string prefix = temporaryPrefix(path_);
  std::random_device random;
  for (int attempt = 0;; ++attempt) {
    std::string suffix(6, 'x');
    for (char& c : suffix) c = kAlphabet[random() % kAlphabet.size()];
    tempPath_ = prefix + suffix;
    fd_ = ::open(tempPath_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ >= 0) break;
    const int error = errno;
    if (error != EEXIST || attempt == 100)
      throw FileError(path_, fmt::format("cannot create the temporary file {}: {}", tempPath_,
                                         errnoText(error)));
  }
  buffer_.reserve(kChunk + kChunk / 4);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(tempPath_.c_str());
}

void AtomicFileWriter::commit() {
  flush();
  // A file being replaced keeps its permissions (a model the user made read-only for others
  // stays so); a new file keeps the 0666-minus-umask it was created with.
  struct stat existing {};
  if (::stat(path_.c_str(), &existing) == 0 && S_ISREG(existing.st_mode) &&
      ::fchmod(fd_, existing.st_mode & 07777) != 0)
    failErrno("cannot set the permissions");
  if (::fsync(fd_) != 0) failErrno("cannot write");
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) failErrno("cannot write");
  if (std::rename(tempPath_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    throw FileError(path_, fmt::format("cannot rename {} to it: {}", tempPath_, errnoText(error)));
  }
  committed_ = true;
}

void AtomicFileWriter::flush() {
  const char* data = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      failErrno("cannot write");
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  buffer_.clear();
}

void AtomicFileWriter::failErrno(std::string_view what) const {
  const int error = errno;
  throw FileError(path_, fmt::format("{}: {}", what, errnoText(error)));
}

}  // namespace detail

void writeFileAtomically(const std::string& path, std::string_view data) {
  detail::AtomicFileWriter file(path);
  file.append(data.data(), data.size());
  file.commit();
}

}  // namespace pdesurf
