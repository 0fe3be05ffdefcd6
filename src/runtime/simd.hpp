// Run-time choice of the instruction set for the hot kernels (the tessellation's row kernel,
// batched polynomial evaluation). The library is compiled for x86-64-v2; each kernel is
// also compiled for x86-64-v3 (AVX2, FMA) and x86-64-v4 (AVX-512), and the widest level the
// CPU supports is called. The kernels' sources are compiled without floating-point
// contraction (-ffp-contract=off, CMakeLists.txt), so that every level rounds the same
// operations the same way: results are bit-identical whichever runs.
#pragma once

namespace pdesurf::detail {

enum class SimdLevel { kV2 = 2, kV3 = 3, kV4 = 4 };

/// The widest level this CPU supports (kV2 off x86-64, where one portable path serves).
SimdLevel cpuSimdLevel();
/// The level the kernels use: cpuSimdLevel(), or lower when the environment variable
/// PDESURF_SIMD is v2 or v3 (for tests and benchmarks), or as setSimdLevel last set it.
SimdLevel simdLevel();
/// Makes the kernels use `level`, capped at cpuSimdLevel(); returns the level now in use.
SimdLevel setSimdLevel(SimdLevel level);

/// Chooses one of three versions of a kernel by simdLevel().
template <class F>
F simdChoose(F v2, F v3, F v4) {
  switch (simdLevel()) {
    case SimdLevel::kV4:
      return v4;
    case SimdLevel::kV3:
      return v3;
    default:
      return v2;
  }
}

}  // namespace pdesurf::detail

// The attributes that compile a kernel's wrapper for one level; the kernel's body is
// always_inline, so it is compiled for the wrapper's level (ymm and zmm registers only there).
// A -DPDESURF_NATIVE=ON build compiles everything for its own processor: no levels there.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(PDESURF_NATIVE_BUILD)
#define PDESURF_TARGET_V3 __attribute__((target("arch=x86-64-v3")))
#define PDESURF_TARGET_V4 __attribute__((target("arch=x86-64-v4,prefer-vector-width=512")))
#else
#define PDESURF_TARGET_V3
#define PDESURF_TARGET_V4
#endif
#define PDESURF_ALWAYS_INLINE inline __attribute__((always_inline))
#define PDESURF_ALWAYS_INLINE_LAMBDA __attribute__((always_inline))
