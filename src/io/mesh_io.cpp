// Mesh files: OBJ, PLY, STL, glb and OFF, written atomically and read with validation.
// OFF and STL are read through CGAL (mesh_read_cgal.cpp), glb through tinygltf. OBJ and PLY
// keep their own readers: CGAL 5.5's polygon-soup readers drop the normals of both (files
// pdesurf writes carry them, and round trips keep them), and its OBJ reader refuses files
// without faces and skips malformed corners ("2/x") without a word.
#include "pdesurf/mesh_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/compile.h>
#include <fmt/format.h>
#include <tiny_gltf.h>

#include "io/atomic_file.hpp"
#include "io/mesh_read.hpp"

namespace pdesurf {
namespace {

// ---------------------------------------------------------------------------------------------
// Common helpers

using detail::fail;

std::string errnoText(int error) { return std::generic_category().message(error); }

std::string lowercase(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return result;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && lowercase(a) == lowercase(b);
}

/// Where in a file a value belongs ("vertex 3", "face 12", "header"), for error messages.
struct Where {
  std::string_view kind;
  std::size_t index = std::numeric_limits<std::size_t>::max();
};

std::string describe(const Where& where) {
  if (where.index == std::numeric_limits<std::size_t>::max()) return std::string(where.kind);
  return fmt::format("{} {}", where.kind, where.index);
}

/// `value` with its bytes reversed when `swap` is set (for files of the other endianness).
template <typename T>
T swapBytesIf(T value, bool swap) {
  if (!swap) return value;
  std::array<unsigned char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), &value, sizeof(T));
  std::reverse(bytes.begin(), bytes.end());
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}

constexpr bool kBigEndianHost = std::endian::native == std::endian::big;

/// Throws unless the mesh's buffers are consistent, so that every writer may trust them.
void validateForWriting(const Mesh& mesh, const std::string& path) {
  if (mesh.positions.size() % 3 != 0)
    fail(path, "invalid mesh: {} position values is not a multiple of 3", mesh.positions.size());
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    fail(path, "invalid mesh: {} normal values for {} position values", mesh.normals.size(),
         mesh.positions.size());
  if (mesh.indices.size() % 3 != 0)
    fail(path, "invalid mesh: {} indices is not a multiple of 3", mesh.indices.size());
  if (mesh.vertexCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "invalid mesh: {} vertices do not fit 32-bit indices", mesh.vertexCount());
  // Every format stores single-precision numbers; an infinite or NaN one would make a file
  // other programs reject or misdraw (a surface beyond ±3.4e38 overflows float).
  for (const auto* buffer : {&mesh.positions, &mesh.normals})
    for (std::size_t i = 0; i < buffer->size(); ++i)
      if (!std::isfinite((*buffer)[i]))
        fail(path,
             "invalid mesh: vertex {} has a non-finite {} ({}): coordinates must fit single "
             "precision (|x| < 3.4e38)",
             i / 3, buffer == &mesh.positions ? "position" : "normal", (*buffer)[i]);
  const std::size_t vertexCount = mesh.vertexCount();
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= vertexCount)
      fail(path, "invalid mesh: triangle {} refers to vertex {} but the mesh has {} vertices",
           i / 3, mesh.indices[i], vertexCount);
  }
}

// ---------------------------------------------------------------------------------------------
// Writing: through the project's one atomic-file writer (src/io/atomic_file.hpp).

using detail::AtomicFileWriter;

/// Appends `value` to `file` in little-endian byte order (call checkpoint() after each record).
template <typename T>
void appendLittle(AtomicFileWriter& file, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  value = swapBytesIf(value, kBigEndianHost);
  file.append(&value, sizeof(T));
}

void writeObj(const Mesh& mesh, AtomicFileWriter& file) {
  const auto& p = mesh.positions;
  const auto& n = mesh.normals;
  fmt::format_to(file.out(), "# pdesurf mesh: {} vertices, {} triangles\n", mesh.vertexCount(),
                 mesh.triangleCount());
  for (std::size_t i = 0; i < p.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("v {} {} {}\n"), p[i], p[i + 1], p[i + 2]);
    file.checkpoint();
  }
  for (std::size_t i = 0; i < n.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("vn {} {} {}\n"), n[i], n[i + 1], n[i + 2]);
    file.checkpoint();
  }
  const auto& t = mesh.indices;
  for (std::size_t i = 0; i < t.size(); i += 3) {
    const std::uint64_t a = t[i] + std::uint64_t{1}, b = t[i + 1] + std::uint64_t{1},
                        c = t[i + 2] + std::uint64_t{1};
    if (n.empty())
      fmt::format_to(file.out(), FMT_COMPILE("f {} {} {}\n"), a, b, c);
    else
      fmt::format_to(file.out(), FMT_COMPILE("f {}//{} {}//{} {}//{}\n"), a, a, b, b, c, c);
    file.checkpoint();
  }
}

