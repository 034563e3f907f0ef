// Global allocation counter of stipple_alloc_tests: tests/alloc/alloc_counter.cpp replaces
// operator new there (and only there); the tests count around the code they check.
#pragma once
#include <atomic>

namespace stipple::test {
extern std::atomic<bool> g_counting;     // count operator new calls while true
extern std::atomic<long> g_allocations;  // calls counted so far
}  // namespace stipple::test
