// Static meshes from every supported file type bake and render, the OSMesa fallback draws
// the same frame as EGL, and llvmpipe's rasterizer on the calling thread (raster_threads 0)
// takes no thread of its own and draws the same frame.
#include <dirent.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <thread>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// A closed tetrahedron in each static format.
const char* kObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char* kStl =
    "solid t\n"
    "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "endsolid t\n";

TEST(StaticMeshes, ObjPlyAndStlBakeAndRender) {
    const ScratchDir scratch;
    const std::string dir = scratch.path();
    const char* names[3] = {"tet.obj", "tet.ply", "tet.stl"};
    const char* texts[3] = {kObj, kPly, kStl};
    for (int i = 0; i < 3; ++i) {
        std::string in = dir + "/" + names[i], asset = in + ".stip", out = in + ".frames";
        std::ofstream(in) << texts[i];
        std::string log;
        ASSERT_EQ(run(bin("stipple-bake") + " " + in + " -o " + asset + " --points 3000", &log), 0)
            << log;
        EXPECT_NE(log.find("\"triangles\": 4"), std::string::npos) << log;
        EXPECT_NE(log.find("\"points\": 3000"), std::string::npos) << log;
        ASSERT_EQ(run(play_checked() + " " + asset + " --out " + out +
                      " --frames 1 --no-apng --pitch 30 --yaw 30 --tone 0.4 --size 200x200"),
                  0);
        Image img;
        ASSERT_TRUE(load_png(out + "/frame_0000.png", &img));
        size_t dark = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) dark += img.luminance(x, y) < 0.5f;
        EXPECT_GT(dark, 1000u) << names[i];
    }
}

TEST(Backends, OsmesaDrawsTheSameFrameAsEgl) {
    const ScratchDir scratch;
    const std::string dir = scratch.path();
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ASSERT_FALSE(asset.empty());
    std::string log;
    for (const char* backend : {"egl", "osmesa"}) {
        ASSERT_EQ(run(play_checked() + " " + asset + " --out " + dir + "/" + backend +
                          " --frames 2 --no-apng --size 320x240 --stats --backend " + backend,
                      &log),
                  0)
            << log;
        EXPECT_NE(log.find(std::string("\"backend\": \"") + backend), std::string::npos) << log;
    }
    EXPECT_EQ(run(bin("stipple-compare") + " " + dir + "/egl/frame_0001.png " + dir +
                      "/osmesa/frame_0001.png --tolerance 0 --max-fraction 0",
                  &log),
              0)
        << log;
}

int process_threads() {
    int n = 0;
    DIR* dir = opendir("/proc/self/task");
    if (!dir) return -1;
    while (const dirent* e = readdir(dir)) n += e->d_name[0] != '.';
    closedir(dir);
    return n;
}

TEST(Backends, RasterThreadsZeroRasterizesOnTheCallingThread) {
    if (std::getenv("LP_NUM_THREADS")) GTEST_SKIP() << "LP_NUM_THREADS is set: it wins";
    int added[2] = {0, 0};  // threads a context adds: the driver's default, then 0
    for (int k = 0; k < 2; ++k) {
        const int before = process_threads();
        stipple::platform::HeadlessConfig config;
        config.raster_threads = k == 0 ? -1 : 0;
        HeadlessGl gl;
        std::string error;
        ASSERT_TRUE(gl.open(&error, config)) << error;
        if (gl.context().renderer.find("llvmpipe") == std::string::npos)
            GTEST_SKIP() << "not llvmpipe: " << gl.context().renderer;
        added[k] = process_threads() - before;
        EXPECT_EQ(std::getenv("LP_NUM_THREADS"), nullptr) << "the environment is restored";
    }
    // Mesa may start one thread of its own either way (its shader cache's queue).
    EXPECT_LE(added[1], 1) << "raster_threads 0: no rasterizer thread";
    if (std::thread::hardware_concurrency() > 1) {
        EXPECT_GE(added[0] - added[1], 2) << "llvmpipe's default: rasterizer threads per core";
    }
}

TEST(Backends, RasterThreadsZeroDrawsTheSameFrames) {
    const ScratchDir scratch;
    const std::string dir = scratch.path();
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ASSERT_FALSE(asset.empty());
    const char* variants[2] = {"", " --raster-threads 0 --threads 2"};
    for (int k = 0; k < 2; ++k)
        ASSERT_EQ(run(play_checked() + " " + asset + " --out " + dir + "/" + std::to_string(k) +
                      " --frames 3 --no-apng --size 320x240" + variants[k]),
                  0);
    std::string log;
    EXPECT_EQ(run(bin("stipple-compare") + " " + dir + "/0/frame_0002.png " + dir +
                      "/1/frame_0002.png --tolerance 0 --max-fraction 0",
                  &log),
              0)
        << log;
}

}  // namespace
