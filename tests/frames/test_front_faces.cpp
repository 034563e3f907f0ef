// The mesh pass's front faces (runtime/renderer_front.cpp): handing the GPU only the
// single-sided triangles that may face the eye leaves the mesh pass's depth and the picture
// exactly as when the GPU culls the back faces itself. Checked in-process: each frame is drawn
// by pipeline_frame (flags from the silhouette stage), then its passes again with no flags;
// the depth copies and the colour must match byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/silhouette.h"
#include "tests/common/pipeline_view.h"

namespace {

using namespace stipple::test;

struct Readback {
    std::vector<uint8_t> colour;
    std::vector<float> depth;
};

Readback read(PipelineView* view) {
    Readback r;
    r.colour = view->read_colour();
    r.depth = view->read_depth();
    return r;
}

// pipeline_frame's draw, with every triangle handed to the GPU.
void redraw_all_triangles(stipple::Pipeline* p) {
    stipple::renderer_set_front_faces(&p->renderer, nullptr, p->view_projection);
    stipple::renderer_draw_fill(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                p->vertex_normals.get(), p->asset->mesh.vertex_count);
    stipple::renderer_draw_line_sets(&p->renderer, p->view_projection, p->lines.get(),
                                     p->lines_drawn, nullptr, 0);
    stipple::renderer_draw_dots(&p->renderer, p->view_projection, p->draw_positions.get(),
                                p->draw_sizes.get(), nullptr, p->points_drawn);
    p->renderer.gl.Finish();
}

void check_asset(const std::string& input, const std::string& options, int clip) {
    SCOPED_TRACE(input);
    PipelineView view;
    std::string error;
    ASSERT_TRUE(view.open(baked_asset(input, options), 320, 240, &error)) << error;
    stipple::Pipeline* p = view.pipeline();
    const CameraView cameras[] = {{1.0f, 0.0f, 0.0f},
                                  {1.0f, 90.0f, 20.0f},
                                  {2.5f, 200.0f, -30.0f},
                                  {0.6f, -60.0f, 60.0f},
                                  {6.0f, 30.0f, 5.0f}};
    uint32_t least_kept = UINT32_MAX;
    for (const CameraView& v : cameras) {
        ASSERT_TRUE(view.set_view(v));
        stipple::pipeline_frame(p, clip, 0.4f, nullptr);
        // The flags were used: the pass drew a subset of the triangles.
        ASSERT_NE(p->renderer.front_count, stipple::Renderer::kFrontNotBuilt);
        least_kept = std::min(least_kept, p->renderer.front_count);
        const Readback front = read(&view);
        redraw_all_triangles(p);
        const Readback all = read(&view);
        SCOPED_TRACE("zoom " + std::to_string(v.zoom) + " yaw " + std::to_string(v.yaw_degrees));
        ASSERT_GT(p->points_drawn, 0u);
        ASSERT_TRUE(front.depth == all.depth);
        ASSERT_TRUE(front.colour == all.colour);
    }
    EXPECT_LT(least_kept, view.asset().mesh.triangle_count * 3 / 4);  // most back faces never sent
}

TEST(FrontFaces, SameDepthAndPictureAsGpuCulling) {
    check_asset("assets/CesiumMan/CesiumMan.glb", "", 0);
    check_asset("assets/Horse/horse.ply", "", -1);
    check_asset("assets/StanfordBunny/stanford-bunny.obj", "", -1);  // open: holes in its base
}

// triangle_facing's flags: a face seen nearly edge-on from behind is kept for the depth pass
// (kFacingEdgeOn) but is not a front face for the silhouettes.
TEST(FrontFaces, NearlyEdgeOnBackFacesAreMarked) {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // normal +z
    const uint32_t indices[] = {0, 1, 2};
    uint8_t front = 9;
    stipple::triangle_facing(1, indices, positions, glm::vec3(0.2f, 0.2f, 3.0f), &front);
    EXPECT_EQ(front, stipple::kFacingFront);
    stipple::triangle_facing(1, indices, positions, glm::vec3(0.2f, 0.2f, -3.0f), &front);
    EXPECT_EQ(front, stipple::kFacingBack);
    stipple::triangle_facing(1, indices, positions, glm::vec3(0.2f, 100.0f, -0.5f), &front);
    EXPECT_EQ(front, stipple::kFacingEdgeOn);  // 0.3 degrees behind the plane
}

}  // namespace
