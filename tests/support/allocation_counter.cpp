// The replacement operator new of support/allocation_counter.h: defined once per test
// program, never inline (a replacement must be).
#include "support/allocation_counter.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// GCC at -O1 (the sanitizer builds) takes the free() below for a mismatch with the
// replaced operator new, which is malloc() underneath.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace imagepro::test {

long allocationCount() { return g_allocations.load(); }

long allocationsOf(const std::function<void()>& work) {
  const long before = allocationCount();
  work();
  return allocationCount() - before;
}

}  // namespace imagepro::test
