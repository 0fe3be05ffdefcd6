// A mesh rebuilt as a cross-section model (seed 002's purpose): slice it, prepare the
// sections (include/pdesurf/sections.hpp), fit each by a Fourier series and join them by
// the global C4 chain of sixth-order PDE patches. The result is an ordinary
// `"cross-sections"` model. docs/rebuild.md shows the command and its accuracy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/sections.hpp"
#include "pdesurf/spectral.hpp"
#include "pdesurf/spectral_model.hpp"

namespace pdesurf {

struct SectionRebuildOptions {
  /// Planes and the loop each keeps. Without `near` or `track`, a plane that cuts several
  /// closed loops is refused (which part is meant is the user's choice, not the largest).
  SliceOptions slice;
  /// Resampling and alignment; `direction` defaults to the slicing axis.
  SectionPrepOptions prep;
  /// Fourier modes of every section: a least-squares fit of the prepared points, no
  /// remainder (a smooth surface through the sections' smooth parts).
  std::uint32_t modes = 8;
  /// Exact interpolation: the model keeps the prepared points of every section and the
  /// remainder makes the surface pass through each of them (the loft's data, for a
  /// like-for-like comparison; far more storage). Off: the sections' M-mode fits.
  bool exact = false;
  double a = 1.0;  ///< the Fu operator's a in the chain parameter u ∈ [0, 1]
  ChainEnds ends = ChainEnds::Natural;
  std::string name, description;  ///< written into the model
};

struct SectionRebuild {
  std::vector<MeshSection> sections;   ///< as the slicer kept them
  std::vector<SampledCurve> prepared;  ///< aligned and resampled (prepareSections)
  CrossSectionModel model;             ///< what a model file holds
  CrossSectionChain chain;             ///< the model, solved
};

/// Throws MeshSliceError (a plane misses the mesh or cuts no closed loop) and
/// InvalidArgument naming the plane ("plane 3 at y=0.25: ...") for several loops
/// without near/track, a loop that is not simple, or (unless `exact`) one with fewer points
/// than M modes need (2M + 1: more modes would fit the straight edges between its points,
/// not the surface); InvalidArgument for bad options.
SectionRebuild rebuildFromSections(const Mesh& mesh, const SectionRebuildOptions& options);

/// Rows per patch and columns around v at which a rebuilt chain is tessellated to measure it
/// against its mesh (`pdesurf rebuild --as cross-sections`, the Python package's rebuild):
/// about 256 rows over the chain and 256 columns, so that the tessellation's own chord error
/// (below 1e-4 of a section's radius for 8 modes) stays far below the distances measured.
TessellateOptions chainMeasureOptions(std::size_t patches);

/// The surface of `mesh` that the sections rebuild: the triangles between the first and the
/// last plane (clipped to them) that are connected, within that slab, to the kept loops.
/// Other parts the planes cut (the other legs) are left out. Clip points are welded by the
/// edge they lie on, so the part is as watertight as the mesh.
Mesh sectionedPart(const Mesh& mesh, Axis axis, std::span<const MeshSection> sections);

}  // namespace pdesurf
