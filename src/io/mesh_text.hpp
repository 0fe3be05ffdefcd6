// The text and byte helpers that the mesh readers of src/io share (mesh_read_obj.cpp,
// mesh_read_ply.cpp, mesh_read_glb.cpp): tokens and numbers with the line they stand on,
// binary values of either byte order, and where in a file a value belongs, for errors.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "io/mesh_read.hpp"

namespace pdesurf::detail {

inline std::string errnoText(int error) { return std::generic_category().message(error); }

inline std::string lowercase(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return result;
}

inline bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && lowercase(a) == lowercase(b);
}

/// Where in a file a value belongs ("vertex 3", "face 12", "header"), for error messages.
struct Where {
  std::string_view kind;
  std::size_t index = std::numeric_limits<std::size_t>::max();
};

inline std::string describe(const Where& where) {
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
    throw MeshIoError(
        path_, fmt::format("line {}: {}", line_, fmt::format(format, std::forward<Args>(args)...)));
  }

  [[noreturn]] void failAtEnd(const Where& where) const {
    detail::fail(path_, "unexpected end of file in {}", describe(where));
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
inline void appendFan(const std::vector<std::uint32_t>& corners,
                      MeshBuffer<std::uint32_t>& indices) {
  for (std::size_t i = 1; i + 1 < corners.size(); ++i)
    indices.insert(indices.end(), {corners[0], corners[i], corners[i + 1]});
}

}  // namespace pdesurf::detail
