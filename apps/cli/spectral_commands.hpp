// The CLI's commands of the spectral engine alone: fit and spine (docs/spectral.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::cli {

/// `fit`: the Fourier fit of every curve of a curves file with each number of terms.
std::string fitReport(const std::string& path, const std::vector<std::uint32_t>& terms,
                      bool chordLength, bool json);

/// `spine`: A0(u) of each patch, sampled at `count` points.
std::string spineJson(const SolvedSpectral& solved, std::uint32_t count);

}  // namespace pdesurf::cli
