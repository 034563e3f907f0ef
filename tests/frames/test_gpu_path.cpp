// Issue 9, item 4: the GPU path (runtime/gpu_stages.h) places, re-weighs and sizes the
// points in a transform feedback vertex shader. Its output, read back from the transform
// feedback buffer, must match the CPU stages run on the same posed mesh and camera: at most
// 1% of the dots differ in diameter by more than 0.5 px, positions agree within 1e-4 of the
// model's size, and the frames drawn by the two paths differ in few pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "runtime/double_sided.h"
#include "runtime/frame_pipeline.h"
#include "runtime/point_placement.h"
#include "runtime/stipple.h"
#include "runtime/stipple_size.h"
#include "tests/common/fixtures.h"

namespace {

using stipple::FramePath;
using stipple::Pipeline;

struct Case {
    const char* input;
    const char* options;  // the bake's (tests/test_assets.txt)
    float yaw;
    bool animated;
    // 1: two lights (one in world space) and ambient; 2: rest-pose radii (no Alg. 6.4) and a
    // constant tone.
    int variant;
};

void PrintTo(const Case& c, std::ostream* os) {
    *os << c.input << " " << c.options;
}

// The CPU stages (place, double-sided facing, relevance, size) on the pipeline's posed mesh
// and camera: positions (3 per point) and diameters.
void cpu_reference(const Pipeline& p, std::vector<float>* positions, std::vector<float>* sizes) {
    const stipple::Asset& a = *p.asset;
    const uint32_t n = a.points.point_count;
    std::vector<float> normals(size_t(n) * 3), radius(n);
    positions->assign(size_t(n) * 3, 0.0f);
    sizes->assign(n, 0.0f);
    stipple::place_points(a.points, a.mesh.indices, p.vertex_positions.get(),
                          p.vertex_normals.get(), positions->data(), normals.data());
    stipple::face_double_sided_points(n, p.point_double_sided.get(), positions->data(),
                                      normals.data(), p.size_params.eye);
    if (p.config.relevance_update)
        stipple::recompute_relevance(a.points, positions->data(), p.radius_scale.get(),
                                     p.rest_radius.get(), radius.data());
    else
        radius.assign(p.rest_radius.get(), p.rest_radius.get() + n);
    stipple::size_stipples(n, positions->data(), normals.data(), radius.data(), p.size_params,
                           sizes->data());
}

struct Agreement {
    uint32_t drawn = 0;       // dots with a size on the CPU
    uint32_t size_off = 0;    // |gpu - cpu| > 0.5 px
    double max_position = 0;  // largest position difference, model units
    double max_size = 0;      // largest diameter difference, px
};

Agreement compare(const std::vector<float>& dots, const std::vector<float>& positions,
                  const std::vector<float>& sizes) {
    Agreement g;
    for (size_t i = 0; i < sizes.size(); ++i) {
        const double ds = std::fabs(double(dots[i * 4 + 3]) - sizes[i]);
        g.drawn += sizes[i] > 0.0f;
        g.size_off += ds > 0.5;
        g.max_size = std::max(g.max_size, ds);
        for (int k = 0; k < 3; ++k)
            g.max_position =
                std::max(g.max_position, std::fabs(double(dots[i * 4 + k]) - positions[i * 3 + k]));
    }
    return g;
}

double model_size(const stipple::Asset& a) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (uint32_t v = 0; v < a.mesh.vertex_count; ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], a.mesh.positions[v * 3 + k]);
            hi[k] = std::max(hi[k], a.mesh.positions[v * 3 + k]);
        }
    return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

class GpuPath : public ::testing::TestWithParam<Case> {};

