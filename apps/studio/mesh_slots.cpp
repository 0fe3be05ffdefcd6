// The page's surface meshes (mesh_slots.hpp).
#include "mesh_slots.hpp"

#include <chrono>

#include "mesh_wire.hpp"

namespace pdesurf::studio {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

MeshSlots::Slot& MeshSlots::slot(std::uint32_t resolution) {
  Slot* pick = &slots_.front();
  for (Slot& s : slots_) {
    if (s.resolution == resolution) {
      pick = &s;
      break;
    }
    if (s.used < pick->used) pick = &s;
  }
  if (pick->resolution != resolution) {
    *pick = Slot{};
    pick->resolution = resolution;
  }
  pick->used = ++clock_;
  return *pick;
}

MeshAnswer MeshSlots::mesh(ModelSession& session, std::uint64_t revision, std::uint32_t resolution,
                           std::uint64_t base, const SolveOptions& options) {
  MeshAnswer out;
  Slot& s = slot(resolution);
  auto t0 = Clock::now();
  const SolvedModel& solved = session.solved(options);  // view-only: solved when changed
  out.solveMs = msSince(t0);
  t0 = Clock::now();
  const Mesh& mesh = s.tessellator.tessellate(solved, {resolution});
  out.tessellateMs = msSince(t0);
  out.c0Gap = largestC0Gap(solved);
  // Same triangles: the tessellator's layout says so (for vertex frames without comparing
  // the index buffers: the drag's hot path).
  const std::uint64_t layout = s.tessellator.layoutVersion();
  const bool delta = base != 0 && base == s.sentId && layout == s.sentLayout;
  out.bytes = delta ? encodeMeshDelta(s.sent, mesh, revision, resolution)
                    : encodeMesh(mesh, revision, resolution);
  s.sent = mesh;  // what the client now has (copies reuse sent's buffers)
  s.sentLayout = layout;
  s.sentId = ++counter_;
  s.sentRevision = revision;
  s.sentOptions = options;
  out.id = s.sentId;
  out.base = delta ? base : 0;
  return out;
}

const Mesh* MeshSlots::sent(std::uint32_t resolution, std::uint64_t revision,
                            const SolveOptions& options) const {
  for (const Slot& s : slots_)
    if (s.resolution == resolution && s.sentId != 0 && s.sentRevision == revision &&
        s.sentOptions == options)
      return &s.sent;
  return nullptr;
}

}  // namespace pdesurf::studio
