// OFF and STL files read through CGAL's readers (CGAL::IO::read_OFF and read_STL, the
// readers CGAL::IO::read_polygon_soup picks for these extensions). Built with the other CGAL
// sources (CMakeLists.txt: CGAL's interface adds -frounding-math).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <CGAL/IO/OFF.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include "io/mesh_read.hpp"

namespace pdesurf::detail {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Polygon = std::vector<std::size_t>;

/// The 1-based number of the line holding byte `offset` of `data`.
std::size_t lineNumber(std::string_view data, std::size_t offset) {
  return 1 + static_cast<std::size_t>(
                 std::count(data.begin(), data.begin() + std::min(offset, data.size()), '\n'));
}

/// Where a reader stopped in `data`: the offset its stream's buffer reached.
std::size_t stopOffset(std::istream& is, std::string_view data) {
  is.clear();  // the buffer's position is what is wanted, whatever the stream's state
  const auto offset =
      static_cast<std::streamoff>(is.rdbuf()->pubseekoff(0, std::ios::cur, std::ios::in));
  return offset < 0 ? data.size()
                    : std::min<std::size_t>(static_cast<std::size_t>(offset), data.size());
}

/// A line of an ASCII format: its number and its text without a '#' comment and end blanks.
struct Line {
  std::size_t number = 0;
  std::string_view text;
};

/// The lines of `data` from `begin` to `end` that hold anything but blanks and comments,
/// which is what CGAL's line-based OFF reader reads a vertex or a face from.
std::vector<Line> dataLines(std::string_view data, std::size_t begin, std::size_t end) {
  std::vector<Line> lines;
  std::size_t number = lineNumber(data, begin);
  for (std::size_t at = begin; at < end; ++number) {
    const std::size_t newline = std::min(data.find('\n', at), data.size());
    std::string_view text = data.substr(at, newline - at);
    text = text.substr(0, text.find('#'));
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
      text.remove_suffix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
      text.remove_prefix(1);
    if (!text.empty()) lines.push_back({number, text});
    at = newline + 1;
  }
  return lines;
}

/// How many times `word` occurs in `data`.
std::size_t occurrences(std::string_view data, std::string_view word) {
  std::size_t count = 0;
  for (std::size_t at = data.find(word); at != std::string_view::npos;
       at = data.find(word, at + word.size()))
    ++count;
  return count;
}

/// The soup as a Mesh: positions as floats, polygons fanned into triangles.
Mesh meshOf(const std::vector<Point>& points, const std::vector<Polygon>& polygons,
            const std::string& path) {
  Mesh mesh;
  mesh.positions.reserve(3 * points.size());
  for (const Point& p : points)
    for (int k = 0; k < 3; ++k) mesh.positions.push_back(toFloat(p[k]));
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const Polygon& polygon = polygons[f];
    if (polygon.size() < 3) fail(path, "face {} has {} corners", f, polygon.size());
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      for (const std::size_t corner : {polygon[0], polygon[i], polygon[i + 1]})
        mesh.indices.push_back(static_cast<std::uint32_t>(
            std::min<std::size_t>(corner, std::numeric_limits<std::uint32_t>::max())));
  }
  return mesh;
}

}  // namespace

Mesh readOff(const std::string& data, const std::string& path) {
  // The header first: CGAL sizes its arrays by the header's counts before reading a vertex,
  // so counts the file cannot hold (a vertex line takes 6 bytes or more, "0 0 0\n"; a face
  // 8, "3 0 1 2\n") are refused here rather than allocated.
  std::istringstream is(data);
  CGAL::File_header_OFF header(false);
  is >> header;
  if (!is || !header.off())
    fail(path, "not an OFF file (it does not start with a valid OFF header)");
  const std::size_t vertices = header.size_of_vertices(), faces = header.size_of_facets();
  const std::size_t headerEnd = stopOffset(is, data);
  constexpr std::size_t kMinVertexBytes = 6, kMinFaceBytes = 8;
  if (vertices > std::numeric_limits<std::uint32_t>::max() ||
      vertices > data.size() / kMinVertexBytes || faces > data.size() / kMinFaceBytes ||
      vertices * kMinVertexBytes + faces * kMinFaceBytes > data.size() - headerEnd + 1)
    fail(path,
         "the file is too short for the counts in its header ({} vertices, {} faces: each vertex "
         "takes {} bytes or more, each face {} or more, and the file has {} bytes)",
         vertices, faces, kMinVertexBytes, kMinFaceBytes, data.size());

  is.seekg(0);
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  std::vector<Kernel::Vector_3> normals;
  if (!CGAL::IO::read_OFF(
          is, points, polygons,
          CGAL::parameters::vertex_normal_output_iterator(std::back_inserter(normals))
              .verbose(false))) {
    // CGAL reports no more than failure. It reads a vertex or a face per line, so the line
    // it stopped on is the last one its stream consumed; a stream failed without badbit is
    // its sign of a vertex index out of range.
    const bool indexOutOfRange = is.fail() && !is.bad();
    const std::size_t stop = stopOffset(is, data);
    const std::vector<Line> read = dataLines(data, headerEnd, stop);
    const Line last = read.empty() ? Line{lineNumber(data, stop), ""} : read.back();
    if (indexOutOfRange) {
      const auto face = std::find_if(polygons.rbegin(), polygons.rend(),
                                     [](const Polygon& p) { return !p.empty(); });
      fail(path, "line {}: face {} refers to a vertex the file does not have (it has {} vertices)",
           last.number, polygons.rend() - face - 1, vertices);
    }
    if (last.text.find_first_not_of("0123456789+-.eE \t\r") != std::string_view::npos)
      fail(path, "line {}: '{}' is not a list of numbers (a vertex or a face)", last.number,
           last.text);
    const std::size_t lines = dataLines(data, headerEnd, data.size()).size();
    if (stop == data.size() && lines < vertices + faces)
      fail(path,
           "unexpected end of file: the header announces {} vertices and {} faces, the file has "
           "{} lines of them",
           vertices, faces, lines);
    fail(path, "line {}: '{}' is not a valid OFF {} line", last.number, last.text,
         read.size() <= vertices ? "vertex" : "face");
  }
  Mesh mesh = meshOf(points, polygons, path);
  if (header.has_normals() && normals.size() == points.size()) {
    mesh.normals.reserve(mesh.positions.size());
    for (const auto& n : normals)
      for (int k = 0; k < 3; ++k) mesh.normals.push_back(toFloat(n[k]));
  }
  return mesh;
}

