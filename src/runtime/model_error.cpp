// ModelError (include/pdesurf/model_error.hpp).
#include "pdesurf/model_error.hpp"

#include <fmt/format.h>

namespace pdesurf {

ModelError::ModelError(const std::string& file, const std::string& jsonPath,
                       const std::string& problem)
    : std::runtime_error(jsonPath.empty() ? fmt::format("{}: {}", file, problem)
                                          : fmt::format("{}: {}: {}", file, jsonPath, problem)),
      file_(file),
      jsonPath_(jsonPath),
      problem_(problem) {}

}  // namespace pdesurf
