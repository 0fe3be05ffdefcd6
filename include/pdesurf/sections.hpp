// Closed cross-section curves taken as they come (from a slicer, a scanner, a user) made
// ready for a cross-section chain: cleaned, checked, oriented alike, resampled by arc length
// and aligned so that v = 0 runs along the chain without twist (docs/spectral.md,
// "Sections taken as they come").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pdesurf/error.hpp"
#include "pdesurf/spectral.hpp"

namespace pdesurf {

struct SectionPrepOptions {
  /// Points per prepared section, evenly spaced by arc length (≥ 8). A Fourier fit of M
  /// modes needs at least 2M + 1 of them; 4× that keeps the fit a least-squares smoother.
  std::uint32_t points = 128;
  /// The direction the chain runs in (e.g. the slicing axis): every section is oriented
  /// counter-clockwise seen from its tip. Default: the direction between the neighbouring
  /// sections' centroids.
  std::optional<Vec3> direction;
  /// Where v = 0 sits on the first section: where the ray from its centroid along this
  /// direction (projected into the section's plane) leaves it. Default: the coordinate axis
  /// most perpendicular to the chain's first step.
  std::optional<Vec3> reference;
};

/// The sections, cleaned and checked (≥ 3 distinct finite points, enclosed area, simple:
/// no two non-adjacent edges meet), each oriented counter-clockwise about the chain
/// direction, resampled to `points` points at equal arc length with v_j = 2πj / points,
/// the first one starting on the reference ray, every later one rotated (continuously,
/// along its arc length) to the start that minimises Σ_j |q_j − c_q − (p_j − c_p)|² /
/// (r_p r_q) against its predecessor p (centroids c, RMS radii r): the least twist.
/// A point that repeats its predecessor, and a last point equal to the first, are dropped.
/// Throws SectionError for a bad section, InvalidArgument for bad options.
std::vector<SampledCurve> prepareSections(std::span<const std::vector<Vec3>> loops,
                                          const SectionPrepOptions& options = {});

}  // namespace pdesurf
