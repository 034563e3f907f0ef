// The kiosk window's key handler (tools/kiosk_keys.h): every key's effect and its limits.
#include <gtest/gtest.h>

#include "tools/kiosk_keys.h"

namespace {

using stipple::platform::Key;
using stipple::play::apply_key;
using stipple::play::KioskLimits;
using stipple::play::KioskState;

KioskLimits limits(int clips, int lights = 3) {
    KioskLimits l;
    l.clip_count = clips;
    l.light_count = lights;
    return l;
}

// Fields other than the ones a key is meant to change stay put.
void expect_same_except_view(const KioskState& a, const KioskState& b) {
    EXPECT_EQ(a.paused, b.paused);
    EXPECT_EQ(a.clip, b.clip);
    EXPECT_EQ(a.light, b.light);
    EXPECT_EQ(a.save, b.save);
    EXPECT_EQ(a.quit, b.quit);
}

TEST(KioskKeys, LimitsComeFromTheFrameSettingsTable) {
    const KioskLimits l;
    EXPECT_EQ(l.zoom_min, stipple::kFrameSettings.zoom.min);
    EXPECT_EQ(l.zoom_max, stipple::kFrameSettings.zoom.max);
    EXPECT_EQ(l.pitch_min, -90.0f);
    EXPECT_EQ(l.pitch_max, 90.0f);
}

TEST(KioskKeys, SpaceTogglesPause) {
    KioskState s;
    s = apply_key(s, Key::space, limits(2));
    EXPECT_TRUE(s.paused);
    s = apply_key(s, Key::space, limits(2));
    EXPECT_FALSE(s.paused);
}

TEST(KioskKeys, LeftAndRightStepTheClipAndWrap) {
    KioskState s;
    s.clip = 0;
    s = apply_key(s, Key::right, limits(3));
    EXPECT_EQ(s.clip, 1);
    s = apply_key(s, Key::right, limits(3));
    s = apply_key(s, Key::right, limits(3));
    EXPECT_EQ(s.clip, 0);  // wrapped past the last
    s = apply_key(s, Key::left, limits(3));
    EXPECT_EQ(s.clip, 2);  // wrapped before the first
    EXPECT_EQ(s.yaw, 0.0f);
}

TEST(KioskKeys, ClipKeysFromTheRestPoseAndWithoutClips) {
    KioskState rest;  // clip -1
    EXPECT_EQ(apply_key(rest, Key::right, limits(4)).clip, 0);
    EXPECT_EQ(apply_key(rest, Key::left, limits(4)).clip, 3);
    EXPECT_EQ(apply_key(rest, Key::right, limits(0)).clip, -1);  // nothing to switch to
    EXPECT_EQ(apply_key(rest, Key::left, limits(0)).clip, -1);
    KioskState one;
    one.clip = 0;
    EXPECT_EQ(apply_key(one, Key::right, limits(1)).clip, 0);
}

TEST(KioskKeys, ShiftLeftAndRightOrbitTheYawAndWrap) {
    const KioskLimits l = limits(3);
    KioskState s;
    s.clip = 1;
    KioskState t = apply_key(s, Key::right, l, true);
    EXPECT_FLOAT_EQ(t.yaw, l.yaw_step);
    expect_same_except_view(s, t);  // the clip stays
    t = apply_key(s, Key::left, l, true);
    EXPECT_FLOAT_EQ(t.yaw, -l.yaw_step);
    s.yaw = 175.0f;
    EXPECT_FLOAT_EQ(apply_key(s, Key::right, l, true).yaw, 175.0f + l.yaw_step - 360.0f);
    s.yaw = -175.0f;
    EXPECT_FLOAT_EQ(apply_key(s, Key::left, l, true).yaw, -175.0f - l.yaw_step + 360.0f);
    s.yaw = 180.0f - l.yaw_step;  // lands on 180 exactly: kept, (-180, 180]
    EXPECT_FLOAT_EQ(apply_key(s, Key::right, l, true).yaw, 180.0f);
    KioskState round;
    for (int i = 0; i < 24; ++i) round = apply_key(round, Key::right, l, true);
    EXPECT_NEAR(round.yaw, 0.0f, 1e-3f);  // a full turn (24 * 15 degrees)
}

TEST(KioskKeys, UpAndDownOrbitThePitchClamped) {
    const KioskLimits l = limits(1);
    KioskState s;
    s = apply_key(s, Key::up, l);
    EXPECT_FLOAT_EQ(s.pitch, l.pitch_step);
    s = apply_key(s, Key::down, l);
    s = apply_key(s, Key::down, l);
    EXPECT_FLOAT_EQ(s.pitch, -l.pitch_step);
    for (int i = 0; i < 30; ++i) s = apply_key(s, Key::up, l);
    EXPECT_EQ(s.pitch, 90.0f);
    for (int i = 0; i < 30; ++i) s = apply_key(s, Key::down, l);
    EXPECT_EQ(s.pitch, -90.0f);
    KioskState shifted;  // Shift does not change up/down
    EXPECT_FLOAT_EQ(apply_key(shifted, Key::up, l, true).pitch, l.pitch_step);
}

TEST(KioskKeys, PlusAndMinusZoomWithinTheLimits) {
    const KioskLimits l = limits(1);
    KioskState s;
    s = apply_key(s, Key::plus, l);
    EXPECT_FLOAT_EQ(s.zoom, l.zoom_step);
    s = apply_key(s, Key::minus, l);
    EXPECT_FLOAT_EQ(s.zoom, 1.0f);
    s = apply_key(s, Key::minus, l);
    EXPECT_FLOAT_EQ(s.zoom, 1.0f / l.zoom_step);
    for (int i = 0; i < 100; ++i) s = apply_key(s, Key::plus, l);
    EXPECT_EQ(s.zoom, l.zoom_max);
    for (int i = 0; i < 200; ++i) s = apply_key(s, Key::minus, l);
    EXPECT_EQ(s.zoom, l.zoom_min);
    expect_same_except_view(KioskState(), s);  // only the zoom moved
}

TEST(KioskKeys, LCyclesTheLight) {
    KioskState s;
    s = apply_key(s, Key::l, limits(1, 3));
    EXPECT_EQ(s.light, 1);
    s = apply_key(s, Key::l, limits(1, 3));
    s = apply_key(s, Key::l, limits(1, 3));
    EXPECT_EQ(s.light, 0);
    EXPECT_EQ(apply_key(KioskState(), Key::l, limits(1, 1)).light, 0);  // one preset
}

TEST(KioskKeys, SAsksForASaveAndEscapeQuits) {
    const KioskState s;
    const KioskState saved = apply_key(s, Key::s, limits(1));
    EXPECT_TRUE(saved.save);
    EXPECT_FALSE(saved.quit);
    const KioskState quit = apply_key(s, Key::escape, limits(1));
    EXPECT_TRUE(quit.quit);
    EXPECT_FALSE(quit.save);
}

TEST(KioskKeys, OtherKeysChangeNothing) {
    KioskState s;
    s.clip = 2;
    s.zoom = 1.5f;
    s.yaw = 30.0f;
    s.pitch = -20.0f;
    s.light = 1;
    s.paused = true;
    const KioskState t = apply_key(s, Key::other, limits(3), true);
    expect_same_except_view(s, t);
    EXPECT_EQ(t.zoom, s.zoom);
    EXPECT_EQ(t.yaw, s.yaw);
    EXPECT_EQ(t.pitch, s.pitch);
}

}  // namespace
