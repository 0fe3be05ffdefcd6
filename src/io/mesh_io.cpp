// Mesh files read: the format chosen by the extension, the file read whole, the reader of
// its format (OBJ and PLY: mesh_read_obj.cpp, mesh_read_ply.cpp; OFF and STL through CGAL:
// mesh_read_cgal.cpp; glb through tinygltf: mesh_read_glb.cpp), then the same checks for
// all. OBJ and PLY keep their own readers, because the libraries Debian 12 offers lose data
// or valid files with them:
// - CGAL 5.5's polygon-soup readers drop the normals of both (files pdesurf writes carry
//   them, and round trips keep them);
// - its PLY reader crashes on integer coordinates ("property int x": a null dynamic_cast in
//   PLY_element::assign) and refuses face lists of indices other than 32-bit integers
//   (tests/io/mesh_io_test.cpp, PlyWithIntegerCoordinatesAndShortIndexLists);
// - its OBJ reader refuses files without faces, skips malformed corners ("2/x") without a
//   word and names no line;
// - tinyobjloader (libtinyobjloader-dev) reads a malformed number as 0 ("v 1 abc 3" is
//   (1, 0, 3)) and a missing one too, where this reader names the line.
#include "pdesurf/mesh_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "io/mesh_read.hpp"
#include "io/mesh_text.hpp"

namespace pdesurf {
namespace {

using detail::errnoText;
using detail::fail;
using detail::lowercase;

std::string readFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    fail(path, "cannot open: {}", errnoText(error));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  std::string data;
  if (::fstat(fd, &info) == 0 && info.st_size > 0)
    data.resize(static_cast<std::size_t>(info.st_size) + 1);
  std::size_t used = 0;
  for (;;) {
    if (used == data.size()) data.resize(std::max<std::size_t>(2 * data.size(), 1 << 16));
    const ssize_t got = ::read(fd, data.data() + used, data.size() - used);
    if (got < 0) {
      const int error = errno;
      if (error == EINTR) continue;
      fail(path, "cannot read: {}", errnoText(error));
    }
    if (got == 0) break;
    used += static_cast<std::size_t>(got);
  }
  data.resize(used);
  return data;
}

/// Throws unless every index names a vertex, every position is finite and the vertices fit
/// 32-bit indices: what every reader's result must hold, checked once for all of them.
/// Normals that are not all finite are dropped (a mesh is usable without them).
void checkReadMesh(Mesh& mesh, const std::string& path) {
  const std::size_t vertexCount = mesh.vertexCount();
  if (vertexCount > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} vertices do not fit 32-bit indices", vertexCount);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      fail(path,
           "vertex {} has a non-finite coordinate ({}): coordinates must fit single precision",
           i / 3, mesh.positions[i]);
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= vertexCount)
      fail(path, "triangle {} refers to vertex {} but the file has {} vertices", i / 3,
           mesh.indices[i], vertexCount);
  if (!std::all_of(mesh.normals.begin(), mesh.normals.end(),
                   [](float n) { return std::isfinite(n); }))
    mesh.normals.clear();
}

}  // namespace

MeshFormat meshFormatFromPath(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  const std::size_t dot = path.rfind('.');
  const std::string extension =
      dot == std::string::npos || (slash != std::string::npos && dot < slash) ? ""
                                                                              : path.substr(dot);
  const std::string lower = lowercase(extension);
  if (lower == ".obj") return MeshFormat::Obj;
  if (lower == ".ply") return MeshFormat::Ply;
  if (lower == ".stl") return MeshFormat::Stl;
  if (lower == ".glb") return MeshFormat::Glb;
  if (lower == ".off") return MeshFormat::Off;
  fail(path, "unknown mesh format '{}' (use .obj, .ply, .stl, .glb or .off)", extension);
}

namespace detail {

CgalMeshReaders& cgalMeshReaders() {
  static CgalMeshReaders readers;
  return readers;
}

}  // namespace detail

Mesh readMesh(const std::string& path) {
  const MeshFormat format = meshFormatFromPath(path);
  const detail::CgalMeshReaders& cgal = detail::cgalMeshReaders();
  const detail::MeshReader readers[] = {detail::readObj, detail::readPly, cgal.stl, detail::readGlb,
                                        cgal.off};  // MeshFormat's order
  static_assert(std::size(readers) == static_cast<std::size_t>(MeshFormat::Off) + 1);
  const detail::MeshReader reader = readers[static_cast<std::size_t>(format)];
  if (reader == nullptr) {
    fail(path,
         "reading {} files needs pdesurf's CGAL module (pdesurf::cgal), which this "
         "program does not link",
         format == MeshFormat::Off ? "OFF" : "STL");
  }
  const std::string data = readFile(path);
  Mesh mesh = reader(data, path);
  checkReadMesh(mesh, path);
  return mesh;
}

}  // namespace pdesurf
