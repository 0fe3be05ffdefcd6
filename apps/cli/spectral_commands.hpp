// The CLI's side of the spectral engine: build, sample and info of "spectral" and
// "cross-sections" models, and the fit and spine commands (docs/spectral.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::cli {

/// `sample`: {"patches": [{"patch": k, "grid": N, "u": [u0, u1], "points": [...]}]} with
/// points[j*N+i] = S(u0 + (u1 − u0) i/(N−1), 2π j/(N−1)).
std::string sampleJson(const SolvedSpectral& solved, std::uint32_t grid);

/// `info` for spectral and cross-section models (text or JSON).
std::string infoText(const SolvedSpectral& solved, const std::string& path, const std::string& name,
                     bool json);

/// `fit`: the Fourier fit of every curve of a curves file with each number of terms.
std::string fitReport(const std::string& path, const std::vector<std::uint32_t>& terms,
                      bool chordLength, bool json);

/// `spine`: A0(u) of each patch, sampled at `count` points.
std::string spineJson(const SolvedSpectral& solved, std::uint32_t count);

}  // namespace pdesurf::cli
