#pragma once
// Counts heap allocations (malloc, calloc, realloc, posix_memalign and everything
// built on them: operator new, cv::Mat buffers) made by the whole process while
// counting is on. `imagepro-cli bench` uses it to show that the frame loop
// allocates nothing per frame in steady state.
//
// Counting replaces malloc and its kin for the whole process. A sanitizer build
// (ASan, TSan, MSan, LSan) must own those itself, so there the replacement is left
// out and nothing is counted: allocationCountingAvailable() says which build this
// is. CMake's IMAGEPRO_COUNT_ALLOCATIONS=OFF leaves it out of any build.
#include <cstdint>

namespace imagepro::cli {

// False when this build counts nothing (a sanitizer build, or counting switched off).
bool allocationCountingAvailable();
void startCountingAllocations();
// Stops counting and returns the number of allocations since the start (0 when
// counting is not available, which the first start says on stderr).
std::uint64_t stopCountingAllocations();

}  // namespace imagepro::cli