void writePly(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  if (mesh.vertexCount() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    fail(path, "{} vertices are too many for PLY's int indices", mesh.vertexCount());
  const bool hasNormals = !mesh.normals.empty();
  fmt::format_to(file.out(),
                 "ply\nformat binary_little_endian 1.0\ncomment pdesurf\nelement vertex {}\n"
                 "property float x\nproperty float y\nproperty float z\n",
                 mesh.vertexCount());
  if (hasNormals)
    fmt::format_to(file.out(), "property float nx\nproperty float ny\nproperty float nz\n");
  fmt::format_to(file.out(),
                 "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                 mesh.triangleCount());
  for (std::size_t i = 0; i < mesh.positions.size(); i += 3) {
    for (std::size_t k = 0; k < 3; ++k) appendLittle(file, mesh.positions[i + k]);
    if (hasNormals)
      for (std::size_t k = 0; k < 3; ++k) appendLittle(file, mesh.normals[i + k]);
    file.checkpoint();
  }
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    appendLittle(file, std::uint8_t{3});
    for (std::size_t k = 0; k < 3; ++k)
      appendLittle(file, static_cast<std::int32_t>(mesh.indices[i + k]));
    file.checkpoint();
  }
}

void writeStl(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  if (mesh.triangleCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} triangles are too many for STL", mesh.triangleCount());
  std::array<char, 80> header{};
  constexpr std::string_view kHeader = "pdesurf binary STL";
  std::copy(kHeader.begin(), kHeader.end(), header.begin());
  file.append(header.data(), header.size());
  appendLittle(file, static_cast<std::uint32_t>(mesh.triangleCount()));
  const float* p = mesh.positions.data();
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const float* a = p + 3 * std::size_t{mesh.indices[i]};
    const float* b = p + 3 * std::size_t{mesh.indices[i + 1]};
    const float* c = p + 3 * std::size_t{mesh.indices[i + 2]};
    const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
    const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
    double normal[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0]};
    const double length =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (double& component : normal) component = length > 0 ? component / length : 0.0;
    for (double component : normal) appendLittle(file, static_cast<float>(component));
    for (const float* corner : {a, b, c})
      for (int k = 0; k < 3; ++k) appendLittle(file, corner[k]);
    appendLittle(file, std::uint16_t{0});
    file.checkpoint();
  }
}

void writeOff(const Mesh& mesh, AtomicFileWriter& file) {
  fmt::format_to(file.out(), "OFF\n{} {} 0\n", mesh.vertexCount(), mesh.triangleCount());
  const auto& p = mesh.positions;
  for (std::size_t i = 0; i < p.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("{} {} {}\n"), p[i], p[i + 1], p[i + 2]);
    file.checkpoint();
  }
  const auto& t = mesh.indices;
  for (std::size_t i = 0; i < t.size(); i += 3) {
    fmt::format_to(file.out(), FMT_COMPILE("3 {} {} {}\n"), t[i], t[i + 1], t[i + 2]);
    file.checkpoint();
  }
}

/// Appends `values` to a glTF buffer in little-endian order; returns the byte offset.
template <typename T>
std::size_t appendToBuffer(std::vector<unsigned char>& buffer, const MeshBuffer<T>& values) {
  const std::size_t offset = buffer.size();
  buffer.resize(offset + values.size() * sizeof(T));
  unsigned char* out = buffer.data() + offset;
  for (const T& value : values) {
    const T little = swapBytesIf(value, kBigEndianHost);
    std::memcpy(out, &little, sizeof(T));
    out += sizeof(T);
  }
  return offset;
}

/// Adds a buffer view over buffer 0 and a tightly packed accessor over it; returns the accessor.
int addAccessor(tinygltf::Model& model, std::size_t byteOffset, std::size_t byteLength, int target,
                int componentType, int type, std::size_t count) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = byteOffset;
  view.byteLength = byteLength;
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

