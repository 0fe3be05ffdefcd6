// pdesurf::Error and the kinds beneath it that are more than a name (include/pdesurf/error.hpp).
#include "pdesurf/error.hpp"

#include <string_view>

namespace pdesurf {
namespace {

/// "FILE: $.path: message", the empty parts left out with their ": ".
std::string errorText(std::string_view file, std::string_view jsonPath, std::string_view message) {
  std::string text;
  for (std::string_view part : {file, jsonPath}) {
    if (part.empty()) continue;
    text += part;
    text += ": ";
  }
  return text += message;
}

}  // namespace

Error::Error(const std::string& message) : Error({}, {}, message) {}

Error::Error(const std::string& file, const std::string& jsonPath, const std::string& message)
    : std::runtime_error(errorText(file, jsonPath, message)),
      file_(file),
      jsonPath_(jsonPath),
      message_(message) {}

SectionError::SectionError(std::uint32_t section, const std::string& reason)
    : InvalidArgument("section " + std::to_string(section) + ": " + reason),
      section_(section),
      reason_(reason) {}

}  // namespace pdesurf
