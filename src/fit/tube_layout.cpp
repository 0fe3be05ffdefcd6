// A tube-like part as R × S frames on its aligned sections (include/pdesurf/tube_layout.hpp).
#include "pdesurf/tube_layout.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "fit/lattice_frame.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/sections.hpp"

namespace pdesurf {

namespace {

/// prepareSections resamples a loop to at least this many points; coarser rings take every
/// m-th of a finer resampling (the same arc-length positions).
constexpr std::uint32_t kMinPreparedPoints = 8;

}  // namespace

TubeLayout tubeLayout(const Mesh& mesh, const TubeLayoutOptions& options,
                      const std::string& source) {
  if (options.rings < 1 || options.sectors < 3)
    throw LayoutError(
        source,
        fmt::format("a tube needs at least 1 ring and 3 sectors of frames (two sectors would "
                    "join along both sides) (got {} × {})",
                    options.rings, options.sectors));
  SliceOptions slice = options.slice;
  slice.count = 2 * options.rings + 1;
  const int k = static_cast<int>(slice.axis);
  if (!slice.range) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
      lo = std::min(lo, double(mesh.positions[3 * v + k]));
      hi = std::max(hi, double(mesh.positions[3 * v + k]));
    }
    if (!(lo < hi))
      throw LayoutError(source,
                        fmt::format("the mesh has no extent along {}", axisName(slice.axis)));
    slice.range = {lo, hi};
  }
  TubeLayout out;
  const bool chosen = slice.near.has_value() || slice.track;
  auto plane = [&](const MeshSection& s) {
    return fmt::format("plane {} at {}={}", s.index, axisName(slice.axis), s.coordinate);
  };
  try {
    out.sections = sliceMesh(mesh, slice);
  } catch (const std::exception& e) {
    throw LayoutError(source, e.what());
  }
  std::vector<std::vector<Vec3>> loops;
  for (const MeshSection& s : out.sections) {
    if (!chosen && s.loops > 1)
      throw LayoutError(
          source,
          fmt::format(
              "{} cuts {} closed loops (separate parts of the mesh): choose the part with --near X "
              "Y Z, and --track to follow it from plane to plane",
              plane(s), s.loops));
    loops.push_back(s.points);
  }
  const std::uint32_t perRing = 2 * options.sectors;
  const std::uint32_t every = (kMinPreparedPoints + perRing - 1) / perRing;
  SectionPrepOptions prep;
  prep.points = perRing * every;
  prep.direction = Vec3::Unit(k);
  std::vector<SampledCurve> prepared;
  try {
    prepared = prepareSections(loops, prep);
  } catch (const SectionError& e) {
    throw LayoutError(source, plane(out.sections.at(e.section())) + ": the loop " + e.reason());
  }

  // Lattice point (j, i): point j of ring i. Only the points frames use become vertices
  // (not the frames' centres), numbered as the frames first reach them.
  VertexFrameModel& model = out.model;
  const std::uint32_t ringCount = 2 * options.rings + 1;
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> index(std::size_t{perRing} * ringCount, kUnused);
  auto at = [&](std::uint32_t j, std::uint32_t i) {
    j %= perRing;  // closed round the tube: the last sector's edge is the first's
    std::uint32_t& v = index[std::size_t{i} * perRing + j];
    if (v == kUnused) {
      v = static_cast<std::uint32_t>(model.vertices.size());
      model.vertices.push_back(prepared[i].points[j * every]);
    }
    return v;
  };
  for (std::uint32_t r = 0; r < options.rings; ++r)
    for (std::uint32_t s = 0; s < options.sectors; ++s)
      model.frames.push_back(detail::latticeFrame(at, 2 * s, 2 * r));
  out.part = sectionedPart(mesh, slice.axis, out.sections);
  return out;
}

}  // namespace pdesurf