void writeGlb(const Mesh& mesh, AtomicFileWriter& file, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "pdesurf";
  tinygltf::Node node;
  node.name = "pdesurf";  // tinygltf writes a node without properties as null, not {}
  // glTF forbids empty accessors: a mesh without vertices is an empty node, one without
  // triangles a point primitive.
  if (mesh.vertexCount() > 0) {
    tinygltf::Buffer buffer;
    tinygltf::Primitive primitive;
    const std::size_t n = mesh.vertexCount();
    const std::size_t vec3Bytes = n * 3 * sizeof(float);
    const int position = addAccessor(model, appendToBuffer(buffer.data, mesh.positions), vec3Bytes,
                                     TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                     TINYGLTF_TYPE_VEC3, n);
    tinygltf::Accessor& positions = model.accessors[static_cast<std::size_t>(position)];
    positions.minValues.assign(3, std::numeric_limits<double>::infinity());
    positions.maxValues.assign(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      positions.minValues[i % 3] = std::min<double>(positions.minValues[i % 3], mesh.positions[i]);
      positions.maxValues[i % 3] = std::max<double>(positions.maxValues[i % 3], mesh.positions[i]);
    }
    primitive.attributes["POSITION"] = position;
    if (!mesh.normals.empty())
      primitive.attributes["NORMAL"] = addAccessor(
          model, appendToBuffer(buffer.data, mesh.normals), vec3Bytes, TINYGLTF_TARGET_ARRAY_BUFFER,
          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    if (mesh.indices.empty()) {
      primitive.mode = TINYGLTF_MODE_POINTS;
    } else {
      primitive.mode = TINYGLTF_MODE_TRIANGLES;
      primitive.indices = addAccessor(
          model, appendToBuffer(buffer.data, mesh.indices),
          mesh.indices.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, mesh.indices.size());
    }
    // The glb container counts its bytes in 32 bits; leave room for the JSON chunk.
    if (buffer.data.size() > std::numeric_limits<std::uint32_t>::max() - (std::size_t{1} << 24))
      fail(path, "{} bytes of mesh data are too many for glb", buffer.data.size());
    model.buffers.push_back(std::move(buffer));
    tinygltf::Mesh gltfMesh;
    gltfMesh.primitives.push_back(std::move(primitive));
    model.meshes.push_back(std::move(gltfMesh));
    node.mesh = 0;
  }
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  std::ostringstream stream;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false, /*writeBinary=*/true) ||
      !stream)
    fail(path, "tinygltf could not serialize the mesh");
  const std::string bytes = std::move(stream).str();
  file.append(bytes.data(), bytes.size());
}

// ---------------------------------------------------------------------------------------------
// Reading helpers

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

/// Parses all of `text` as a number; also accepts a leading '+'.
template <typename T>
std::optional<T> parseNumber(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || ptr != end) return std::nullopt;
  return value;
}

/// Splits the ASCII formats into whitespace-separated tokens, line by line, skipping comments.
class Tokenizer {
 public:
  /// `comment` starts a comment that runs to the end of the line ('\0' for none).
  Tokenizer(std::string_view text, const std::string& path, char comment)
      : text_(text), path_(path), comment_(comment) {}