TEST_P(GpuPath, SizesAndFramesMatchTheCpuPath) {
    const Case c = GetParam();
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(
        stipple::test::load_baked(stipple::test::baked_asset(c.input, c.options), &asset, &error))
        << error;
    stipple::test::HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    stipple::FrameConfig config;
    config.width = 640;
    config.height = 480;
    config.yaw_degrees = c.yaw;
    config.refinement_budget = 0;  // the GPU path draws the baked points only
    config.frame_clip = c.animated ? 0 : -1;
    if (c.variant == 1) {
        config.light_count = 2;
        config.lights[1].direction[0] = 0.8f;
        config.lights[1].intensity = 0.5f;
        config.lights[1].camera_space = false;
        config.ambient = 0.1f;
    }
    if (c.variant == 2) {
        config.relevance_update = false;
        config.constant_tone = 0.3f;
    }
    auto cpu = std::make_unique<Pipeline>(), gpu = std::make_unique<Pipeline>();
    ASSERT_TRUE(stipple::pipeline_init(cpu.get(), asset, gl.gl(), config).ok());
    config.path = FramePath::gpu;
    const stipple::Status st = stipple::pipeline_init(gpu.get(), asset, gl.gl(), config);
    ASSERT_TRUE(st.ok()) << st.message;

    const uint32_t n = asset.points.point_count;
    const size_t pixels = size_t(config.width) * size_t(config.height);
    std::vector<float> dots(size_t(n) * 4), positions, sizes;
    std::vector<uint8_t> cpu_rgba(pixels * 4), gpu_rgba(pixels * 4);
    const double tolerance = 1e-4 * model_size(asset);
    const int frames = c.animated ? 4 : 1;
    for (int f = 0; f < frames; ++f) {
        const float time = 0.25f * float(f);
        const int clip = c.animated ? 0 : -1;
        stipple::pipeline_frame(cpu.get(), clip, time, nullptr);
        stipple::pipeline_frame(gpu.get(), clip, time, nullptr);
        stipple::renderer_read_color(&cpu->renderer, cpu_rgba.data());
        stipple::renderer_read_color(&gpu->renderer, gpu_rgba.data());
        ASSERT_TRUE(stipple::gpu_stages_read_dots(gpu->gpu, dots.data()));
        cpu_reference(*gpu, &positions, &sizes);
        const Agreement g = compare(dots, positions, sizes);
        // Pixels whose darkness differs by more than 1/4 of full ink, and the ink overall.
        size_t changed = 0, dark_cpu = 0;
        double ink_cpu = 0, ink_gpu = 0;
        for (size_t i = 0; i < pixels; ++i) {
            const int a = cpu_rgba[i * 4], b = gpu_rgba[i * 4];
            changed += std::abs(a - b) > 64;
            dark_cpu += a < 128;
            ink_cpu += 255 - a;
            ink_gpu += 255 - b;
        }
        std::printf(
            "%s t=%.2f: %u points, %u drawn, %u off by > 0.5 px (max %.3g px), "
            "max position %.3g (tol %.3g); %zu changed pixels of %zu dark, ink %.4f\n",
            c.input, time, n, g.drawn, g.size_off, g.max_size, g.max_position, tolerance, changed,
            dark_cpu, ink_gpu / ink_cpu);
        EXPECT_GT(g.drawn, n / 50);  // a real frame: a few percent of the points have a size
        EXPECT_LE(g.size_off, n / 100) << "more than 1% of the dots differ by more than 0.5 px";
        EXPECT_LE(g.max_position, tolerance);
        EXPECT_GT(dark_cpu, 1000u);
        EXPECT_LE(changed, dark_cpu / 100) << "frames differ in more than 1% of the ink pixels";
        EXPECT_NEAR(ink_gpu / ink_cpu, 1.0, 0.01);
    }
    stipple::pipeline_destroy(gpu.get());
    stipple::pipeline_destroy(cpu.get());
}

const Case kCases[] = {
    {"assets/CesiumMan/CesiumMan.glb", "", -60.0f, true, 0},
    {"assets/StanfordBunny/stanford-bunny.obj", "", 0.0f, false, 0},
    {"assets/Horse/horse.ply", "", 90.0f, false, 0},
    {"assets/SimpleSkin/SimpleSkin.gltf", "--points 20000 --double-sided on", 180.0f, true, 1},
    {"assets/CesiumMan/CesiumMan.glb", "--points 60000", 200.0f, true, 2}};

