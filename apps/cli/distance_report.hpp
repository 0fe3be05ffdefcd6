// How `compare` and `rebuild` print the distances between a model and a mesh.
#pragma once

#include <string>

#include <fmt/format.h>

#include "pdesurf/mesh_distance.hpp"

namespace pdesurf::cli {

/// "1.23%" for a distance relative to the bounding-box diagonal.
inline std::string percent(double relative) { return fmt::format("{:.3g}%", 100.0 * relative); }

/// One direction's RMS, mean and largest distance, absolute (`digits` significant) and
/// relative, on one line.
inline void printOneWay(const char* label, const OneWayDistance& w, int digits = 6) {
  fmt::print("{}  RMS {:.{}g} ({})  mean {:.{}g} ({})  max {:.{}g} ({})\n", label, w.rms, digits,
             percent(w.rmsRelative), w.mean, digits, percent(w.meanRelative), w.max, digits,
             percent(w.maxRelative));
}

/// Both one-way distances and the Hausdorff distance, one line each.
inline void printDistances(const MeshDistance& d) {
  printOneWay("model -> mesh", d.aToB);
  printOneWay("mesh -> model", d.bToA);
  fmt::print("Hausdorff      {:.6g} ({})\n", d.hausdorff, percent(d.hausdorffRelative));
}

}  // namespace pdesurf::cli