  /// The next token on the current line, or an empty view when the line ends first.
  std::string_view onLine() {
    while (pos_ < text_.size() && isBlank(text_[pos_])) ++pos_;
    if (pos_ == text_.size() || text_[pos_] == '\n') return {};
    if (comment_ != '\0' && text_[pos_] == comment_) {
      const std::size_t newline = text_.find('\n', pos_);
      pos_ = newline == std::string_view::npos ? text_.size() : newline;
      return {};
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !isBlank(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    return text_.substr(start, pos_ - start);
  }

  /// The next token, on this line or a later one; an empty view at the end of the file.
  std::string_view next() {
    for (;;) {
      const std::string_view token = onLine();
      if (!token.empty() || !nextLine()) return token;
    }
  }

  /// Skips the rest of the current line; false when there is no next line.
  bool nextLine() {
    const std::size_t newline = text_.find('\n', pos_);
    if (newline == std::string_view::npos) {
      pos_ = text_.size();
      return false;
    }
    pos_ = newline + 1;
    ++line_;
    return true;
  }

  bool atEnd() const { return pos_ >= text_.size(); }
  std::size_t offset() const { return pos_; }

  /// `token` as a number of type T; `where` names what it belongs to in error messages.
  template <typename T>
  T number(std::string_view token, const Where& where) const {
    if (token.empty()) failAtEnd(where);
    const std::optional<T> value = parseNumber<T>(token);
    if (!value) fail("expected a number in {}, found '{}'", describe(where), token);
    return *value;
  }

  template <typename T>
  T nextNumber(const Where& where) {
    return number<T>(next(), where);
  }

  template <typename T>
  T numberOnLine(const Where& where) {
    const std::string_view token = onLine();
    if (token.empty()) fail("missing a number in {}", describe(where));
    return number<T>(token, where);
  }

  /// Reads the next token and fails unless it is `keyword` (ignoring case).
  void expect(std::string_view keyword, const Where& where) {
    const std::string_view token = next();
    if (token.empty()) failAtEnd(where);
    if (!equalsIgnoringCase(token, keyword))
      fail("expected '{}' in {}, found '{}'", keyword, describe(where), token);
  }

  /// Fails with the file name and current line number.
  template <typename... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
    throw MeshIoError(fmt::format("{}: line {}: {}", path_, line_,
                                  fmt::format(format, std::forward<Args>(args)...)));
  }

  [[noreturn]] void failAtEnd(const Where& where) const {
    pdesurf::fail(path_, "unexpected end of file in {}", describe(where));
  }

 private:
  static bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
  }

  std::string_view text_;
  const std::string& path_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

/// Reads little- or big-endian binary values from a byte string.
class ByteReader {
 public:
  ByteReader(std::string_view data, std::size_t offset, const std::string& path, bool bigEndian)
      : data_(data), pos_(offset), path_(path), swap_(bigEndian != kBigEndianHost) {}

