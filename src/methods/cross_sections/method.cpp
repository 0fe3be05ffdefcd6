// The "cross-sections" method (include/pdesurf/method.hpp): its description, a spectral one
// (spectral/method.hpp: the chain is solved as SolvedSpectral), with its shape edits
// (cross_sections/edits.hpp).
#include "methods/spectral/method.hpp"

#include "methods/cross_sections/edits.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::detail {

const SurfaceMethod& crossSectionsMethod() {
  static const SpectralMethod<CrossSectionModel> method(kCrossSectionEdits, "cross-sections",
                                                        parseCrossSectionsDocument);
  return method;
}

}  // namespace pdesurf::detail
