// The GI'98 §6 benchmark scene (Neulander & van de Panne, Table 1), shared by
// bench/bench_paintstrokes.cpp and tools/paintstroke_table_main.cpp: a 3x3x3 cluster of 27
// curved tubes (Catmull-Rom paintstrokes of 5 control points with varying radius), a 50-frame
// orbit of the camera at three constant distances (large, medium, small scale), and the static
// comparison model of §6 / Figure 10: an orthogonal extrusion of a regular n-gon of varying
// radius along the same path, adaptive lengthwise to curvature. Static models come out as eye-
// space StrokeVertex triangles, so runtime/stroke_renderer.h draws both kinds.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "runtime/gl_api.h"
#include "runtime/paintstroke.h"

namespace stipple::bench {

constexpr int kTubeCount = 27;
constexpr int kTubePoints = 5;
constexpr int kFrames = 50;
constexpr int kScales = 3;  // large, medium, small
constexpr int kWidth = 640;
constexpr int kHeight = 480;

struct Tube {
    StrokePoint points[kTubePoints];  // world space
};

struct Scene {
    std::vector<Tube> tubes;
};

// The 27 tubes: deterministic shapes, orientations and colours; opaque unless `opacity` < 1
// (then op_min = opacity and op_max = opacity + (1 - opacity) / 2: lengthwise variation).
Scene make_gi98_scene(float opacity = 1.0f);

const char* scale_name(int scale);  // "large", "medium", "small"

// One frame's camera: eye-space view, GL projection, the tessellator's camera, the light.
struct View {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    StrokeCamera camera;
    glm::vec3 light_eye{0.0f, 0.0f, 1.0f};
};
View scene_view(int scale, int frame, int width = kWidth, int height = kHeight);

// The Catmull-Rom path of a tube (position and radius) and its parameter derivatives, in
// section `section` (0 .. count - 2) at t in [0, 1]. The ends use reflected phantom points.
struct PathSample {
    glm::vec3 pos{0.0f}, d_pos{0.0f};
    float rad = 0.0f, d_rad = 0.0f;
};
PathSample eval_path(const StrokePoint* points, int count, int section, float t);

// A static extrusion of all tubes, world space (StrokeVertex positions and normals in world
// coordinates; normals are the true surface normals).
struct StaticModel {
    int sides = 0;
    std::vector<StrokeVertex> vertices;
    std::vector<uint32_t> indices;
    uint32_t triangles = 0;  // all tubes
};
// `angle_tolerance` (radians): a segment is split while its end tangents differ by more.
StaticModel build_extrusion(const Scene& scene, int sides, float angle_tolerance);

// The model in eye space with back faces culled on the CPU (what GL_CULL_FACE would do):
// `indices` hold the triangles facing the viewer.
struct StaticFrame {
    std::vector<StrokeVertex> vertices;
    std::vector<uint32_t> indices;
    uint32_t rendered_triangles = 0;
};
void static_to_eye(const StaticModel& model, const glm::mat4& view, StaticFrame* out);

// Buffers for one frame of tessellated paintstrokes, sized once for the scene's worst case.
struct StrokeFrame {
    TessellationParams params;
    std::unique_ptr<StrokeVertex[]> vertices;
    std::unique_ptr<uint32_t[]> indices, sorted_indices, order, scratch;
    std::unique_ptr<StrokeSegment[]> segments;
    StrokeMeshBound bound;  // whole scene
    StrokeMesh mesh;
    TessellationStats stats;
    std::vector<StrokePoint> eye_points;  // one tube's control points in eye space
};
void stroke_frame_init(StrokeFrame* f, const TessellationParams& params);
// Tessellates every tube (control points taken to eye space) and sorts the segments back to
// front into sorted_indices (mesh.index_count of them).
void tessellate_scene(const Scene& scene, const View& view, StrokeFrame* f);
// Only the tessellation (for per-stroke cost): no sort.
void tessellate_scene_only(const Scene& scene, const View& view, StrokeFrame* f);

// An offscreen RGBA8 + depth framebuffer.
struct Target {
    GLuint fbo = 0, colour = 0, depth = 0;
    int width = 0, height = 0;
};
bool target_init(const GlApi& gl, int width, int height, Target* t);
void target_clear(const GlApi& gl, const Target& t);  // black, depth 1
void target_read(const GlApi& gl, const Target& t, uint8_t* rgba);
void target_destroy(const GlApi& gl, Target* t);

}  // namespace stipple::bench
