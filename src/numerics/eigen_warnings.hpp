// Included first by every spectral source file. GCC 12 reports false "may be used
// uninitialized" warnings inside its own AVX-512 intrinsics (avx512fintrin.h's
// `__m512d __Y = __Y;`, GCC bug 105593, fixed in GCC 13) whenever Eigen's QR and
// matrix products are inlined with -march=native. The pragma must precede the first
// inclusion of Eigen, because the diagnostic state is taken at the header's location.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
