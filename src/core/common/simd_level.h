// Which vector instructions the pixel loops may use. The loops are built for SSE2
// (every x86-64 processor) and, where the compiler allows, for AVX and AVX2, and pick
// the widest the processor has at run time. Every path gives the same result; tests
// lower the ceiling to run the narrower paths on a wide processor and compare.
//
// One pattern for the loops written once for several widths: the loop's text is a
// <name>_pass.inc file (no include guard), written against a struct Ops that gives its
// vector type and operations. The source file includes it once per width, inside a
// namespace sse2 and a namespace avx2 that each define their Ops, the avx2 one between
// IMAGEPRO_AVX2_BEGIN and IMAGEPRO_AVX2_END; at run time it calls
// avx2::f when simdAllows(SimdLevel::Avx2), else sse2::f.
#pragma once

namespace imagepro {

enum class SimdLevel { Sse2, Avx2 };

// The widest level the processor supports, capped by setSimdCeiling.
SimdLevel simdLevel();

// Caps simdLevel() (for tests and side-by-side benchmarks); SimdLevel::Avx2 lifts the cap.
void setSimdCeiling(SimdLevel ceiling);

// Whether the code built for `level` may run: the processor has it and no ceiling lies
// below it. The one run-time test the loops make.
inline bool simdAllows(SimdLevel level) { return simdLevel() >= level; }

}  // namespace imagepro

// The code between these is compiled for AVX2 and the bit instructions that go with it
// (BMI1, BMI2: simdLevel() reports Avx2 only with them), whatever the build's own target.
#define IMAGEPRO_AVX2_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,bmi,bmi2\")")
#define IMAGEPRO_AVX2_END _Pragma("GCC pop_options")
