// The models in examples/ for tests: their paths, and the spectral ones solved.
#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pdesurf/spectral_io.hpp"

namespace pdesurf::testing {

/// examples/FILE in the source tree ("mug.json").
inline std::string example(const std::string& file) {
  return (std::filesystem::path(PDESURF_SOURCE_DIR) / "examples" / file).string();
}

/// Every model file in examples/, sorted.
inline std::vector<std::string> exampleFiles() {
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(PDESURF_SOURCE_DIR) / "examples"))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

/// A spectral or cross-section model file, solved (std::logic_error for another type).
inline SolvedSpectral solveSpectralFile(const std::string& path) {
  const AnyModel model = loadModel(path);
  if (const auto* m = model.as<SpectralModel>()) return solve(*m, path);
  if (const auto* m = model.as<CrossSectionModel>()) return solve(*m, path);
  throw std::logic_error(path + " is not a spectral example");
}

}  // namespace pdesurf::testing
