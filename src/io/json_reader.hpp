// Reading JSON documents with errors that name the file and the JSON path: shared by the
// model parser and the edit parser (private to src/io).
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/model_io.hpp"

namespace pdesurf::detail {

using Json = nlohmann::json;

/// The whole text of a model file (errors name the path).
inline std::string readModelFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path, "", "cannot open the file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ModelError(path, "", "read error");
  return text.str();
}

inline const char* kComponents[3] = {"x", "y", "z"};

/// Readable names of the four sides, for messages.
inline const char* sideName(Side s) {
  // Indexed by Side: Alpha, Delta, Beta, Gamma.
  static constexpr const char* kNames[] = {"P1-P2-P3", "P3-P4-P5", "P7-P6-P5", "P1-P8-P7"};
  return kNames[static_cast<std::size_t>(s) & 3];
}

inline const char* typeName(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

/// Where and why parsing stopped.
struct ParseFailure {
  std::string path;       ///< JSON path of the value being read ("$" at the top level)
  std::string what;       ///< nlohmann's message
  std::string token;      ///< the last token read
  bool overflow = false;  ///< a number beyond the range of a double (out_of_range.406)
};

/// Builds the document like nlohmann's own parser, but knows the JSON path of the value
/// being read, so that a syntax error or a number like 1e999 can be reported by its path.
class PathTrackingBuilder {
 public:
  explicit PathTrackingBuilder(Json& root) : root_(root) {}
  const ParseFailure& failure() const { return failure_; }

  bool null() { return value(nullptr); }
  bool boolean(bool b) { return value(b); }
  bool number_integer(Json::number_integer_t x) { return value(x); }
  bool number_unsigned(Json::number_unsigned_t x) { return value(x); }
  bool number_float(Json::number_float_t x, const Json::string_t& /*text*/) { return value(x); }
  bool string(Json::string_t& s) { return value(std::move(s)); }
  bool binary(Json::binary_t& b) { return value(Json::binary(std::move(b))); }
  bool start_object(std::size_t /*size*/) { return open(Json::object(), false); }
  bool start_array(std::size_t /*size*/) { return open(Json::array(), true); }
  bool key(Json::string_t& k) {
    levels_.back().key = std::move(k);
    levels_.back().haveKey = true;
    return true;
  }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool parse_error(std::size_t /*position*/, const std::string& lastToken,
                   const Json::exception& e) {
    std::vector<std::string_view> steps;
    for (const Level& l : levels_) steps.push_back(l.self);
    std::string last;  // the value that was being read inside the innermost container
    if (!levels_.empty()) {
      const Level& in = levels_.back();
      if (in.array)
        last = fmt::format("[{}]", in.node->size());
      else if (in.haveKey)
        last = member(in.key);
    }
    failure_.path = fmt::format("${}{}", fmt::join(steps, ""), last);
    failure_.what = e.what();
    failure_.token = lastToken;
    failure_.overflow = e.id == 406;
    return false;
  }

 private:
  struct Level {
    Json* node;
    bool array;
    std::string self;  ///< this container's step in the path from its parent
    std::string key;   ///< objects: the key whose value comes next
    bool haveKey = false;
  };

  static std::string member(const std::string& key) {
    const bool plain =
        !key.empty() && (std::isalpha(static_cast<unsigned char>(key[0])) || key[0] == '_') &&
        std::all_of(key.begin(), key.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    return plain ? fmt::format(".{}", key) : fmt::format("[{}]", Json(key).dump());
  }

  /// Places a value in the innermost container (or at the root) and returns it.
  Json* place(Json&& v, std::string* step) {
    if (levels_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Level& in = levels_.back();
    if (in.array) {
      if (step) *step = fmt::format("[{}]", in.node->size());
      in.node->push_back(std::move(v));
      return &in.node->back();
    }
    if (step) *step = member(in.key);
    in.haveKey = false;
    Json& slot = (*in.node)[in.key];
    slot = std::move(v);
    return &slot;
  }
  bool value(Json&& v) {
    place(std::move(v), nullptr);
    return true;
  }
  bool open(Json&& container, bool array) {
    std::string step;
    Json* node = place(std::move(container), &step);
    levels_.push_back({node, array, std::move(step), {}, false});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return true;
  }

  Json& root_;
  std::vector<Level> levels_;
  ParseFailure failure_;
};

/// Walks a document, checking as it goes; every error names the file and the JSON path.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  /// Parses JSON text; a syntax error or an out-of-range number fails with its JSON path.
  Json parseDocument(std::string_view text) const {
    Json doc;
    PathTrackingBuilder builder(doc);
    if (!Json::sax_parse(text.begin(), text.end(), &builder)) {
      const ParseFailure& failure = builder.failure();
      if (failure.overflow)  // nlohmann reports a number beyond a double as out_of_range.406
        fail(failure.path, fmt::format("number is not finite ({} is beyond the range of a double)",
                                       failure.token));
      // nlohmann's text reads "[json.exception.parse_error.101] parse error at line L, ..."
      const auto at = failure.what.find("parse error");
      fail(failure.path,
           fmt::format("malformed JSON: {}",
                       at == std::string::npos ? failure.what : failure.what.substr(at)));
    }
    return doc;
  }

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw ModelError(source_, path, problem);
  }

  const Json& member(const Json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(path, fmt::format("missing required field \"{}\"", key));
    return *it;
  }

  void expectObject(const Json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, fmt::format("expected an object, found {}", typeName(j)));
  }

  void expectArray(const Json& j, const std::string& path, std::size_t minSize) const {
    if (!j.is_array()) fail(path, fmt::format("expected an array, found {}", typeName(j)));
    if (j.size() < minSize)
      fail(path, fmt::format("expected at least {} entr{}, found {}", minSize,
                             minSize == 1 ? "y" : "ies", j.size()));
  }

  double number(const Json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, fmt::format("expected a number, found {}", typeName(j)));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(path, "number is not finite");
    return x;
  }

  template <std::size_t N>
  std::array<double, N> numbers(const Json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != N)
      fail(path, j.is_array()
                     ? fmt::format("expected {} numbers, found {}", N, j.size())
                     : fmt::format("expected an array of {} numbers, found {}", N, typeName(j)));
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = number(j[i], fmt::format("{}[{}]", path, i));
    return out;
  }

  Vec3 vec3(const Json& j, const std::string& path) const {
    const auto a = numbers<3>(j, path);
    return {a[0], a[1], a[2]};
  }

  /// An index into a list of `count` things called `what` (plural `whats`).
  std::uint32_t index(const Json& j, const std::string& path, std::size_t count, const char* what,
                      const char* whats) const {
    if (j.is_number_float()) {
      const double d = j.get<double>();
      fail(path, std::trunc(d) == d
                     ? fmt::format("expected an integer {} index, found {} (written with a "
                                   "fraction or exponent, or beyond 64-bit integers)",
                                   what, j.dump())
                     : fmt::format("expected an integer {} index, found a fractional number {}",
                                   what, j.dump()));
    }
    if (!j.is_number_integer())
      fail(path, fmt::format("expected an integer {} index, found {}", what, typeName(j)));
    // nlohmann keeps non-negative integers unsigned (2^64 - 1 is not -1); "-0" is signed 0.
    const bool negative = !j.is_number_unsigned() && j.get<std::int64_t>() < 0;
    const std::uint64_t value = negative ? 0 : j.get<std::uint64_t>();
    if (negative || value >= count)
      fail(path,
           fmt::format("{} index {} is out of range (the model has {} {}, indices 0 to {})", what,
                       j.dump(), count, count == 1 ? what : whats, count == 0 ? 0 : count - 1));
    return static_cast<std::uint32_t>(value);
  }

  Region region(const Json& j, const std::string& path) const {
    const auto r = numbers<4>(j, path);
    for (int i = 0; i < 4; ++i)
      if (r[i] < 0.0 || r[i] > 1.0)
        fail(path, fmt::format("region bounds must lie in [0, 1], found {}", r[i]));
    if (!(r[0] < r[1]))
      fail(path, fmt::format("empty or inverted region: u0 = {} is not below u1 = {}", r[0], r[1]));
    if (!(r[2] < r[3]))
      fail(path, fmt::format("empty or inverted region: v0 = {} is not below v1 = {}", r[2], r[3]));
    return {r[0], r[1], r[2], r[3]};
  }

  /// A force must have a particular solution: a1/Lu² + a2/Lv² ≠ 0 where f0 ≠ 0.
  void checkSolvable(const Frame& f, const Vec3& f0, const Region& r, const std::string& path,
                     std::uint32_t frame, bool wholeFrame) const {
    const double lu = r.u1 - r.u0, lv = r.v1 - r.v0;
    for (int c = 0; c < 3; ++c) {
      if (f0[c] == 0.0) continue;
      const double t1 = f.a1[c] / (lu * lu), t2 = f.a2[c] / (lv * lv);
      const double den = t1 + t2;
      const bool zero = std::isfinite(den) &&
                        std::abs(den) <= kForceSolvabilityTolerance * (std::abs(t1) + std::abs(t2));
      if (zero || !std::isfinite(den))
        fail(path, fmt::format("on frame {}, a1.{}/Lu² + a2.{}/Lv² is {} (a1.{} = {}, a2.{} = {}, "
                               "Lu = {}, Lv = {}), so the force component f0.{} = {} has no "
                               "solution: change {}",
                               frame, kComponents[c], kComponents[c],
                               zero ? "0 (to rounding)" : "not finite", kComponents[c], f.a1[c],
                               kComponents[c], f.a2[c], lu, lv, kComponents[c], f0[c],
                               wholeFrame ? fmt::format("a1 or a2 of frames[{}]", frame)
                                          : std::string("a1, a2 or the region")));
    }
  }

  /// An array of forces at `path`: each an object with "f0", the rest read by
  /// `rest(force, json, itsPath)`.
  template <class Force, class Rest>
  std::vector<Force> forceList(const Json& list, const std::string& path, Rest&& rest) const {
    expectArray(list, path, 0);
    std::vector<Force> forces;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string fp = fmt::format("{}[{}]", path, i);
      const Json& jforce = list[i];
      expectObject(jforce, fp);
      Force force;
      force.f0 = vec3(member(jforce, fp, "f0"), fp + ".f0");
      rest(force, jforce, fp);
      forces.push_back(std::move(force));
    }
    return forces;
  }

  /// A frame's "forces": an array of {"f0", optional "region"}, each solvable on frame f.
  std::vector<FrameForce> frameForces(const Json& list, const std::string& path, const Frame& f,
                                      std::uint32_t frame) const {
    return forceList<FrameForce>(list, path,
                                 [&](FrameForce& force, const Json& jforce, const std::string& fp) {
                                   if (auto r = jforce.find("region"); r != jforce.end())
                                     force.region = region(*r, fp + ".region");
                                   checkSolvable(f, force.f0, force.region, fp, frame, false);
                                 });
  }

  /// The top-level "forces": an array of {"f0", "frames"}, frames listed once each, each
  /// force solvable on each of its frames (with the model's a1, a2 of that frame).
  std::vector<SharedForce> sharedForces(const Json& list, const std::string& path,
                                        const VertexFrameModel& model) const {
    return forceList<SharedForce>(
        list, path, [&](SharedForce& force, const Json& jforce, const std::string& fp) {
          const Json& frames = member(jforce, fp, "frames");
          expectArray(frames, fp + ".frames", 1);
          std::vector<std::uint8_t> seen(model.frames.size(), 0);
          for (std::size_t j = 0; j < frames.size(); ++j) {
            const std::string ip = fmt::format("{}.frames[{}]", fp, j);
            const std::uint32_t k = index(frames[j], ip, model.frames.size(), "frame", "frames");
            if (seen[k]) fail(ip, fmt::format("frame {} is listed twice", k));
            seen[k] = 1;
            checkSolvable(model.frames[k], force.f0, Region{}, fp, k, true);
            force.frames.push_back(k);
          }
        });
  }

 private:
  std::string source_;
};

/// A parsed document as a vertex-frames model (parseVertexFrameModel after the JSON syntax;
/// the dispatch on "type" in parseModel calls it on the document it already parsed).
VertexFrameModel parseVertexFrameDocument(const Json& doc, const Reader& rd);

}  // namespace pdesurf::detail
