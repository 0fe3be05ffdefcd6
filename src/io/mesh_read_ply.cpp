// PLY meshes, ASCII and binary of either byte order: the vertex element's x y z (and nx ny nz),
// the face element's index list, polygons fanned into triangles; other elements skipped.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <optional>

#include "io/mesh_read.hpp"
#include "io/mesh_text.hpp"

namespace pdesurf::detail {

namespace {

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
    return binary(static_cast<std::size_t>(type), where,
                  std::make_index_sequence<std::tuple_size_v<CTypes>>{});
  }

 private:
  /// The C types of PlyType's values, in its order.
  using CTypes = std::tuple<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t,
                            std::uint32_t, float, double>;
  static_assert(std::tuple_size_v<CTypes> == static_cast<std::size_t>(PlyType::Float64) + 1);

  /// The next binary value of the type CTypes[type].
  template <std::size_t... I>
  double binary(std::size_t type, const Where& where, std::index_sequence<I...>) {
    double value = 0;
    ((I == type && (value = bytes_->get<std::tuple_element_t<I, CTypes>>(where), true)) || ...);
    return value;
  }

  Tokenizer& tokens_;
  std::optional<ByteReader> bytes_;
};

}  // namespace

Mesh readPly(const std::string& data, const std::string& path) {
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

}  // namespace pdesurf::detail
