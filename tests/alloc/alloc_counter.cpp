// Replaces the global operator new / delete for the allocation tests (stipple_alloc_tests
// only: no other test executable links this file) and defines the counters of
// tests/alloc/alloc_counter.h.
#include "tests/alloc/alloc_counter.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace stipple::test {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace stipple::test
using stipple::test::g_allocations;
using stipple::test::g_counting;

void* operator new(std::size_t size) {
    if (g_counting) ++g_allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
    return operator new(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    if (g_counting) ++g_allocations;
    return std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
    return operator new(size, tag);
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}
