#include "bench/paintstroke_scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "runtime/stroke_sort.h"

namespace stipple::bench {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kSpacing = 3.0f;                              // between tube centres
constexpr float kDistances[kScales] = {16.0f, 32.0f, 64.0f};  // camera to cluster centre
constexpr float kFovY = 45.0f;                                // degrees
constexpr float kElevation = 25.0f;                           // degrees

struct Lcg {
    uint32_t state;
    float next() {  // [0, 1)
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    }
};

glm::mat3 rotation(glm::vec3 axis, float angle) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)));
}

// Uniform Catmull-Rom through p1 (t = 0) and p2 (t = 1): value and derivative.
template <class T>
void catmull_rom(const T& p0, const T& p1, const T& p2, const T& p3, float t, T* value, T* deriv) {
    const T a = p1 * 2.0f;
    const T b = p2 - p0;
    const T c = p0 * 2.0f - p1 * 5.0f + p2 * 4.0f - p3;
    const T d = p1 * 3.0f - p0 - p2 * 3.0f + p3;
    *value = (a + b * t + c * (t * t) + d * (t * t * t)) * 0.5f;
    *deriv = (b + c * (2.0f * t) + d * (3.0f * t * t)) * 0.5f;
}

// Rotation-minimising frame step (Wang et al. 2008, double reflection): carries `u` from
// (x0, t0) to (x1, t1).
glm::vec3 transport(glm::vec3 x0, glm::vec3 t0, glm::vec3 u, glm::vec3 x1, glm::vec3 t1) {
    const glm::vec3 v1 = x1 - x0;
    const float c1 = glm::dot(v1, v1);
    if (c1 < 1e-20f) return glm::normalize(u - glm::dot(u, t1) * t1);
    const glm::vec3 ul = u - (2.0f / c1) * glm::dot(v1, u) * v1;
    const glm::vec3 tl = t0 - (2.0f / c1) * glm::dot(v1, t0) * v1;
    const glm::vec3 v2 = t1 - tl;
    const float c2 = glm::dot(v2, v2);
    glm::vec3 r = c2 < 1e-20f ? ul : ul - (2.0f / c2) * glm::dot(v2, ul) * v2;
    r -= glm::dot(r, t1) * t1;
    return glm::normalize(r);
}

// Parameters (section + t) of the rings of one tube: a segment is halved while its end
// tangents differ by more than `tolerance` or its midpoint radius is off the chord's by more
// than 2% of the radius.
void split(const StrokePoint* p, int section, float a, float b, const PathSample& sa,
           const PathSample& sb, float tolerance, int depth, std::vector<float>* out) {
    const float m = 0.5f * (a + b);
    const PathSample sm = eval_path(p, kTubePoints, section, m);
    const float cosang = glm::dot(glm::normalize(sa.d_pos), glm::normalize(sb.d_pos));
    const bool bent = cosang < std::cos(tolerance);
    const bool swell = std::fabs(sm.rad - 0.5f * (sa.rad + sb.rad)) > 0.02f * sm.rad;
    if (depth < 10 && (bent || swell)) {
        split(p, section, a, m, sa, sm, tolerance, depth + 1, out);
        out->push_back(float(section) + m);
        split(p, section, m, b, sm, sb, tolerance, depth + 1, out);
    }
}

StrokeVertex make_vertex(glm::vec3 pos, glm::vec3 normal, const StrokePoint& cp) {
    StrokeVertex v = {};
    for (int k = 0; k < 3; ++k) {
        v.position[k] = pos[k];
        v.normal[k] = normal[k];
        v.colour[k] = cp.colour[k];
    }
    v.colour[3] = 1.0f;
    v.reflectance = cp.reflectance;
    v.shade = 1.0f;
    return v;
}