std::string case_name(const ::testing::TestParamInfo<Case>& param) {
    const char* names[5] = {"CesiumManWalk", "Bunny", "Horse", "DoubleSidedTwoLights",
                            "RestRadiiConstantTone"};
    return names[param.index];
}

INSTANTIATE_TEST_SUITE_P(WalkAndStatic, GpuPath, ::testing::ValuesIn(kCases), case_name);

TEST(GpuPathConfig, UnknownPathIsRefused) {
    stipple::FrameConfig in, out;
    in.path = FramePath(7);
    const stipple::Status st = stipple::resolve_frame_config(in, &out);
    EXPECT_EQ(st.code, stipple::StatusCode::invalid_argument);
    EXPECT_NE(std::string(st.message).find("path"), std::string::npos) << st.message;
}

// The C API's desc.path: the GPU path draws the same frame as the CPU path (both without
// refinement), and an unknown path is an invalid argument.
TEST(GpuPathConfig, CApiPathDrawsTheSameFrame) {
    stipple::test::HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    stipple_asset* asset = nullptr;
    const std::string path = stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "");
    ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset), STIPPLE_OK);
    stipple_player_desc desc;
    std::memset(&desc, 0, sizeof(desc));
    desc.width = 320;
    desc.height = 240;
    desc.refinement_budget = -1;
    desc.get_proc_address = stipple::platform::proc_loader(gl.context());
    std::vector<uint8_t> rgba[2];
    for (int path_value : {STIPPLE_PATH_CPU, STIPPLE_PATH_GPU}) {
        desc.path = path_value;
        stipple_player* player = nullptr;
        ASSERT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_OK) << stipple_last_error();
        stipple_player_draw(player, 0, 0.5f);
        rgba[path_value].resize(size_t(desc.width) * size_t(desc.height) * 4);
        stipple_player_read_rgba(player, rgba[path_value].data());
        stipple_player_destroy(player);
    }
    size_t dark = 0, changed = 0;
    for (size_t i = 0; i < rgba[0].size(); i += 4) {
        dark += rgba[0][i] < 128;
        changed += std::abs(int(rgba[0][i]) - int(rgba[1][i])) > 64;
    }
    EXPECT_GT(dark, 500u);
    EXPECT_LE(changed, dark / 100);
    desc.path = 5;
    stipple_player* bad = nullptr;
    EXPECT_EQ(stipple_player_create(asset, &desc, &bad), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stipple_last_error()).find("path"), std::string::npos);
    stipple_asset_destroy(asset);
}

// stipple-play --path gpu: the same frames as --path cpu without refinement, through the CLI
// (--check-gl: no GL error in any pass); --dots-out needs the CPU path.
TEST(GpuPathConfig, PlayerPathOption) {
    stipple::test::ScratchDir scratch;
    const std::string asset = stipple::test::baked_asset("assets/Horse/horse.ply", "");
    stipple::test::Image frames[2];
    const char* paths[2] = {"cpu --refinement-budget 0", "gpu"};
    for (int k = 0; k < 2; ++k) {
        const std::string out = scratch.file(k ? "gpu" : "cpu");
        std::string log;
        ASSERT_EQ(stipple::test::run(stipple::test::play_checked() + " " + asset + " --out " + out +
                                         " --frames 2 --no-apng --size 320x240 --yaw 45 --path " +
                                         paths[k],
                                     &log),
                  0)
            << log;
        ASSERT_TRUE(stipple::test::load_png(out + "/frame_0001.png", &frames[k])) << out;
    }
    size_t dark = 0, changed = 0;
    for (size_t i = 0; i < frames[0].rgba.size(); i += 4) {
        dark += frames[0].rgba[i] < 128;
        changed += std::abs(int(frames[0].rgba[i]) - int(frames[1].rgba[i])) > 64;
    }
    EXPECT_GT(dark, 500u);
    EXPECT_LE(changed, dark / 100);
    std::string log;
    EXPECT_EQ(stipple::test::run(stipple::test::play_checked() + " " + asset + " --out " +
                                     scratch.file("dots") + " --path gpu --dots-out",
                                 &log),
              1);
    EXPECT_NE(log.find("--path cpu"), std::string::npos) << log;
}

}  // namespace
