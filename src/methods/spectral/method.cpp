// The "spectral" method (include/pdesurf/method.hpp): its description (spectral/method.hpp)
// with its shape edits (spectral/edits.hpp).
#include "methods/spectral/method.hpp"

#include "methods/spectral/edits.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::detail {

const SurfaceMethod& spectralMethod() {
  static const SpectralMethod<SpectralModel> m(kSpectralEdits, "spectral", parseSpectralDocument);
  return m;
}

}  // namespace pdesurf::detail