// A flat end cap: a fan over ring `ring_start`'s positions with normal `n`.
void add_cap(StaticModel* m, uint32_t ring_start, int sides, glm::vec3 n, bool flip) {
    const uint32_t base = uint32_t(m->vertices.size());
    for (int j = 0; j < sides; ++j) {
        StrokeVertex v = m->vertices[ring_start + uint32_t(j)];
        v.normal[0] = n.x;
        v.normal[1] = n.y;
        v.normal[2] = n.z;
        m->vertices.push_back(v);
    }
    for (int j = 1; j + 1 < sides; ++j) {
        const uint32_t b = base + uint32_t(flip ? j + 1 : j), c = base + uint32_t(flip ? j : j + 1);
        m->indices.insert(m->indices.end(), {base, b, c});
    }
}

void extrude_tube(const Tube& tube, int sides, float tolerance, StaticModel* m) {
    std::vector<float> params = {0.0f};
    for (int s = 0; s + 1 < kTubePoints; ++s) {
        split(tube.points, s, 0.0f, 1.0f, eval_path(tube.points, kTubePoints, s, 0.0f),
              eval_path(tube.points, kTubePoints, s, 1.0f), tolerance, 0, &params);
        params.push_back(float(s + 1));
    }
    const uint32_t first = uint32_t(m->vertices.size());
    glm::vec3 prev_x(0.0f), prev_t(0.0f), u(0.0f);
    for (size_t i = 0; i < params.size(); ++i) {
        const int section = std::min(int(params[i]), kTubePoints - 2);
        const float t = params[i] - float(section);
        const PathSample ps = eval_path(tube.points, kTubePoints, section, t);
        const glm::vec3 tan = glm::normalize(ps.d_pos);
        if (i == 0) {
            const glm::vec3 any = std::fabs(tan.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            u = glm::normalize(glm::cross(tan, any));
        } else {
            u = transport(prev_x, prev_t, u, ps.pos, tan);
        }
        const glm::vec3 w = glm::cross(tan, u);                // u x w = tan
        const float slope = ps.d_rad / glm::length(ps.d_pos);  // d radius / d arc length
        const StrokePoint& cp = tube.points[std::min(int(params[i] + 0.5f), kTubePoints - 1)];
        for (int j = 0; j < sides; ++j) {
            const float a = 2.0f * kPi * float(j) / float(sides);
            const glm::vec3 radial = std::cos(a) * u + std::sin(a) * w;
            m->vertices.push_back(
                make_vertex(ps.pos + ps.rad * radial, glm::normalize(radial - slope * tan), cp));
        }
        prev_x = ps.pos;
        prev_t = tan;
    }
    const uint32_t rings = uint32_t(params.size()), n = uint32_t(sides);
    for (uint32_t i = 0; i + 1 < rings; ++i) {
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t a = first + i * n + j, b = first + i * n + (j + 1) % n;
            const uint32_t c = a + n, d = b + n;
            m->indices.insert(m->indices.end(), {a, b, c, b, d, c});  // outward
        }
    }
    const PathSample s0 = eval_path(tube.points, kTubePoints, 0, 0.0f);
    const PathSample s1 = eval_path(tube.points, kTubePoints, kTubePoints - 2, 1.0f);
    add_cap(m, first, sides, -glm::normalize(s0.d_pos), true);
    add_cap(m, first + (rings - 1) * n, sides, glm::normalize(s1.d_pos), false);
}

}  // namespace

Scene make_gi98_scene(float opacity) {
    Scene scene;
    Lcg rng{12345u};
    const glm::vec3 palette[6] = {{0.85f, 0.30f, 0.25f}, {0.25f, 0.65f, 0.30f},
                                  {0.25f, 0.40f, 0.85f}, {0.85f, 0.70f, 0.25f},
                                  {0.65f, 0.30f, 0.75f}, {0.25f, 0.70f, 0.75f}};
    const float radii[kTubePoints] = {0.10f, 0.19f, 0.24f, 0.18f, 0.11f};
    for (int i = 0; i < kTubeCount; ++i) {
        const glm::vec3 centre =
            kSpacing * glm::vec3(float(i % 3 - 1), float(i / 3 % 3 - 1), float(i / 9 - 1));
        const glm::vec3 axis(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f);
        const glm::mat3 rot = rotation(axis + glm::vec3(0, 0, 1e-3f), 2.0f * kPi * rng.next());
        const float bend = 0.4f + 0.5f * rng.next(), twist = 2.0f * kPi * rng.next();
        const float size = 0.9f + 0.2f * rng.next();
        Tube tube;
        for (int k = 0; k < kTubePoints; ++k) {
            const float s = float(k - 2) / 2.0f;  // -1 .. 1
            const glm::vec3 local(1.3f * s, bend * (1.0f - s * s),
                                  0.3f * std::sin(2.0f * s + twist));
            StrokePoint& p = tube.points[k];
            p.position = centre + rot * (size * local);
            p.radius = size * radii[k];
            p.colour = palette[i % 6];
            p.reflectance = 0.35f;
            p.op_min = opacity;
            p.op_max = opacity < 1.0f ? opacity + 0.5f * (1.0f - opacity) : 1.0f;
        }
        scene.tubes.push_back(tube);
    }
    return scene;
}

