// The JSON reading shared by every model type's parser: typed members with JSON paths in
// errors, on top of the vertex-frame Reader (json_reader.hpp).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "io/json_reader.hpp"
#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf::detail {

/// Reading of the members every model type shares.
class ModelReader : public Reader {
 public:
  using Reader::Reader;

  std::uint32_t integer(const Json& j, const std::string& path, std::uint32_t lo,
                        std::uint32_t hi) const {
    if (!j.is_number_integer())
      fail(path, fmt::format("expected an integer, found {}",
                             j.is_number() ? j.dump() : std::string(typeName(j))));
    const bool negative = !j.is_number_unsigned() && j.get<std::int64_t>() < 0;
    if (negative || j.get<std::uint64_t>() < lo || j.get<std::uint64_t>() > hi)
      fail(path, fmt::format("{} is out of range (expected {} to {})", j.dump(), lo, hi));
    return static_cast<std::uint32_t>(j.get<std::uint64_t>());
  }

  std::string string(const Json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, fmt::format("expected a string, found {}", typeName(j)));
    return j.get<std::string>();
  }

  /// An edit of the studio's (edit_io.hpp): its JSON object, its "group" (empty without one)
  /// and its "op".
  struct Edit {
    Json doc;
    std::string group, op;
  };
  Edit edit(std::string_view json) const {
    Edit e{parseDocument(json), {}, {}};
    expectObject(e.doc, "$");
    if (auto it = e.doc.find("group"); it != e.doc.end()) e.group = string(*it, "$.group");
    e.op = string(member(e.doc, "$", "op"), "$.op");
    return e;
  }

  bool boolean(const Json& j, const std::string& path) const {
    if (!j.is_boolean()) fail(path, fmt::format("expected true or false, found {}", typeName(j)));
    return j.get<bool>();
  }

  /// One of the listed words.
  template <typename T>
  T choice(const Json& j, const std::string& path,
           std::initializer_list<std::pair<const char*, T>> words) const {
    const std::string word = string(j, path);
    std::string known;
    for (const auto& [name, value] : words) {
      if (word == name) return value;
      known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", name);
    }
    fail(path, fmt::format("unknown value \"{}\" (expected one of {})", word, known));
  }

  /// Members a document of this type may have; anything else is a typo worth reporting.
  void onlyMembers(const Json& obj, const std::string& path,
                   std::initializer_list<const char*> allowed) const {
    for (const auto& [key, value] : obj.items()) {
      bool ok = false;
      for (const char* a : allowed) ok = ok || key == a;
      if (!ok) {
        std::string list;
        for (const char* a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", a);
        fail(path, fmt::format("unknown field \"{}\" (expected {})", key, list));
      }
    }
  }

  void header(const Json& doc, std::string& name, std::string& description) const {
    if (auto it = doc.find("name"); it != doc.end()) name = string(*it, "$.name");
    if (auto it = doc.find("description"); it != doc.end())
      description = string(*it, "$.description");
  }
};

// Each model type's document, parsed beside its type's other file code; `source` names it in
// errors. parseModel (src/io/any_model_io.cpp) picks one by the document's "type".
/// The "bspline-pde" document (src/io/bspline_pde_io.cpp).
BSplinePdeModel parseBSplinePdeDocument(const Json& doc, const std::string& source);
/// The "spectral" and "cross-sections" documents (src/io/spectral_io.cpp).
SpectralModel parseSpectralDocument(const Json& doc, const std::string& source);
CrossSectionModel parseCrossSectionsDocument(const Json& doc, const std::string& source);

}  // namespace pdesurf::detail
