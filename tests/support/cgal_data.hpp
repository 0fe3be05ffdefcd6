// CGAL's sample meshes (Debian's libcgal-demo, which scripts/setup installs) for tests,
// extracted by scripts/cgal_data into the build directory. A missing package fails the
// test that needs it, loudly: it is never skipped.
#pragma once

#include <stdio.h>
#include <sys/wait.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace pdesurf::testing {

/// The path of CGAL's data file `name` (e.g. "elephant.off"). Throws std::runtime_error
/// with scripts/cgal_data's message when libcgal-demo or the file is missing.
inline std::string cgalData(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(PDESURF_CLI).parent_path() / "cgal-data";
  auto quote = [](const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  };
  const std::string command = quote(std::string(PDESURF_SOURCE_DIR) + "/scripts/cgal_data") + " " +
                              quote(name) + " " + quote(dir.string()) + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  std::string output;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    output.append(buffer, n);
  const int status = ::pclose(pipe);
  while (!output.empty() && output.back() == '\n') output.pop_back();
  if (status != 0 || !std::filesystem::is_regular_file(output))
    throw std::runtime_error("CGAL data file " + name + " is missing: " + output +
                             " (scripts/setup installs libcgal-demo)");
  return output;
}

}  // namespace pdesurf::testing
