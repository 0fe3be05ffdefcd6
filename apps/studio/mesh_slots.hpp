// The page's surface meshes (GET /api/mesh, and an edit's `?mesh=1`): one slot per resolution
// it last asked for, each with the tessellator that makes its meshes and the last mesh sent,
// the base of the next delta at that resolution. No HTTP here: the routes send the bytes.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "pdesurf/model.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::studio {

/// A mesh for the page: the bytes of mesh_wire.hpp (whole, or a delta against `base`) and
/// what the answer's headers say.
struct MeshAnswer {
  std::string bytes;
  std::uint64_t id = 0;    ///< X-Mesh-Id: names this mesh in the page's next `base`
  std::uint64_t base = 0;  ///< X-Mesh-Base: the mesh a delta applies to, 0 for a whole mesh
  double solveMs = 0.0, tessellateMs = 0.0;
  double c0Gap = 0.0;  ///< the largest C0 gap of the solved model (X-C0-Gap)
};

class MeshSlots {
 public:
  /// Resolutions whose last mesh is kept as a delta base: a gesture's preview and the chosen
  /// resolution (web/src/preview.ts), so the release comes back as a delta against the last
  /// full-resolution mesh.
  static constexpr std::size_t kSlots = 2;

  /// The surface of the session's model at `resolution`, solved with `options`: whole, or,
  /// when `base` is the last mesh sent at this resolution and only positions and normals
  /// changed, a delta against it. `revision` is written in the mesh's header.
  MeshAnswer mesh(ModelSession& session, std::uint64_t revision, std::uint32_t resolution,
                  std::uint64_t base, const SolveOptions& options);

  /// The last mesh sent at `resolution` if it is the surface of `revision` solved with
  /// `options` (revisions are never reused while the server runs), else nullptr: the routes
  /// that describe the page's mesh (its triangles' patches, its curvature) read it instead of
  /// tessellating the model again.
  const Mesh* sent(std::uint32_t resolution, std::uint64_t revision,
                   const SolveOptions& options) const;

 private:
  struct Slot {
    std::uint32_t resolution = 0;  // 0: unused
    ModelTessellator tessellator;
    Mesh sent;
    std::uint64_t sentLayout = 0;  // the tessellator's layout of `sent`
    std::uint64_t sentId = 0;      // X-Mesh-Id of `sent`
    std::uint64_t sentRevision = 0;
    SolveOptions sentOptions;  // how the model of `sent` was solved
    std::uint64_t used = 0;    // when it last served (the least recent is reused)
  };

  /// The slot of `resolution`, else the least recently used one, emptied for it.
  Slot& slot(std::uint32_t resolution);

  std::array<Slot, kSlots> slots_;
  std::uint64_t clock_ = 0;
  // Mesh ids are never reused while the server runs, so a client's `base` names exactly one
  // mesh, across resolutions and opened models too.
  std::uint64_t counter_ = 0;
};

}  // namespace pdesurf::studio
