// Static meshes from every supported file type bake and render, and the OSMesa fallback
// draws the same frame as EGL.
#include <gtest/gtest.h>

#include <fstream>

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

}  // namespace
