#pragma once
// Counts heap allocations (malloc, calloc, realloc, posix_memalign and everything
// built on them: operator new, cv::Mat buffers) made by the whole process while
// counting is on. `imagepro-cli bench` uses it to show that the frame loop
// allocates nothing per frame in steady state.
#include <cstdint>

namespace imagepro::cli {

void startCountingAllocations();
// Stops counting and returns the number of allocations since the start.
std::uint64_t stopCountingAllocations();

}  // namespace imagepro::cli
