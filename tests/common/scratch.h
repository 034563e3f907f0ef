// Scratch files of the tests: one directory per test process, <TempDir>/stipple_<pid>/,
// removed with everything in it when the process exits, so a test run leaves nothing in /tmp.
// Per process: ctest runs the tests in parallel processes, and a fixed name would be a race
// between two of them. Removed at exit, not after each test: a test hands its paths to the
// tools it runs, and a suite's files outlive its tests (SetUpTestSuite).
#pragma once

#include <gtest/gtest.h>
#include <sys/types.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

namespace stipple::test {

namespace detail {

// The process's scratch directory. Kept when a test failed, for what it left to look at (a
// golden frame's actual image and diff); its path is then printed.
class ProcessScratch {
  public:
    ProcessScratch()
        : owner_(::getpid()),
          path_(std::filesystem::path(::testing::TempDir()) /
                ("stipple_" + std::to_string(owner_))) {
        // gtest's instance is built before this one, so it is destroyed after it (and can
        // still say whether a test failed).
        ::testing::UnitTest::GetInstance();
        std::filesystem::remove_all(path_);  // left by a crashed process of the same pid
        std::filesystem::create_directories(path_);
    }
    ~ProcessScratch() {
        if (::getpid() != owner_) return;  // a forked child exiting: the files are the parent's
        if (::testing::UnitTest::GetInstance()->Failed()) {
            std::fprintf(stderr, "scratch files kept (a test failed): %s\n", path_.c_str());
            return;
        }
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ProcessScratch(const ProcessScratch&) = delete;
    ProcessScratch& operator=(const ProcessScratch&) = delete;

    const std::filesystem::path& path() const { return path_; }

  private:
    pid_t owner_;
    std::filesystem::path path_;
};

}  // namespace detail

// `name` inside the process's scratch directory (made on first use). `name` may hold
// subdirectories; the caller makes them.
inline std::string scratch_path(const std::string& name) {
    static const detail::ProcessScratch dir;
    return (dir.path() / name).string();
}

}  // namespace stipple::test
