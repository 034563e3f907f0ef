// The kiosk window (stipple-play --window) under Xvfb: after N frames drawn at a fixed clip
// time, a screenshot of the window's back buffer equals the headless frame of the same state
// within the golden tolerance. Skipped where xvfb-run is not installed (scripts/setup.sh
// installs it).
#include <gtest/gtest.h>

#include <string>

#include "tests/common/fixtures.h"
#include "tools/image_write.h"

namespace {

using namespace stipple::test;

bool have_xvfb_run() {
    return run("command -v xvfb-run") == 0;
}

// A window has no alpha channel: the headless frame's PNG keeps the framebuffer's alpha
// (below 255 on antialiased dot edges), which a screen never shows. Writes `png` with every
// alpha at 255 to `opaque`, the picture as a window shows it.
void write_opaque(const std::string& png, const std::string& opaque) {
    Image frame;
    ASSERT_TRUE(load_png(png, &frame)) << png;
    for (size_t i = 3; i < frame.rgba.size(); i += 4) frame.rgba[i] = 255;
    std::string error;
    ASSERT_TRUE(stipple::image::write_png(opaque.c_str(), frame.width, frame.height,
                                          frame.rgba.data(), false, &error))
        << error;
}

// xvfb-run with a free server number (-a: the first free one from -n; starting from one
// derived from the process id keeps tests that ctest runs in parallel apart) and a 24-bit
// screen larger than the window.
std::string under_xvfb(const std::string& command) {
    return "xvfb-run -a -n " + std::to_string(100 + getpid() % 800) +
           " -s \"-screen 0 800x600x24\" " + command;
}

TEST(KioskWindow, ScreenshotEqualsTheHeadlessFrame) {
    if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run not found (Debian package xvfb)";
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000");
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    const std::string view = " --size 320x240 --yaw -60";
    std::string log;
    ASSERT_EQ(
        run(under_xvfb(play_checked() + " " + asset + " --window" + view +
                       " --frames 5 --fixed-time 0.66 --screenshot " + dir.file("window.png")),
            &log),
        0)
        << log;
    ASSERT_EQ(run(play_checked() + " " + asset + view + " --frames 1 --time 0.66 --no-apng --out " +
                      dir.file("headless"),
                  &log),
              0)
        << log;
    Image shot;
    ASSERT_TRUE(load_png(dir.file("window.png"), &shot));
    EXPECT_EQ(shot.width, 320);
    EXPECT_EQ(shot.height, 240);
    write_opaque(dir.file("headless/frame_0000.png"), dir.file("headless.png"));
    EXPECT_EQ(run(bin("stipple-compare") + " " + dir.file("window.png") + " " +
                      dir.file("headless.png") + " --tolerance 8 --shift 1 --max-fraction 0.005",
                  &log),
              0)
        << log;
}

// --raster-threads reaches the window's display too (platform::WindowConfig::raster_threads):
// llvmpipe rasterizing on the calling thread, with the point part on the worker, draws the
// same screenshot as the driver's default, byte for byte.
TEST(KioskWindow, RasterThreadsZeroDrawsTheSameScreenshot) {
    if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run not found (Debian package xvfb)";
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000");
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    const char* variants[2] = {"", " --raster-threads 0 --threads 2"};
    std::string log;
    for (int k = 0; k < 2; ++k)
        ASSERT_EQ(run(under_xvfb(play_checked() + " " + asset + " --window --size 320x240" +
                                 variants[k] + " --frames 3 --fixed-time 0.5 --screenshot " +
                                 dir.file("shot" + std::to_string(k) + ".png")),
                      &log),
                  0)
            << variants[k] << ": " << log;
    EXPECT_EQ(run(bin("stipple-compare") + " " + dir.file("shot0.png") + " " +
                      dir.file("shot1.png") + " --tolerance 0",
                  &log),
              0)
        << log;
}

TEST(KioskWindow, AnotherTimeDoesNotMatch) {
    // The comparison is not vacuous: the window at another clip time differs.
    if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run not found (Debian package xvfb)";
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000");
    ASSERT_FALSE(asset.empty());
    ScratchDir dir;
    std::string log;
    ASSERT_EQ(run(under_xvfb(play_checked() + " " + asset +
                             " --window --size 320x240 --frames 2 --fixed-time 0.2 --screenshot " +
                             dir.file("window.png")),
                  &log),
              0)
        << log;
    ASSERT_EQ(run(play_checked() + " " + asset + " --size 320x240 --frames 1 --time 0.66 " +
                      "--no-apng --out " + dir.file("headless"),
                  &log),
              0)
        << log;
    write_opaque(dir.file("headless/frame_0000.png"), dir.file("headless.png"));
    EXPECT_EQ(run(bin("stipple-compare") + " " + dir.file("window.png") + " " +
                      dir.file("headless.png") + " --tolerance 8 --shift 1 --max-fraction 0.005",
                  &log),
              1)
        << log;
}

TEST(KioskWindow, WithoutADisplayFailsWithOneLine) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000");
    ASSERT_FALSE(asset.empty());
    std::string log;
    EXPECT_EQ(
        run("env -u DISPLAY " + bin("stipple-play") + " " + asset + " --window --frames 1", &log),
        1);
    EXPECT_NE(log.find("no X display: set DISPLAY or run under xvfb-run"), std::string::npos)
        << log;
    EXPECT_EQ(log.find('\n'), log.size() - 1) << log;  // one line
}

TEST(KioskWindow, WindowOnlyOptionsNeedWindow) {
    std::string log;
    EXPECT_EQ(run(bin("stipple-play") + " x.stip --out d --screenshot s.png", &log), 1);
    EXPECT_NE(log.find("need --window"), std::string::npos) << log;
}

}  // namespace