  template <typename T>
  T get(const Where& where) {
    if (pos_ > data_.size() || data_.size() - pos_ < sizeof(T))
      fail(path_, "unexpected end of file in {}", describe(where));
    T value;
    std::memcpy(&value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return swapBytesIf(value, swap_);
  }

  void skip(std::size_t bytes) { pos_ += bytes; }

 private:
  std::string_view data_;
  std::size_t pos_;
  const std::string& path_;
  bool swap_;
};

/// Appends polygon `corners` to `indices` as a fan of triangles.
void appendFan(const std::vector<std::uint32_t>& corners, MeshBuffer<std::uint32_t>& indices) {
  for (std::size_t i = 1; i + 1 < corners.size(); ++i)
    indices.insert(indices.end(), {corners[0], corners[i], corners[i + 1]});
}

// ---------------------------------------------------------------------------------------------
// OBJ

/// The 0-based index that OBJ index `raw` (1-based, or negative counting back) denotes, of
/// one of the `defined` vertices (or normals) so far.
std::uint32_t resolveObjIndex(std::int64_t raw, std::size_t defined, const Tokenizer& tokens,
                              bool normal, std::size_t face) {
  const std::int64_t count = static_cast<std::int64_t>(defined);
  const std::int64_t index = raw > 0 ? raw - 1 : count + raw;
  if (raw == 0 || index < 0 || index >= count)
    tokens.fail("face {} refers to {} {} but only {} {} defined before it", face,
                normal ? "normal" : "vertex", raw, defined,
                normal ? (defined == 1 ? "normal is" : "normals are")
                       : (defined == 1 ? "vertex is" : "vertices are"));
  return static_cast<std::uint32_t>(index);
}

Mesh readObj(std::string_view text, const std::string& path) {
  Tokenizer tokens(text, path, '#');
  Mesh mesh;
  std::vector<float> normals;
  constexpr std::int64_t kNone = -1;
  std::vector<std::int64_t> normalOf;  // per vertex, the normal every corner pairs it with
  bool normalsConsistent = true;
  std::vector<std::uint32_t> corners;
  std::size_t faceCount = 0;
  while (!tokens.atEnd()) {
    const std::string_view keyword = tokens.onLine();
    if (keyword == "v") {
      const Where where{"vertex", mesh.vertexCount()};
      for (int k = 0; k < 3; ++k) mesh.positions.push_back(tokens.numberOnLine<float>(where));
    } else if (keyword == "vn") {
      const Where where{"normal", normals.size() / 3};
      for (int k = 0; k < 3; ++k) normals.push_back(tokens.numberOnLine<float>(where));
    } else if (keyword == "f") {
      corners.clear();
      for (std::string_view corner = tokens.onLine(); !corner.empty(); corner = tokens.onLine()) {
        // v, v/vt, v//vn or v/vt/vn.
        const auto index = [&](std::string_view part) {
          const std::optional<std::int64_t> value = parseNumber<std::int64_t>(part);
          if (!value) tokens.fail("malformed corner '{}' in face {}", corner, faceCount);
          return *value;
        };
        const std::size_t slash = corner.find('/');
        const std::size_t slash2 =
            slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
        const std::uint32_t vertex = resolveObjIndex(index(corner.substr(0, slash)),
                                                     mesh.vertexCount(), tokens, false, faceCount);
        corners.push_back(vertex);
        if (slash != std::string_view::npos && slash2 != slash + 1)
          index(corner.substr(slash + 1, slash2 - slash - 1));  // the texture coordinate
        if (slash2 == std::string_view::npos) {
          normalsConsistent = false;
          continue;
        }
        const std::uint32_t normal = resolveObjIndex(index(corner.substr(slash2 + 1)),
                                                     normals.size() / 3, tokens, true, faceCount);
        if (normalsConsistent) {
          normalOf.resize(mesh.vertexCount(), kNone);
          if (normalOf[vertex] == kNone) normalOf[vertex] = normal;
          normalsConsistent = normalOf[vertex] == normal;
        }
      }
      if (corners.size() < 3) tokens.fail("face {} has {} corners", faceCount, corners.size());
      appendFan(corners, mesh.indices);
      ++faceCount;
    }
    tokens.nextLine();  // Other statements (vt, g, o, s, usemtl, l, ...) are ignored.
  }
  // Per-vertex normals when every corner pairs its vertex with one normal; vertices no face
  // uses take the normal of the same number.
  if (normalsConsistent && !normals.empty()) {
    normalOf.resize(mesh.vertexCount(), kNone);
    mesh.normals.reserve(mesh.positions.size());
    for (std::size_t v = 0; v < normalOf.size() && normalsConsistent; ++v) {
      const std::int64_t n = normalOf[v] != kNone ? normalOf[v] : static_cast<std::int64_t>(v);
      normalsConsistent = static_cast<std::size_t>(n) < normals.size() / 3;
      if (normalsConsistent)
        mesh.normals.insert(mesh.normals.end(), normals.begin() + 3 * n,
                            normals.begin() + 3 * n + 3);
    }
    if (!normalsConsistent) mesh.normals.clear();
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// PLY

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyType(std::string_view name) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [typeName, type] : kNames)
    if (typeName == name) return type;
  return std::nullopt;
}

bool isInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

struct PlyProperty {
  std::string name;
  PlyType type;  // of the value, or of a list's items
  bool isList = false;
  PlyType countType = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;

  /// The index of the property called `name`, or -1.
  int find(std::string_view propertyName) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == propertyName) return static_cast<int>(i);
    return -1;
  }
};

/// Reads PLY values, ASCII or binary, as doubles (exact for every PLY type).
class PlyValues {
 public:
  PlyValues(Tokenizer& tokens, std::optional<ByteReader> bytes)
      : tokens_(tokens), bytes_(std::move(bytes)) {}

  double get(PlyType type, const Where& where) {
    if (!bytes_) {
      const std::string_view token = tokens_.next();
      if (type == PlyType::Float32) return tokens_.number<float>(token, where);
      if (type == PlyType::Float64) return tokens_.number<double>(token, where);
      return static_cast<double>(tokens_.number<std::int64_t>(token, where));
    }
    switch (type) {
      case PlyType::Int8:
        return bytes_->get<std::int8_t>(where);
      case PlyType::UInt8:
        return bytes_->get<std::uint8_t>(where);
      case PlyType::Int16:
        return bytes_->get<std::int16_t>(where);
      case PlyType::UInt16:
        return bytes_->get<std::uint16_t>(where);
      case PlyType::Int32:
        return bytes_->get<std::int32_t>(where);
      case PlyType::UInt32:
        return bytes_->get<std::uint32_t>(where);
      case PlyType::Float32:
        return bytes_->get<float>(where);
      case PlyType::Float64:
        return bytes_->get<double>(where);
    }
    return 0;
  }

