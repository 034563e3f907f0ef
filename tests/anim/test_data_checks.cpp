// Load-time content checks of anim/: check_clip, check_skeleton, check_morph name the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "anim/anim.h"
#include "tests/common/anim_builders.h"

namespace {

using namespace stipple::anim;
using namespace stipple::test;

TEST(AnimDataChecks, RejectNamedProblems) {
    const std::vector<float> times = {0, 1};
    const std::vector<float> bad_times = {1, 1};
    const std::vector<float> values = {0, 0, 0, 1, 1, 1};
    const std::vector<float> nan_values = {0, 0, 0, 1, std::nanf(""), 1};
    uint32_t bad = 0;
    std::vector<Channel> c = {channel(0, Path::translation, Interp::linear, times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::ok);
    EXPECT_EQ(check_clip(make_clip(c, 1), 0, 0, &bad), DataError::node_out_of_range);
    c = {channel(0, Path::translation, Interp::linear, bad_times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::times_not_increasing);
    c = {channel(0, Path::translation, Interp::linear, times, nan_values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::non_finite_value);
    c = {channel(0, Path(7), Interp::linear, times, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::bad_path);
    c = {channel(0, Path::translation, Interp::linear, {}, values)};
    EXPECT_EQ(check_clip(make_clip(c, 1), 1, 0, &bad), DataError::no_keys);
    EXPECT_STREQ(data_error_name(DataError::times_not_increasing), "times_not_increasing");

    const std::vector<int32_t> parents = {-1, 1};
    const std::vector<Trs> rest = {identity_trs(), identity_trs()};
    EXPECT_EQ(check_skeleton(make_skeleton(parents, rest)), DataError::parent_out_of_range);
    const std::vector<float> deltas = {1, 1, 1};
    const MorphTarget target{0, 2, 1, deltas.data(), nullptr};
    const float w = 0;
    const Morph morph{1, &w, 1, &target};
    EXPECT_EQ(check_morph(morph, 3), DataError::ok);
    EXPECT_EQ(check_morph(morph, 2), DataError::target_out_of_range);
}

}  // namespace
