// The project's one atomic-file writer (include/pdesurf/atomic_file.hpp): whole or nothing,
// and one permission rule (a replaced file keeps its mode, a new one gets 0666 minus the
// umask), whoever writes (meshes, models, autosaves, slices, STEP and IGES).
#include "pdesurf/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>
#include <vector>

#include "pdesurf/mesh_io.hpp"
#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

using testing::readText;
using testing::TempDir;

/// The permission bits of `path`.
mode_t modeOf(const std::string& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return info.st_mode & 07777;
}

/// Sets the umask for the scope, restoring the old one at its end.
class ScopedUmask {
 public:
  explicit ScopedUmask(mode_t mask) : saved_(::umask(mask)) {}
  ~ScopedUmask() { ::umask(saved_); }

 private:
  mode_t saved_;
};

Mesh oneTriangle() {
  Mesh mesh;
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  mesh.indices = {0, 1, 2};
  return mesh;
}

TEST(AtomicFile, WritesTheBytesAndLeavesNoTemporaryFile) {
  TempDir dir;
  writeFileAtomically(dir.file("a.json"), "first");
  writeFileAtomically(dir.file("a.json"), std::string("second\0binary", 13));
  EXPECT_EQ(readText(dir.file("a.json")), std::string("second\0binary", 13));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.json"});
}

TEST(AtomicFile, ANewFileGetsTheModeTheUmaskLeaves) {
  TempDir dir;
  for (const mode_t mask : {mode_t{022}, mode_t{077}, mode_t{002}}) {
    ScopedUmask scoped(mask);
    const std::string text = dir.file("text-" + std::to_string(mask));
    const std::string mesh = dir.file("mesh-" + std::to_string(mask) + ".obj");
    writeFileAtomically(text, "x");
    writeMesh(oneTriangle(), mesh);
    EXPECT_EQ(modeOf(text), 0666 & ~mask) << "umask " << mask;
    EXPECT_EQ(modeOf(mesh), 0666 & ~mask) << "umask " << mask;
  }
}

TEST(AtomicFile, AReplacedFileKeepsItsMode) {
  TempDir dir;
  ScopedUmask scoped(022);
  for (const mode_t mode : {mode_t{0600}, mode_t{0640}, mode_t{0444}, mode_t{0664}}) {
    const std::string text = dir.file("model.json"), mesh = dir.file("mesh.ply");
    writeFileAtomically(text, "old");
    writeMesh(oneTriangle(), mesh);
    ASSERT_EQ(::chmod(text.c_str(), mode), 0);
    ASSERT_EQ(::chmod(mesh.c_str(), mode), 0);
    writeFileAtomically(text, "new");
    writeMesh(oneTriangle(), mesh);
    EXPECT_EQ(readText(text), "new");
    EXPECT_EQ(modeOf(text), mode);
    EXPECT_EQ(modeOf(mesh), mode);
    ASSERT_EQ(::chmod(text.c_str(), 0644), 0);  // so that the next round may start afresh
    ASSERT_EQ(::chmod(mesh.c_str(), 0644), 0);
  }
}

TEST(AtomicFile, FailuresNameThePathAndLeaveNothing) {
  TempDir dir;
  const std::string missing = dir.file("missing/model.json");
  try {
    writeFileAtomically(missing, "x");
    ADD_FAILURE() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos)
        << e.what();
  }
  ASSERT_EQ(::mkdir(dir.file("taken").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir(dir.file("taken/inside").c_str(), 0755), 0);
  EXPECT_THROW(writeFileAtomically(dir.file("taken"), "x"), FileError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken"});
}

}  // namespace
}  // namespace pdesurf
