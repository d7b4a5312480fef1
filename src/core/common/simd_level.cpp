#include "core/common/simd_level.h"

#include <algorithm>
#include <atomic>

namespace imagepro {

namespace {

SimdLevel detectSimdLevel() {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  // The AVX2 loops also use BMI1/BMI2 bit instructions (mask scans).
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2"))
    return SimdLevel::Avx2;
#endif
  return SimdLevel::Sse2;
}

std::atomic<SimdLevel> ceiling_level{SimdLevel::Avx2};

}  // namespace

SimdLevel simdLevel() {
  static const SimdLevel detected = detectSimdLevel();
  return std::min(detected, ceiling_level.load(std::memory_order_relaxed));
}

void setSimdCeiling(SimdLevel ceiling) { ceiling_level.store(ceiling, std::memory_order_relaxed); }

}  // namespace imagepro
