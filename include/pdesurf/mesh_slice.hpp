// Cross sections of triangle meshes by parallel planes: each plane's largest closed loop,
// as the curves a cross-section model is built from (docs/mesh-tools.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf {

using Vec3 = Eigen::Vector3d;

/// A coordinate axis; slicing planes are perpendicular to it.
enum class Axis { X, Y, Z };

/// "x", "y" or "z".
const char* axisName(Axis axis);

/// The axis named "x", "y" or "z" (lower or upper case); nullopt for anything else.
std::optional<Axis> parseAxis(const std::string& name);

struct SliceOptions {
  Axis axis = Axis::Z;
  /// Number of planes K ≥ 1, evenly spaced.
  std::uint32_t count = 10;
  /// [a, b] with a < b (a ≤ b when count is 1): plane i at a + i (b - a) / (K - 1), so the
  /// end planes lie at a and b exactly (one plane: at (a + b) / 2). Default (nullopt): the
  /// mesh's extent [lo, hi] along the axis cut into K equal slabs, plane i in the middle of
  /// slab i, at lo + (i + ½)(hi - lo) / K, so that every plane cuts the mesh.
  std::optional<std::pair<double, double>> range;
  /// Which closed loop each plane keeps. Default (neither set): the largest by enclosed
  /// area. With `near`: the loop whose area centroid is nearest to `near` projected onto the
  /// plane (distances measured in the plane). With `track`: plane 0 keeps the loop chosen by
  /// the rule above (nearest to `near` if given, else the largest) and every later plane the
  /// loop whose centroid is nearest to the previous plane's kept centroid projected onto it,
  /// so that a curving part (an elephant's trunk) is followed plane by plane. A plane through
  /// several parts (four legs) thus gives the same part on every plane.
  std::optional<Vec3> near;
  bool track = false;
};

/// One plane's kept closed loop (the largest, or the one SliceOptions::near / track pick).
struct MeshSection {
  std::uint32_t index = 0;  ///< plane index, 0 … K-1
  double coordinate = 0.0;  ///< the plane: {p : p[axis] = coordinate}
  /// The loop as an ordered polyline, closed implicitly (the last point joins the first),
  /// without repeated consecutive points. Counter-clockwise seen from the axis' positive
  /// side (looking towards -axis): positive signed area in the plane. Every point has
  /// p[axis] == coordinate exactly.
  std::vector<Vec3> points;
  double length = 0.0;  ///< perimeter, closing segment included
  double area = 0.0;    ///< enclosed area in the plane (shoelace formula), > 0
  /// Area centroid of the loop (in the plane). Not part of the CLI's JSON.
  Vec3 centroid = Vec3::Zero();
  /// Number of closed (non-degenerate) loops the plane cut, the kept one included.
  std::uint32_t loops = 0;
};

/// The planes' coordinates for `options` on a mesh whose extent along the axis is [lo, hi]
/// (the rule documented at SliceOptions::range). Throws InvalidArgument for a count
/// of 0 or a range that is not finite or has a > b (a == b with more than one plane).
std::vector<double> slicePlanes(const SliceOptions& options, double lo, double hi);

/// Cuts `mesh` by the planes of `options` and returns, for each plane, one closed loop: the
/// largest by enclosed area, or the one picked by SliceOptions::near / track.
///
/// The cut is exact in topology: a loop's points are the intersections of the plane with
/// mesh edges, welded by edge (vertex indices), never by distance, so loops close exactly.
/// Vertices on the plane are handled by symbolic perturbation: they count as lying above
/// it (the plane is moved an infinitesimal step towards -axis), except for a plane at the
/// mesh's lowest coordinate, where they count as lying below. So a plane through vertices
/// or along edges gets a well-defined section, and a face in the plane is not a loop.
/// Chains that do not close (at the border of an open mesh) are ignored; a non-manifold
/// edge joins the chains through it greedily, preferring the mesh's orientation.
///
/// Throws MeshSliceError when a plane meets no triangle ("plane 3 at z=2.5 does not meet
/// the mesh (extent z in [0, 2])") or has no closed loop (only open chains); and
/// InvalidArgument for bad options (see slicePlanes; a `near` point that is not
/// finite).
std::vector<MeshSection> sliceMesh(const Mesh& mesh, const SliceOptions& options);

}  // namespace pdesurf