const char* scale_name(int scale) {
    static const char* names[kScales] = {"large", "medium", "small"};
    return scale >= 0 && scale < kScales ? names[scale] : "?";
}

View scene_view(int scale, int frame, int width, int height) {
    View v;
    const float a = 2.0f * kPi * float(frame) / float(kFrames);
    const float el = glm::radians(kElevation);
    const float d = kDistances[std::clamp(scale, 0, kScales - 1)];
    const glm::vec3 eye =
        d * glm::vec3(std::cos(el) * std::sin(a), std::sin(el), std::cos(el) * std::cos(a));
    v.view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    v.projection = glm::perspective(glm::radians(kFovY), float(width) / float(height), 0.1f,
                                    4.0f * kDistances[kScales - 1]);
    v.camera.focal_px = 0.5f * float(height) / std::tan(glm::radians(0.5f * kFovY));
    v.camera.near_z = 0.1f;
    v.light_eye = glm::normalize(glm::vec3(0.3f, 0.5f, 1.0f));
    return v;
}

PathSample eval_path(const StrokePoint* p, int count, int section, float t) {
    const int i1 = section, i2 = section + 1;
    const glm::vec3 x1 = p[i1].position, x2 = p[i2].position;
    const glm::vec3 x0 = i1 > 0 ? p[i1 - 1].position : 2.0f * x1 - x2;
    const glm::vec3 x3 = i2 + 1 < count ? p[i2 + 1].position : 2.0f * x2 - x1;
    const float r1 = p[i1].radius, r2 = p[i2].radius;
    const float r0 = i1 > 0 ? p[i1 - 1].radius : 2.0f * r1 - r2;
    const float r3 = i2 + 1 < count ? p[i2 + 1].radius : 2.0f * r2 - r1;
    PathSample s;
    catmull_rom(x0, x1, x2, x3, t, &s.pos, &s.d_pos);
    catmull_rom(r0, r1, r2, r3, t, &s.rad, &s.d_rad);
    return s;
}

StaticModel build_extrusion(const Scene& scene, int sides, float angle_tolerance) {
    StaticModel m;
    m.sides = sides;
    for (const Tube& tube : scene.tubes) extrude_tube(tube, sides, angle_tolerance, &m);
    m.triangles = uint32_t(m.indices.size() / 3);
    return m;
}

void static_to_eye(const StaticModel& model, const glm::mat4& view, StaticFrame* out) {
    const size_t n = model.vertices.size();
    out->vertices.resize(n);
    out->indices.resize(model.indices.size());
    const glm::mat3 rot(view);
    for (size_t i = 0; i < n; ++i) {
        const StrokeVertex& src = model.vertices[i];
        StrokeVertex& dst = out->vertices[i];
        dst = src;
        const glm::vec3 p =
            glm::vec3(view * glm::vec4(src.position[0], src.position[1], src.position[2], 1.0f));
        const glm::vec3 nn = rot * glm::vec3(src.normal[0], src.normal[1], src.normal[2]);
        for (int k = 0; k < 3; ++k) {
            dst.position[k] = p[k];
            dst.normal[k] = nn[k];
        }
    }
    uint32_t kept = 0;
    for (size_t t = 0; t + 2 < model.indices.size(); t += 3) {
        const uint32_t* tri = &model.indices[t];
        const float* a = out->vertices[tri[0]].position;
        const float* b = out->vertices[tri[1]].position;
        const float* c = out->vertices[tri[2]].position;
        const glm::vec3 pa(a[0], a[1], a[2]);
        const glm::vec3 face =
            glm::cross(glm::vec3(b[0], b[1], b[2]) - pa, glm::vec3(c[0], c[1], c[2]) - pa);
        if (glm::dot(face, pa) >= 0.0f) continue;  // back face (or edge-on)
        out->indices[kept++] = tri[0];
        out->indices[kept++] = tri[1];
        out->indices[kept++] = tri[2];
    }
    out->indices.resize(kept);
    out->rendered_triangles = kept / 3;
}

