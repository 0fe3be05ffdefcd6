// Every script under scripts/ and bench/ answers --help with its usage and exit status 0,
// and does nothing else: no file appears in the directory it runs in (bench/studio's
// make_model.py used to write a model named "--help"). A new script is tested for free.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

namespace fs = std::filesystem;
using testing::readText;
using testing::shellQuote;
using testing::TempDir;

/// The scripts: executable files, and Python or Node files run through their interpreter.
/// scripts/format_check.cmake is not one (it is run by `cmake -P` from ctest).
std::vector<std::string> scripts() {
  std::vector<std::string> found;
  for (const char* folder : {"scripts", "bench"})
    for (const auto& entry :
         fs::recursive_directory_iterator(fs::path(PDESURF_SOURCE_DIR) / folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      const bool executable =
          (entry.status().permissions() & fs::perms::owner_exec) != fs::perms::none;
      if (executable || ext == ".py" || ext == ".mjs")
        found.push_back(fs::relative(entry.path(), PDESURF_SOURCE_DIR).string());
    }
  std::sort(found.begin(), found.end());
  return found;
}

/// The command that runs `script` (relative to the source folder) with `args`.
std::string commandFor(const std::string& script, const std::string& args) {
  const std::string path = shellQuote((fs::path(PDESURF_SOURCE_DIR) / script).string());
  const std::string ext = fs::path(script).extension().string();
  const std::string runner = ext == ".py" ? "python3 " : ext == ".mjs" ? "node " : "";
  return runner + path + " " + args;
}

std::string lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

TEST(Scripts, TheListFindsTheKnownOnes) {
  const std::vector<std::string> found = scripts();
  for (const char* known : {"scripts/setup", "scripts/check_docs", "scripts/make_examples.py",
                            "bench/studio/make_model.py", "bench/studio/latency.mjs"})
    EXPECT_NE(std::find(found.begin(), found.end(), known), found.end()) << known;
}

class ScriptHelp : public ::testing::TestWithParam<std::string> {};

TEST_P(ScriptHelp, PrintsItsUsageAndExitsZeroWithoutSideEffects) {
  const std::string& script = GetParam();
  if (fs::path(script).extension() == ".mjs" && std::system("command -v node >/dev/null") != 0)
    GTEST_SKIP() << "no node";
  TempDir work, capture;
  for (const char* flag : {"--help", "-h"}) {
    const std::string out = capture.file("stdout"), err = capture.file("stderr");
    const std::string command = "cd " + shellQuote(work.file("")) + " && " +
                                commandFor(script, flag) + " >" + shellQuote(out) + " 2>" +
                                shellQuote(err) + " </dev/null";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << script << " " << flag << ": " << readText(err);
    EXPECT_NE(lowercase(readText(out)).find("usage"), std::string::npos)
        << script << " " << flag << " printed: " << readText(out);
    EXPECT_TRUE(work.entries().empty()) << script << " " << flag << " left files behind";
  }
}

INSTANTIATE_TEST_SUITE_P(Scripts, ScriptHelp, ::testing::ValuesIn(scripts()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

}  // namespace
}  // namespace pdesurf
