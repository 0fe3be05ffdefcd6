// The studio's root folder (root_sandbox.hpp).
#include "root_sandbox.hpp"

#include <algorithm>
#include <system_error>

#include <fmt/format.h>

#include "http_error.hpp"

namespace pdesurf::studio {

namespace fs = std::filesystem;

bool RootSandbox::inside(const fs::path& canonical) const {
  auto [r, c] = std::mismatch(root_.begin(), root_.end(), canonical.begin(), canonical.end());
  return r == root_.end();
}

fs::path RootSandbox::resolve(const std::string& requested) const {
  if (requested.empty()) fail(400, "$.path: empty path");
  if (requested.find('\0') != std::string::npos) fail(400, "$.path: contains a NUL character");
  fs::path p(requested);
  if (p.is_relative()) p = root_ / p;
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(p, ec);
  if (ec) fail(400, fmt::format("{}: {}", requested, ec.message()));
  if (!inside(canonical) || canonical == root_)
    fail(403, fmt::format("{}: outside the root folder", requested));
  return canonical;
}

std::string RootSandbox::relative(const fs::path& p) const {
  return p.lexically_relative(root_).generic_string();
}

void RootSandbox::makeParent(const fs::path& p) const {
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  if (ec) fail(500, fmt::format("{}: cannot create the folder: {}", relative(p), ec.message()));
}

}  // namespace pdesurf::studio