 private:
  Tokenizer& tokens_;
  std::optional<ByteReader> bytes_;
};

/// `value` rounded to float; beyond float's range, infinite (a plain cast would be undefined).
float toFloat(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  return value > kMax ? kInfinity : value < -kMax ? -kInfinity : static_cast<float>(value);
}

Mesh readPly(std::string_view data, const std::string& path) {
  Tokenizer tokens(data, path, '\0');
  if (tokens.onLine() != "ply") fail(path, "not a PLY file (it does not start with 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!tokens.nextLine()) fail(path, "unexpected end of file in the header");
    const std::string_view keyword = tokens.onLine();
    if (keyword == "format") {
      format = tokens.onLine();
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        tokens.fail("unknown PLY format '{}'", format);
    } else if (keyword == "element") {
      PlyElement element;
      element.name = tokens.onLine();
      const auto count = tokens.numberOnLine<std::int64_t>(Where{"the element line"});
      if (element.name.empty() || count < 0) tokens.fail("malformed element line");
      element.count = static_cast<std::size_t>(count);
      elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (elements.empty()) tokens.fail("property before any element");
      PlyProperty property;
      std::string_view typeName = tokens.onLine();
      if (typeName == "list") {
        property.isList = true;
        const std::string_view countName = tokens.onLine();
        const std::optional<PlyType> countType = plyType(countName);
        if (!countType || !isInteger(*countType))
          tokens.fail("unknown list count type '{}'", countName);
        property.countType = *countType;
        typeName = tokens.onLine();
      }
      const std::optional<PlyType> type = plyType(typeName);
      if (!type) tokens.fail("unknown property type '{}'", typeName);
      property.type = *type;
      property.name = tokens.onLine();
      if (property.name.empty()) tokens.fail("property without a name");
      elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      tokens.nextLine();
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      tokens.fail("unexpected '{}' in the PLY header", keyword);
    }
  }
  if (format.empty()) fail(path, "the header has no format line");

  // What the vertex and face elements hold.
  const auto vertexElement = std::find_if(elements.begin(), elements.end(),
                                          [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertexElement == elements.end()) fail(path, "the file has no vertex element");
  const std::size_t vertexCount = vertexElement->count;
  if (vertexCount > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} vertices do not fit 32-bit indices", vertexCount);
  constexpr std::array<std::string_view, 6> kSlots = {"x", "y", "z", "nx", "ny", "nz"};
  std::vector<int> slotOf(vertexElement->properties.size(), -1);
  std::array<bool, 6> present{};
  for (std::size_t slot = 0; slot < kSlots.size(); ++slot) {
    const int property = vertexElement->find(kSlots[slot]);
    if (property < 0) continue;
    if (vertexElement->properties[static_cast<std::size_t>(property)].isList)
      fail(path, "vertex property '{}' is a list", kSlots[slot]);
    slotOf[static_cast<std::size_t>(property)] = static_cast<int>(slot);
    present[slot] = true;
  }
  for (std::size_t slot = 0; slot < 3; ++slot)
    if (!present[slot]) fail(path, "the vertex element has no property '{}'", kSlots[slot]);
  const bool hasNormals = present[3] && present[4] && present[5];
  const auto faceElement = std::find_if(elements.begin(), elements.end(),
                                        [](const PlyElement& e) { return e.name == "face"; });
  int indexProperty = -1;
  if (faceElement != elements.end()) {
    indexProperty = faceElement->find("vertex_indices");
    if (indexProperty < 0) indexProperty = faceElement->find("vertex_index");
    if (indexProperty < 0) fail(path, "the face element has no vertex_indices list");
    const PlyProperty& property = faceElement->properties[static_cast<std::size_t>(indexProperty)];
    if (!property.isList || !isInteger(property.type))
      fail(path, "the face property '{}' is not a list of integers", property.name);
  }

  // The body. Counts come from the file, so reservations are capped by its size.
  std::optional<ByteReader> bytes;
  if (format != "ascii") bytes.emplace(data, tokens.offset(), path, format == "binary_big_endian");
  PlyValues values(tokens, std::move(bytes));
  Mesh mesh;
  mesh.positions.reserve(3 * std::min(vertexCount, data.size()));
  if (hasNormals) mesh.normals.reserve(3 * std::min(vertexCount, data.size()));
  std::vector<std::uint32_t> corners;
  for (auto element = elements.begin(); element != elements.end(); ++element) {
    const bool isVertex = element == vertexElement, isFace = element == faceElement;
    if (isFace) mesh.indices.reserve(3 * std::min(element->count, data.size()));
    for (std::size_t i = 0; i < element->count; ++i) {
      const Where where{element->name, i};
      std::array<double, 6> vertex{};
      for (std::size_t p = 0; p < element->properties.size(); ++p) {
        const PlyProperty& property = element->properties[p];
        if (!property.isList) {
          const double value = values.get(property.type, where);
          if (isVertex && slotOf[p] >= 0) vertex[static_cast<std::size_t>(slotOf[p])] = value;
          continue;
        }
        const double length = values.get(property.countType, where);
        if (length < 0) fail(path, "{} has a list of negative length", describe(where));
        const bool isIndices = isFace && static_cast<int>(p) == indexProperty;
        corners.clear();
        for (std::size_t k = 0; k < static_cast<std::size_t>(length); ++k) {
          const double value = values.get(property.type, where);
          if (!isIndices) continue;
          if (value < 0 || value >= static_cast<double>(vertexCount))
            fail(path, "face {} refers to vertex {} but the file has {} vertices", i,
                 static_cast<std::int64_t>(value), vertexCount);
          corners.push_back(static_cast<std::uint32_t>(value));
        }
        if (isIndices && corners.size() < 3)
          fail(path, "face {} has {} corners", i, corners.size());
        appendFan(corners, mesh.indices);
      }
      if (isVertex) {
        for (std::size_t k = 0; k < 3; ++k) mesh.positions.push_back(toFloat(vertex[k]));
        if (hasNormals)
          for (std::size_t k = 3; k < 6; ++k) mesh.normals.push_back(toFloat(vertex[k]));
      }
    }
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// glb

/// Where accessor `index`'s elements start in their buffer, and their stride.
struct AccessorData {
  const unsigned char* data;
  std::size_t stride;
  std::size_t count;
  int componentType;
};

AccessorData accessorData(const tinygltf::Model& model, int index, const std::string& path,
                          const std::string& what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    fail(path, "{}: no accessor {}", what, index);
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.sparse.isSparse) fail(path, "{}: sparse accessors are not supported", what);
  if (accessor.bufferView < 0 ||
      static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size())
    fail(path, "{}: accessor {} has no valid buffer view", what, index);
  const tinygltf::BufferView& view =
      model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail(path, "{}: buffer view {} has no valid buffer", what, accessor.bufferView);
  const std::vector<unsigned char>& buffer =
      model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const int stride = accessor.ByteStride(view);
  const int componentSize =
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  const int components =
      tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  if (stride <= 0 || componentSize <= 0 || components <= 0)
    fail(path, "{}: accessor {} has an invalid type or stride", what, index);
  const std::size_t elementSize = static_cast<std::size_t>(componentSize * components);
  const std::size_t needed = accessor.count == 0
                                 ? 0
                                 : accessor.byteOffset +
                                       static_cast<std::size_t>(stride) * (accessor.count - 1) +
                                       elementSize;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset ||
      needed > view.byteLength)
    fail(path, "{}: accessor {} reaches beyond its buffer", what, index);
  return {buffer.data() + view.byteOffset + accessor.byteOffset, static_cast<std::size_t>(stride),
          accessor.count, accessor.componentType};
}

/// Appends the float VEC3 accessor `index` to `out`.
std::size_t appendVec3(const tinygltf::Model& model, int index, const std::string& path,
                       const std::string& what, MeshBuffer<float>& out) {
  const AccessorData data = accessorData(model, index, path, what);
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
      accessor.type != TINYGLTF_TYPE_VEC3)
    fail(path, "{}: expected float VEC3 values", what);
  for (std::size_t i = 0; i < data.count; ++i) {
    std::array<float, 3> value;
    std::memcpy(value.data(), data.data + i * data.stride, sizeof(value));
    for (float component : value) out.push_back(swapBytesIf(component, kBigEndianHost));
  }
  return data.count;
}

