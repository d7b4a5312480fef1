#include "cli/allocation_counter.h"

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <mutex>

// Sanitizers replace malloc themselves (ASan's start-up dies in dlsym when the
// executable interposes it first): their builds count nothing.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define IMAGEPRO_SANITIZER_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(leak_sanitizer)
#define IMAGEPRO_SANITIZER_BUILD 1
#endif
#endif

#if defined(IMAGEPRO_SANITIZER_BUILD) || defined(IMAGEPRO_NO_ALLOCATION_COUNTING)
#define IMAGEPRO_COUNTING 0
#else
#define IMAGEPRO_COUNTING 1
#endif

namespace {
std::atomic<bool> gCounting{false};
std::atomic<std::uint64_t> gCount{0};

[[maybe_unused]] inline void note() {
  if (gCounting.load(std::memory_order_relaxed)) gCount.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if IMAGEPRO_COUNTING
// glibc's own entry points, which the definitions below forward to. Defining malloc
// and friends in the executable interposes them for every library in the process.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t n, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* p);
}

extern "C" {
void* malloc(std::size_t size) {
  note();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  note();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  note();
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  note();
  void* p = __libc_memalign(alignment, size);
  if (!p && size != 0) return ENOMEM;
  *out = p;
  return 0;
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  note();
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  note();
  return __libc_memalign(alignment, size);
}
}
#endif

namespace imagepro::cli {

bool allocationCountingAvailable() { return IMAGEPRO_COUNTING != 0; }

void startCountingAllocations() {
  // Said once, so a report's "allocations: 0" is not read as measured.
  static std::once_flag told;
  if (!allocationCountingAvailable())
    std::call_once(told, [] {
      std::fprintf(stderr, "note: this build does not count heap allocations (a sanitizer owns malloc, or "
                           "IMAGEPRO_COUNT_ALLOCATIONS=OFF): allocation figures read 0\n");
    });
  gCount.store(0);
  gCounting.store(true);
}

std::uint64_t stopCountingAllocations() {
  gCounting.store(false);
  return gCount.load();
}

}  // namespace imagepro::cli
