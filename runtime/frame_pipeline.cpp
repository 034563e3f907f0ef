#include "runtime/frame_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/point_placement.h"
#include "runtime/silhouette.h"

namespace stipple {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point* t) {
    Clock::time_point now = Clock::now();
    double ms = std::chrono::duration<double, std::milli>(now - *t).count();
    *t = now;
    return ms;
}

template <typename T>
bool alloc(std::unique_ptr<T[]>* out, size_t count) {
    out->reset(new (std::nothrow) T[count > 0 ? count : 1]);
    return bool(*out);
}

// Skins (or copies) the mesh into p->vertex_positions/normals for the given pose.
void pose_mesh(Pipeline* p, int clip, float time, StageTimes* t, Clock::time_point* clock) {
    const Asset& a = *p->asset;
    const MeshView& m = a.mesh;
    if (!a.skinned) {
        std::memcpy(p->vertex_positions.get(), m.positions, size_t(m.vertex_count) * 12);
        std::memcpy(p->vertex_normals.get(), m.normals, size_t(m.vertex_count) * 12);
        if (t) t->skin += ms_since(clock);
        return;
    }
    const anim::Skeleton& k = a.skin.skeleton;
    if (clip >= 0 && uint32_t(clip) < a.clip_count)
        anim::sample_clip(k, a.clips[clip], time, p->locals.get());
    else
        anim::rest_pose(k, p->locals.get());
    anim::local_to_model(k, p->locals.get(), p->models.get());
    anim::joint_matrices(k, p->models.get(), p->skin_matrices.get());
    if (t) t->sample += ms_since(clock);
    anim::SkinJob job = {m.vertex_count, p->skin_matrices.get(), k.joint_count, a.skin.joints,
                         a.skin.weights, m.positions, m.normals, p->vertex_positions.get(),
                         p->vertex_normals.get()};
    anim::skin_lbs(job);
    if (t) t->skin += ms_since(clock);
}

// Orbit camera around the rest-pose bounding sphere; zoom narrows the field of view so
// that zoom 2 is exactly twice as large on screen.
void setup_camera(Pipeline* p) {
    const Asset& a = *p->asset;
    const PipelineConfig& c = p->config;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t i = 0; i < a.mesh.vertex_count; ++i) {
        glm::vec3 v(p->vertex_positions[i * 3], p->vertex_positions[i * 3 + 1],
                    p->vertex_positions[i * 3 + 2]);
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
    const float aspect = float(c.width) / float(c.height);
    const float half_fov = glm::radians(c.fov_degrees) * 0.5f;
    const float half_fov_min = aspect < 1.0f ? std::atan(std::tan(half_fov) * aspect) : half_fov;
    const float distance = radius / std::sin(half_fov_min);
    const float yaw = glm::radians(c.yaw_degrees), pitch = glm::radians(c.pitch_degrees);
    const glm::vec3 dir(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                        std::cos(yaw) * std::cos(pitch));
    const glm::vec3 eye = center + dir * distance;
    const glm::mat4 view = glm::lookAt(eye, center, glm::vec3(0, 1, 0));
    const float zoomed_half_fov = std::atan(std::tan(half_fov) / c.zoom);
    const float near_plane = std::max(distance - 3.0f * radius, 0.02f * distance);
    const glm::mat4 proj =
        glm::perspective(2.0f * zoomed_half_fov, aspect, near_plane, distance + 3.0f * radius);
    p->view_projection = proj * view;

    SizeParams& s = p->size_params;
    s.view_projection = p->view_projection;
    s.eye = eye;
    s.viewport_height = float(c.height);
    s.max_point_size = c.max_point_size;
    s.smooth_slope = c.smooth_slope;
    s.constant_tone = c.constant_tone;
    // Key light from the upper left, in front of the subject (camera space), to world.
    const glm::vec3 light_view = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.6f));
    s.light_direction = glm::normalize(glm::vec3(glm::inverse(view) * glm::vec4(light_view, 0.0f)));
}

}  // namespace

