// The studio's root folder: every path a request names must resolve inside it
// (apps/studio/README.md, "Security").
#pragma once

#include <filesystem>
#include <string>

namespace pdesurf::studio {

class RootSandbox {
 public:
  RootSandbox() = default;
  /// `root`: a canonical folder.
  explicit RootSandbox(std::filesystem::path root) : root_(std::move(root)) {}

  const std::filesystem::path& root() const { return root_; }
  /// Whether a canonical path lies in the root (or is the root).
  bool inside(const std::filesystem::path& canonical) const;
  /// A path from a request, resolved against the root: HttpError 400 for an empty path or a
  /// NUL character, 403 when it leaves the root (through "..", a symbolic link or an
  /// absolute path) or is the root itself.
  std::filesystem::path resolve(const std::string& requested) const;
  /// A path inside the root as the API writes it: relative, with '/'.
  std::string relative(const std::filesystem::path& p) const;
  /// Makes the parent folder of a path inside the root (HttpError 500 when it cannot).
  void makeParent(const std::filesystem::path& p) const;

 private:
  std::filesystem::path root_;
};

}  // namespace pdesurf::studio
