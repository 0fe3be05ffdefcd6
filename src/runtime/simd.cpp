// The SIMD level of the hot kernels (src/runtime/simd.hpp).
#include "runtime/simd.hpp"

#include <atomic>
#include <cstdlib>
#include <string_view>

namespace pdesurf::detail {

namespace {

SimdLevel detect() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return SimdLevel::kV4;
  if (__builtin_cpu_supports("x86-64-v3")) return SimdLevel::kV3;
#endif
  return SimdLevel::kV2;
}

SimdLevel lower(SimdLevel a, SimdLevel b) {
  return static_cast<int>(a) < static_cast<int>(b) ? a : b;
}

/// The level asked for by PDESURF_SIMD (v2, v3, v4), capped at the CPU's.
SimdLevel initial() {
  SimdLevel level = cpuSimdLevel();
  if (const char* env = std::getenv("PDESURF_SIMD")) {
    const std::string_view asked(env);
    if (asked == "v2") level = SimdLevel::kV2;
    if (asked == "v3") level = lower(level, SimdLevel::kV3);
  }
  return level;
}

std::atomic<SimdLevel>& current() {
  static std::atomic<SimdLevel> level{initial()};
  return level;
}

}  // namespace

SimdLevel cpuSimdLevel() {
  static const SimdLevel level = detect();
  return level;
}

SimdLevel simdLevel() { return current().load(std::memory_order_relaxed); }

SimdLevel setSimdLevel(SimdLevel level) {
  const SimdLevel used = lower(level, cpuSimdLevel());
  current().store(used, std::memory_order_relaxed);
  return used;
}

}  // namespace pdesurf::detail
