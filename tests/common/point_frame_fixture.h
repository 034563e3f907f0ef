// The fixture of the frame-level point tests (tests/runtime/test_point_stages.cpp,
// test_point_clusters_frame.cpp): CesiumMan baked to 60k points and a headless GL context;
// TearDown restores the detected SIMD path, which these tests force either way.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "runtime/point_simd.h"
#include "tests/common/fixtures.h"

namespace stipple::test {

class Cesium60kFrame : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 60000"),
                               &asset_, &error))
            << error;
        ASSERT_TRUE(gl_.open(&error)) << error;
    }
    void TearDown() override { point_simd_force(point_simd_detected()); }

    Asset asset_;
    HeadlessGl gl_;
};

// Same length and the same bits.
inline bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * 4) == 0;
}

}  // namespace stipple::test
