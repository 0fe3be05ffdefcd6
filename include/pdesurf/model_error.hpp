// The error of a model that is malformed, invalid or cannot be solved: thrown by the model
// files' parsers (io) and by the solvers' wrappers that name the model (engines).
#pragma once

#include <stdexcept>
#include <string>

namespace pdesurf {

/// A model file is malformed or invalid. what() reads "FILE: $.json.path: what is wrong".
class ModelError : public std::runtime_error {
 public:
  ModelError(const std::string& file, const std::string& jsonPath, const std::string& problem);
  const std::string& file() const { return file_; }
  const std::string& jsonPath() const { return jsonPath_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, jsonPath_, problem_;
};

}  // namespace pdesurf
