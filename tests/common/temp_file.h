// A path in the test temp directory that no other test process shares: ctest runs tests in
// parallel processes, so a fixed name ("checker.gltf") is a race between two tests that
// write it. The process id keeps each test's files its own.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

namespace stipple::test {

inline std::string temp_file(const std::string& name) {
    return ::testing::TempDir() + "stipple_" + std::to_string(::getpid()) + "_" + name;
}

}  // namespace stipple::test