template <typename T>
std::uint32_t loadIndex(const unsigned char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return swapBytesIf(value, kBigEndianHost);
}

Mesh readGlb(const std::string& data, const std::string& path) {
  if (data.size() > std::numeric_limits<unsigned int>::max())
    fail(path, "{} bytes is too large for tinygltf", data.size());
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const std::size_t slash = path.rfind('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  if (!loader.LoadBinaryFromMemory(&model, &error, &warning,
                                   reinterpret_cast<const unsigned char*>(data.data()),
                                   static_cast<unsigned int>(data.size()), directory)) {
    while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back())))
      error.pop_back();
    fail(path, "{}", error.empty() ? std::string("not a valid glb file") : error);
  }
  Mesh mesh;
  bool allNormals = true;
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      const std::string what = fmt::format("mesh {} primitive {}", m, p);
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != TINYGLTF_MODE_POINTS)
        fail(path, "{}: mode {} is not triangles", what, primitive.mode);
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) fail(path, "{} has no POSITION", what);
      const std::size_t base = mesh.vertexCount();
      const std::size_t count = appendVec3(model, position->second, path, what, mesh.positions);
      const auto normal = primitive.attributes.find("NORMAL");
      allNormals = allNormals && normal != primitive.attributes.end() &&
                   appendVec3(model, normal->second, path, what, mesh.normals) == count;
      if (primitive.mode == TINYGLTF_MODE_POINTS) continue;
      if (primitive.indices < 0) {  // not indexed: consecutive corners
        if (count % 3 != 0) fail(path, "{}: {} corners do not make triangles", what, count);
        for (std::size_t i = 0; i < count; ++i)
          mesh.indices.push_back(static_cast<std::uint32_t>(base + i));
        continue;
      }
      const AccessorData indices = accessorData(model, primitive.indices, path, what);
      if (indices.count % 3 != 0 ||
          model.accessors[static_cast<std::size_t>(primitive.indices)].type != TINYGLTF_TYPE_SCALAR)
        fail(path, "{}: the indices are not triangles", what);
      for (std::size_t i = 0; i < indices.count; ++i) {
        const unsigned char* at = indices.data + i * indices.stride;
        std::uint32_t index = 0;
        switch (indices.componentType) {
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            index = *at;
            break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            index = loadIndex<std::uint16_t>(at);
            break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            index = loadIndex<std::uint32_t>(at);
            break;
          default:
            fail(path, "{}: indices must be unsigned integers", what);
        }
        if (index >= count)
          fail(path, "{}: triangle {} refers to vertex {} but the primitive has {} vertices", what,
               i / 3, index, count);
        mesh.indices.push_back(static_cast<std::uint32_t>(base + index));
      }
    }
  }
  if (mesh.vertexCount() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "{} vertices do not fit 32-bit indices", mesh.vertexCount());
  if (!allNormals) mesh.normals.clear();
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// After reading, whatever the format

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

