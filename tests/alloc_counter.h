// Global allocation counter shared by the tests. All tests/test_*.cpp link into one binary,
// so exactly one translation unit (test_frame_allocation.cpp) replaces operator new and
// defines these; others include this header and count around the code they check.
#pragma once
#include <atomic>

namespace stipple::test {
extern std::atomic<bool> g_counting;    // count operator new calls while true
extern std::atomic<long> g_allocations; // calls counted so far
}  // namespace stipple::test
