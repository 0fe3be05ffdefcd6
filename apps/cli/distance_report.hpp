// How `compare` and `rebuild` print the distances between a model and a mesh, and how
// the model's normals agree with the mesh's.
#pragma once

#include <string>

#include <fmt/format.h>

#include "cli_common.hpp"
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

/// The model's normals against the mesh's (normalDeviation): its folded area and RMS normal
/// deviation, on one line.
inline void printNormals(const NormalDeviation& n) {
  fmt::print("normals        folded {:.3g}% of the model's area, RMS deviation {:.3g}°{}\n",
             100.0 * n.foldedArea, n.rmsDegrees,
             n.reversed ? " (the model faces the other way, taken as it faces)" : "");
}

}  // namespace pdesurf::cli
