#pragma once
// Counts every allocation of the test executable that includes this header (once, in its only
// source file): the global operator new is replaced. For tests that a loop allocates nothing.
#include <atomic>
#include <cstdlib>
#include <new>

namespace test_support {
inline std::atomic<long> g_allocations{0};
}  // namespace test_support

void* operator new(std::size_t size) {
  test_support::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
