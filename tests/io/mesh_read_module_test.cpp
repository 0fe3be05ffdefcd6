// readMesh reads OFF and STL through the CGAL module, which registers its readers when the
// program links it (src/io/mesh_read.hpp); a program of the core alone gets an error naming
// the module and the file, and no reader runs. Built in both configurations: the full build
// (PDESURF_TEST_CGAL=1) and the core-only one (scripts/check_core_only, PDESURF_TEST_CGAL=0).
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "pdesurf/mesh_io.hpp"

#ifndef PDESURF_TEST_CGAL
#error "tests/CMakeLists.txt defines PDESURF_TEST_CGAL for this file"
#endif

namespace pdesurf {
namespace {

namespace fs = std::filesystem;

/// A folder of its own under the system's temporary one, removed at the end.
class Folder {
 public:
  Folder() : path_(fs::temp_directory_path() / ("pdesurf-module-" + std::to_string(getpid()))) {
    fs::create_directories(path_);
  }
  ~Folder() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

/// One triangle, as OFF text and as pdesurf's own STL.
void writeTriangleFiles(const Folder& folder) {
  std::ofstream(folder.file("t.off")) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  Mesh mesh;
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  mesh.indices = {0, 1, 2};
  writeMesh(mesh, folder.file("t.stl"));
}

TEST(MeshReadModule, OffAndStlAreReadExactlyWhereTheCgalModuleIsLinked) {
  const Folder folder;
  writeTriangleFiles(folder);
  for (const std::string name : {"t.off", "t.stl"}) {
    const std::string path = folder.file(name);
    if (PDESURF_TEST_CGAL) {
      const Mesh mesh = readMesh(path);
      EXPECT_EQ(mesh.vertexCount(), 3u) << name;
      EXPECT_EQ(mesh.triangleCount(), 1u) << name;
    } else {
      try {
        readMesh(path);
        ADD_FAILURE() << name << " was read without the CGAL module";
      } catch (const MeshIoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("needs pdesurf's CGAL module (pdesurf::cgal)"), std::string::npos)
            << message;
      }
    }
  }
}

}  // namespace
}  // namespace pdesurf