Mesh readStl(const std::string& data, const std::string& path) {
  // Binary STL is an 80-byte header, a triangle count and 50 bytes per triangle; ASCII STL
  // starts with "solid". CGAL reads anything else as an empty binary file, so say here
  // what the file is not.
  constexpr std::size_t kHeader = 84, kTriangle = 50;
  const std::size_t first = std::min(data.find_first_not_of(" \t\r\n"), data.size());
  const bool startsWithSolid = data.compare(first, 5, "solid") == 0;
  std::uint64_t count = 0;  // the binary triangle count: a little-endian uint32 at byte 80
  if (data.size() >= kHeader)
    for (int k = 3; k >= 0; --k) count = count << 8 | static_cast<unsigned char>(data[80 + k]);
  const bool binarySized = data.size() >= kHeader && kHeader + kTriangle * count == data.size();
  if (!startsWithSolid) {
    if (data.size() < kHeader)
      fail(path,
           "not an STL file: {} bytes is too short for binary STL and it does not start "
           "with 'solid'",
           data.size());
    if (!binarySized)
      fail(path,
           "not a valid binary STL: {} triangles take {} bytes but the file has {} (and it is "
           "not ASCII STL, which starts with 'solid')",
           count, kHeader + kTriangle * count, data.size());
  }
  std::istringstream is(data, std::ios::in | std::ios::binary);
  CGAL::IO::set_mode(is, CGAL::IO::BINARY);
  std::vector<Point> points;
  std::vector<Polygon> triangles;
  // read_STL indexes the soup as it reads: corners at equal positions become one vertex
  // (what the polygon-soup repair's merge_duplicate_points_in_polygon_soup would do).
  // The rest of that repair is not wanted: it drops degenerate triangles, which meshes of
  // collapsed frame edges have and a round trip must keep.
  if (!CGAL::IO::read_STL(is, points, triangles, CGAL::parameters::verbose(false))) {
    const std::size_t stop = stopOffset(is, data);
    if (stop == data.size()) fail(path, "unexpected end of file (not valid ASCII STL)");
    fail(path, "line {}: not valid ASCII STL (CGAL's reader stopped there)",
         lineNumber(data, stop));
  }
  // When its ASCII reading fails, read_STL tries binary, which takes a file shorter than a
  // binary header for an empty one: a successful ASCII reading found "endsolid" and made a
  // triangle of every facet.
  const std::size_t facets = occurrences(data, "endfacet");
  if (startsWithSolid && !binarySized &&
      (triangles.size() != facets || !occurrences(data, "endsolid")))
    fail(path, "not valid ASCII STL: {} of its {} complete facets could be read{}",
         triangles.size(), facets,
         occurrences(data, "endsolid") ? "" : ", and it has no 'endsolid'");
  return meshOf(points, triangles, path);
}

}  // namespace pdesurf::detail

namespace {

bool registerCgalMeshReaders() {
  pdesurf::detail::CgalMeshReaders& readers = pdesurf::detail::cgalMeshReaders();
  readers.off = pdesurf::detail::readOff;
  readers.stl = pdesurf::detail::readStl;
  return true;
}

}  // namespace

// Registers the readers with readMesh (mesh_read.hpp) before main, in every program that links
// the CGAL module: its link options name this symbol, so the linker keeps this object.
extern "C" const bool pdesurf_cgal_mesh_readers = registerCgalMeshReaders();