void stroke_frame_init(StrokeFrame* f, const TessellationParams& params) {
    f->params = params;
    const StrokeMeshBound one = stroke_mesh_bound(kTubePoints, params);
    f->bound.vertices = one.vertices * kTubeCount;
    f->bound.indices = one.indices * kTubeCount;
    f->bound.segments = one.segments * kTubeCount;
    f->vertices.reset(new StrokeVertex[f->bound.vertices]);
    f->indices.reset(new uint32_t[f->bound.indices]);
    f->sorted_indices.reset(new uint32_t[f->bound.indices]);
    f->segments.reset(new StrokeSegment[f->bound.segments]);
    f->order.reset(new uint32_t[f->bound.segments]);
    f->scratch.reset(new uint32_t[2 * f->bound.segments]);
    f->eye_points.resize(kTubePoints);
}

void tessellate_scene_only(const Scene& scene, const View& view, StrokeFrame* f) {
    StrokeMesh& m = f->mesh;
    m = StrokeMesh();
    m.vertices = f->vertices.get();
    m.vertex_capacity = uint32_t(f->bound.vertices);
    m.indices = f->indices.get();
    m.index_capacity = uint32_t(f->bound.indices);
    m.segments = f->segments.get();
    m.segment_capacity = uint32_t(f->bound.segments);
    f->stats = TessellationStats();
    TessellationParams params = f->params;
    params.light_eye = view.light_eye;
    const StrokeStyle style;
    for (size_t i = 0; i < scene.tubes.size(); ++i) {
        for (int k = 0; k < kTubePoints; ++k) {
            StrokePoint p = scene.tubes[i].points[k];
            p.position = glm::vec3(view.view * glm::vec4(p.position, 1.0f));
            f->eye_points[size_t(k)] = p;
        }
        tessellate_stroke(f->eye_points.data(), kTubePoints, style, uint32_t(i), view.camera,
                          params, &m, &f->stats);
    }
}

void tessellate_scene(const Scene& scene, const View& view, StrokeFrame* f) {
    tessellate_scene_only(scene, view, f);
    sort_segments_back_to_front(f->mesh, f->order.get(), f->scratch.get());
    gather_sorted_indices(f->mesh, f->order.get(), f->sorted_indices.get());
}

bool target_init(const GlApi& gl, int width, int height, Target* t) {
    t->width = width;
    t->height = height;
    gl.GenFramebuffers(1, &t->fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    gl.GenRenderbuffers(1, &t->colour);
    gl.BindRenderbuffer(GL_RENDERBUFFER, t->colour);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->colour);
    gl.GenRenderbuffers(1, &t->depth);
    gl.BindRenderbuffer(GL_RENDERBUFFER, t->depth);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    gl.Viewport(0, 0, width, height);
    return gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

void target_clear(const GlApi& gl, const Target& t) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    gl.Viewport(0, 0, t.width, t.height);
    gl.DepthMask(GL_TRUE);
    gl.ClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void target_read(const GlApi& gl, const Target& t, uint8_t* rgba) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

void target_destroy(const GlApi& gl, Target* t) {
    if (t->fbo) gl.DeleteFramebuffers(1, &t->fbo);
    if (t->colour) gl.DeleteRenderbuffers(1, &t->colour);
    if (t->depth) gl.DeleteRenderbuffers(1, &t->depth);
    *t = Target();
}

}  // namespace stipple::bench
