// Which vector instructions the pixel loops may use. The loops are built for SSE2
// (every x86-64 processor) and, where the compiler allows, for AVX and AVX2, and pick
// the widest the processor has at run time. Every path gives the same result; tests
// lower the ceiling to run the narrower paths on a wide processor and compare.
#pragma once

namespace imagepro {

enum class SimdLevel { Sse2, Avx, Avx2 };

// The widest level the processor supports, capped by setSimdCeiling.
SimdLevel simdLevel();

// Caps simdLevel() (for tests and side-by-side benchmarks); SimdLevel::Avx2 lifts the cap.
void setSimdCeiling(SimdLevel ceiling);

}  // namespace imagepro
