// How `compare` and `rebuild` print the distances between a model and a mesh.
#pragma once

#include <utility>

#include <fmt/format.h>

#include "pdesurf/mesh_distance.hpp"

namespace pdesurf::cli {

/// "1.23%" for a distance relative to the bounding-box diagonal.
inline std::string percent(double relative) { return fmt::format("{:.3g}%", 100.0 * relative); }

/// Both one-way distances and the Hausdorff distance, one line each.
inline void printDistances(const MeshDistance& d) {
  for (const auto& [label, w] : {std::pair{"model -> mesh", &d.aToB}, {"mesh -> model", &d.bToA}})
    fmt::print("{}  RMS {:.6g} ({})  mean {:.6g} ({})  max {:.6g} ({})\n", label, w->rms,
               percent(w->rmsRelative), w->mean, percent(w->meanRelative), w->max,
               percent(w->maxRelative));
  fmt::print("Hausdorff      {:.6g} ({})\n", d.hausdorff, percent(d.hausdorffRelative));
}

}  // namespace pdesurf::cli
