// The grids of one disk-like mesh (gridLayout, include/pdesurf/rebuild.hpp): the mesh
// parameterised onto the square once, then any number of U × V grids laid through it. The
// target search (src/fit/auto_rebuild.cpp) tries several grid sizes on one mesh.
#pragma once

#include <memory>
#include <string>

#include "pdesurf/mesh.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::detail {

class DiskGrids {
 public:
  /// Parameterises `disk` onto the unit square. Throws LayoutError (naming `source`) when
  /// the mesh is not a manifold disk or the parameterisation fails.
  DiskGrids(const Mesh& disk, const std::string& source);
  ~DiskGrids();
  DiskGrids(const DiskGrids&) = delete;
  DiskGrids& operator=(const DiskGrids&) = delete;

  /// The U × V grid of frames (options.u, options.v at least 1).
  VertexFrameModel grid(const GridLayoutOptions& options) const;

 private:
  struct Map;
  std::unique_ptr<Map> map_;
};

}  // namespace pdesurf::detail