bool pipeline_init(Pipeline* p, const Asset& asset, const GlApi& gl, const PipelineConfig& config,
                   char* error, size_t error_size) {
    *p = Pipeline();
    p->asset = &asset;
    p->config = config;
    const uint32_t nodes = asset.skinned ? asset.skin.skeleton.node_count : 0;
    const uint32_t joints = asset.skinned ? asset.skin.skeleton.joint_count : 0;
    const size_t verts = asset.mesh.vertex_count, points = asset.points.point_count;
    if (!alloc(&p->locals, nodes) || !alloc(&p->models, nodes) ||
        !alloc(&p->skin_matrices, joints) || !alloc(&p->vertex_positions, verts * 3) ||
        !alloc(&p->vertex_normals, verts * 3) || !alloc(&p->point_positions, points * 3) ||
        !alloc(&p->point_normals, points * 3) || !alloc(&p->rest_radius, points) ||
        !alloc(&p->radius, points) || !alloc(&p->size, points) ||
        !alloc(&p->radius_scale, points) ||
        !alloc(&p->triangle_front, asset.mesh.triangle_count) ||
        !alloc(&p->lines, size_t(asset.edges.edge_count) * 6)) {
        std::snprintf(error, error_size, "out of memory for %zu points", points);
        return false;
    }
    // Bind pose (the bake's space): how each baked radius relates to its neighbour distances.
    place_points(asset.points, asset.mesh.indices, asset.mesh.positions, asset.mesh.normals,
                 p->point_positions.get(), p->point_normals.get());
    relevance_scale(asset.points, p->point_positions.get(), p->radius_scale.get());
    // Rest pose: camera bounds, and the radii used when relevance updates are off (the baked
    // radii expressed in the same space as the posed mesh).
    Clock::time_point clock = Clock::now();
    pose_mesh(p, -1, 0.0f, nullptr, &clock);
    place_points(asset.points, asset.mesh.indices, p->vertex_positions.get(),
                 p->vertex_normals.get(), p->point_positions.get(), p->point_normals.get());
    recompute_relevance(asset.points, p->point_positions.get(), p->radius_scale.get(),
                        asset.points.radius, p->rest_radius.get());
    setup_camera(p);

    RendererConfig rc;
    rc.width = config.width;
    rc.height = config.height;
    rc.max_points = asset.points.point_count;
    rc.vertex_count = asset.mesh.vertex_count;
    rc.max_lines = asset.edges.edge_count;
    rc.line_width = config.line_width;
    rc.indices = asset.mesh.indices;
    rc.triangle_count = asset.mesh.triangle_count;
    std::memcpy(rc.background, config.background, sizeof(rc.background));
    return renderer_init(&p->renderer, gl, rc, error, error_size);
}

void pipeline_frame(Pipeline* p, int clip, float time, StageTimes* t) {
    const Asset& a = *p->asset;
    Clock::time_point clock = Clock::now();
    pose_mesh(p, clip, time, t, &clock);
    place_points(a.points, a.mesh.indices, p->vertex_positions.get(), p->vertex_normals.get(),
                 p->point_positions.get(), p->point_normals.get());
    if (t) t->place += ms_since(&clock);
    const float* radius = p->rest_radius.get();
    if (p->config.relevance_update) {
        recompute_relevance(a.points, p->point_positions.get(), p->radius_scale.get(),
                            p->rest_radius.get(), p->radius.get());
        radius = p->radius.get();
    }
    if (t) t->relevance += ms_since(&clock);
    size_stipples(a.points.point_count, p->point_positions.get(), p->point_normals.get(), radius,
                  p->size_params, p->size.get());
    uint32_t drawn = 0;
    for (uint32_t i = 0; i < a.points.point_count; ++i) drawn += p->size[i] > 0.0f;
    p->points_drawn = drawn;
    if (t) t->size += ms_since(&clock);
    p->lines_drawn = 0;
    if (p->config.silhouettes && a.edges.edge_count > 0) {
        triangle_facing(a.mesh.triangle_count, a.mesh.indices, p->vertex_positions.get(),
                        p->size_params.eye, p->triangle_front.get());
        p->lines_drawn = silhouette_lines(a.edges, p->triangle_front.get(),
                                          p->vertex_positions.get(), p->lines.get());
    }
    if (t) t->silhouette += ms_since(&clock);
    renderer_draw_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                       a.mesh.vertex_count);
    renderer_draw_lines(&p->renderer, p->view_projection, p->lines.get(), p->lines_drawn);
    renderer_draw_points(&p->renderer, p->view_projection, p->point_positions.get(),
                         p->size.get(), a.points.point_count);
    p->renderer.gl.Finish();
    if (t) t->draw += ms_since(&clock);
}

glm::vec3 pipeline_project(const Pipeline& p, uint32_t i) {
    const glm::vec4 clip = p.view_projection * glm::vec4(p.point_positions[i * 3],
                                                         p.point_positions[i * 3 + 1],
                                                         p.point_positions[i * 3 + 2], 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return glm::vec3((ndc.x * 0.5f + 0.5f) * float(p.config.width),
                     (0.5f - ndc.y * 0.5f) * float(p.config.height), ndc.z * 0.5f + 0.5f);
}

void pipeline_destroy(Pipeline* p) {
    renderer_destroy(&p->renderer);
    *p = Pipeline();
}

}  // namespace stipple