// ---------------------------------------------------------------------------------------------
// Public interface

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

void writeMesh(const Mesh& mesh, const std::string& path) {
  const MeshFormat format = meshFormatFromPath(path);
  validateForWriting(mesh, path);
  try {
    AtomicFileWriter file(path);
    switch (format) {
      case MeshFormat::Obj:
        writeObj(mesh, file);
        break;
      case MeshFormat::Ply:
        writePly(mesh, file, path);
        break;
      case MeshFormat::Stl:
        writeStl(mesh, file, path);
        break;
      case MeshFormat::Glb:
        writeGlb(mesh, file, path);
        break;
      case MeshFormat::Off:
        writeOff(mesh, file);
        break;
    }
    file.commit();
  } catch (const MeshIoError&) {
    throw;
  } catch (const FileError& e) {  // the write itself: a MeshIoError like every other failure
    throw MeshIoError(e.what());
  }
}

Mesh readMesh(const std::string& path) {
  const MeshFormat format = meshFormatFromPath(path);
  const std::string data = readFile(path);
  Mesh mesh;
  switch (format) {
    case MeshFormat::Obj:
      mesh = readObj(data, path);
      break;
    case MeshFormat::Ply:
      mesh = readPly(data, path);
      break;
    case MeshFormat::Stl:
      mesh = detail::readStl(data, path);
      break;
    case MeshFormat::Glb:
      mesh = readGlb(data, path);
      break;
    case MeshFormat::Off:
      mesh = detail::readOff(data, path);
      break;
  }
  checkReadMesh(mesh, path);
  return mesh;
}

}  // namespace pdesurf
