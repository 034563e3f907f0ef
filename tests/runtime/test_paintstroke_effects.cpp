// Unit tests of the paintstroke effects (GI'98 §4.4, §5): normals (eq. 2, nudge), lengthwise
// opacity (eq. 3), breadthwise opacity (eqs. 4-5), global shading (eq. 6) and the linear
// interpolation of the per-point attributes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "runtime/paintstroke.h"
#include "runtime/paintstroke_breadthwise.h"

namespace {

using stipple::StrokePoint;

StrokePoint pt(glm::vec3 pos, float r) {
    StrokePoint p;
    p.position = pos;
    p.radius = r;
    p.colour = glm::vec3(0.2f, 0.4f, 0.6f);
    p.reflectance = 0.5f;
    return p;
}

struct Mesh {
    std::vector<stipple::StrokeVertex> v = std::vector<stipple::StrokeVertex>(4096);
    std::vector<uint32_t> i = std::vector<uint32_t>(16384);
    std::vector<stipple::StrokeSegment> s = std::vector<stipple::StrokeSegment>(512);
    stipple::StrokeMesh m;
    Mesh() {
        m.vertices = v.data();
        m.vertex_capacity = uint32_t(v.size());
        m.indices = i.data();
        m.index_capacity = uint32_t(i.size());
        m.segments = s.data();
        m.segment_capacity = uint32_t(s.size());
    }
};

stipple::StrokeCamera camera() {
    stipple::StrokeCamera c;
    c.focal_px = 1000.0f;
    return c;
}

// One segment per two-point stroke: its rings sit exactly at the control points.
stipple::TessellationParams one_segment(int quality) {
    stipple::TessellationParams p;
    p.tol_theta_px = 1e9f;
    p.tol_z_px = 1e9f;
    p.quality = quality;
    p.end_caps = false;
    return p;
}

glm::vec3 vpos(const stipple::StrokeVertex& v) {
    return glm::vec3(v.position[0], v.position[1], v.position[2]);
}
glm::vec3 vnorm(const stipple::StrokeVertex& v) {
    return glm::vec3(v.normal[0], v.normal[1], v.normal[2]);
}

TEST(PaintstrokeEffects, LengthwiseOpacityFollowsEquation3) {
    // A straight segment starting at P0 on the view axis, its direction at angle psi to the
    // view vector: alpha = |cos psi|, op_len = alpha op_max + (1 - alpha) op_min (eq. 3 as
    // printed: op_max looking along the path, op_min broadside).
    const float op_min = 0.2f, op_max = 0.9f;
    for (float deg : {0.0f, 30.0f, 45.0f, 60.0f, 90.0f, 120.0f}) {
        const float psi = glm::radians(deg);
        const glm::vec3 p0(0, 0, -5);
        const glm::vec3 dir(std::sin(psi), 0.0f, -std::cos(psi));  // view at P0 is (0, 0, -1)
        StrokePoint p[2] = {pt(p0, 0.1f), pt(p0 + dir, 0.1f)};
        for (auto& q : p) {
            q.op_min = op_min;
            q.op_max = op_max;
        }
        for (int quality : {0, 1, 2}) {
            Mesh mesh;
            stipple::tessellate_stroke(p, 2, {}, 0, camera(), one_segment(quality), &mesh.m,
                                       nullptr);
            ASSERT_EQ(mesh.m.segment_count, 1u);
            const float alpha = std::fabs(std::cos(psi));
            const float expect = alpha * op_max + (1.0f - alpha) * op_min;
            // Style opacities 1: the vertex alpha is op_len.
            for (int k = 0; k < stipple::ring_front_count(quality); ++k)
                EXPECT_NEAR(mesh.v[k].colour[3], expect, 1e-5f) << deg << " q" << quality;
        }
    }
    EXPECT_NEAR(stipple::lengthwise_opacity(0.1f, 0.7f, glm::vec3(0, 0, -3), glm::vec3(0, 0, 2)),
                0.7f, 1e-6f);
    EXPECT_NEAR(stipple::lengthwise_opacity(0.1f, 0.7f, glm::vec3(0, 0, -3), glm::vec3(1, 0, 0)),
                0.1f, 1e-6f);
}

TEST(PaintstrokeEffects, BreadthwiseOpacityFollowsEquations4And5) {
    // Straight tube seen broadside: the normals of the ring are its unit out directions, so
    // s = 0 at the edges, 1 at the centre and cos 45 deg = 0.7071 at the mids.
    StrokePoint p[2] = {pt(glm::vec3(-0.5f, 0, -5), 0.1f), pt(glm::vec3(0.5f, 0, -5), 0.1f)};
    for (auto& q : p) q.op_min = q.op_max = 0.8f;
    stipple::StrokeStyle style;
    style.op_centre = 0.9f;
    style.op_edge = 0.1f;
    Mesh mesh;
    stipple::tessellate_stroke(p, 2, style, 0, camera(), one_segment(2), &mesh.m, nullptr);
    ASSERT_EQ(mesh.m.vertex_count, 10u);
    // Ring A vertices 0..4: edge, mid, centre, mid, edge. View at P0 is not along -z exactly,
    // so compute s_i from the vertex normals and the view vector (eq. 4).
    const glm::vec3 view = glm::normalize(p[0].position);
    float dots[5], max_dot = -1.0f;
    for (int k = 0; k < 5; ++k) {
        dots[k] = glm::dot(glm::normalize(vnorm(mesh.v[k])), -view);
        max_dot = std::max(max_dot, dots[k]);
    }
    const float op_len = 0.8f;
    for (int k = 0; k < 5; ++k) {
        const float s = std::max(dots[k] / max_dot, 0.0f);
        EXPECT_NEAR(mesh.v[k].colour[3], op_len * ((1 - s) * 0.1f + s * 0.9f), 1e-5f);
    }
    EXPECT_NEAR(mesh.v[0].colour[3], op_len * 0.1f, 1e-5f);  // edge: op_edge
    EXPECT_NEAR(mesh.v[2].colour[3], op_len * 0.9f, 1e-5f);  // centre: op_centre
    const float s_mid = 0.70710678f;
    EXPECT_NEAR(mesh.v[1].colour[3], op_len * ((1 - s_mid) * 0.1f + s_mid * 0.9f), 1e-4f);
    EXPECT_NEAR(mesh.v[3].colour[3], mesh.v[1].colour[3], 1e-5f);
    // Quality 0: no breadthwise variation (§4.3.1 (4)): the body opacity op_centre.
    Mesh m0;
    stipple::tessellate_stroke(p, 2, style, 0, camera(), one_segment(0), &m0.m, nullptr);
    ASSERT_EQ(m0.m.vertex_count, 4u);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(m0.v[k].colour[3], op_len * 0.9f, 1e-5f);
}

TEST(PaintstrokeEffects, NormalsFollowEquation2) {
    // A truncated cone along x, radius 0.1 -> 0.3 over length 1 (dr/ds = 0.2): each ring normal
    // out + adj is perpendicular to the cone's generator joining matching ring vertices, and
    // adj = -rad' / |pos'|^2 pos'.
    const StrokePoint p[2] = {pt(glm::vec3(-0.5f, 0, -5), 0.1f), pt(glm::vec3(0.5f, 0, -5), 0.3f)};
    Mesh mesh;
    stipple::tessellate_stroke(p, 2, {}, 0, camera(), one_segment(2), &mesh.m, nullptr);
    const uint32_t ring = mesh.m.vertex_count / 2;
    ASSERT_GE(ring, 5u);
    for (uint32_t k = 0; k < ring; ++k) {
        const glm::vec3 gen = vpos(mesh.v[ring + k]) - vpos(mesh.v[k]);
        EXPECT_NEAR(glm::dot(glm::normalize(vnorm(mesh.v[k])), glm::normalize(gen)), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(glm::normalize(vnorm(mesh.v[ring + k])), glm::normalize(gen)), 0.0f,
                    1e-5f);
        // Component along the path: -dr/ds = -0.2 with a unit out direction.
        EXPECT_NEAR(vnorm(mesh.v[k]).x, -0.2f, 1e-5f);
    }
    // Quality 0: edge normals nudged toward the centre normal by `nudge`.
    stipple::TessellationParams prm = one_segment(0);
    prm.nudge = 0.5f;
    Mesh m0;
    stipple::tessellate_stroke(p, 2, {}, 0, camera(), prm, &m0.m, nullptr);
    const glm::vec3 centre_n = vnorm(mesh.v[2]);  // quality 2's centre normal at ring A
    const glm::vec3 edge_n = vnorm(mesh.v[0]);
    const glm::vec3 nudged = vnorm(m0.v[0]);
    EXPECT_NEAR(glm::length(nudged - (0.5f * edge_n + 0.5f * centre_n)), 0.0f, 1e-5f);
    EXPECT_GT(glm::dot(glm::normalize(nudged), glm::normalize(centre_n)),
              glm::dot(glm::normalize(edge_n), glm::normalize(centre_n)));
}

double penetration_eq6(double d_gl, double beta) {
    const double a = 1.0 - d_gl;
    return 0.5 * (std::sqrt(a * a * beta * beta - a * a + 1.0) - a * beta);
}

TEST(PaintstrokeEffects, GlobalShadingFollowsEquation6) {
    const glm::vec3 light(0, 0, 1);
    struct Case {
        glm::vec3 n;
        float d;
    };
    const Case cases[] = {{{0, 0, 1}, 0.0f},        {{0, 0, 1}, 0.4f}, {{0, 0, -1}, 0.0f},
                          {{0, 0, -1}, 0.3f},       {{1, 0, 0}, 0.5f}, {{0.6f, 0, 0.8f}, 0.2f},
                          {{0, 0.8f, -0.6f}, 0.7f}, {{0, 0, 1}, 1.0f}};
    for (const Case& c : cases) {
        const double beta = glm::dot(glm::normalize(c.n), light);
        const double p = penetration_eq6(c.d, beta);
        EXPECT_NEAR(stipple::global_penetration(c.n, c.d, light), p, 1e-6);
        const double shade = std::exp(-double(stipple::kGlobalShadingK) * p);
        StrokePoint s[2] = {pt(glm::vec3(-0.5f, 0, -5), 0.1f), pt(glm::vec3(0.5f, 0, -5), 0.1f)};
        s[0].global_normal = c.n;
        s[0].global_depth = c.d;
        stipple::TessellationParams prm = one_segment(1);
        prm.light_eye = light;
        Mesh mesh;
        stipple::tessellate_stroke(s, 2, {}, 0, camera(), prm, &mesh.m, nullptr);
        ASSERT_EQ(mesh.m.vertex_count, 6u);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(mesh.v[k].shade, shade, 1e-6);
            EXPECT_NEAR(mesh.v[k].reflectance, 0.5 * shade, 1e-6);
        }
        // Zero global normal at cp_1: no global shading there.
        for (int k = 3; k < 6; ++k) {
            EXPECT_EQ(mesh.v[k].shade, 1.0f);
            EXPECT_EQ(mesh.v[k].reflectance, 0.5f);
        }
    }
    // Known geometry: lit side on the surface p = 0; centre of the sphere p = 1/2; the far
    // side on the surface p = 1 (a chord through the whole sphere).
    EXPECT_NEAR(stipple::global_penetration({0, 0, 1}, 0.0f, light), 0.0f, 1e-6f);
    EXPECT_NEAR(stipple::global_penetration({0, 0, 1}, 1.0f, light), 0.5f, 1e-6f);
    EXPECT_NEAR(stipple::global_penetration({0, 0, -1}, 0.0f, light), 1.0f, 1e-6f);
    EXPECT_EQ(stipple::global_shade({0, 0, 0}, 0.5f, light), 1.0f);
}

TEST(PaintstrokeEffects, AttributesInterpolateLinearly) {
    // Three evenly spaced collinear points: pos(t) is linear in each section (so t follows x),
    // while the bulging radius forces lengthwise splits (radius constraint). Colour,
    // reflectance and op_min interpolate linearly between the control points.
    StrokePoint p[3] = {pt(glm::vec3(-1, 0, -3), 0.1f), pt(glm::vec3(0, 0, -3), 0.4f),
                        pt(glm::vec3(1, 0, -3), 0.1f)};
    p[0].colour = glm::vec3(1, 0, 0);
    p[1].colour = glm::vec3(0, 1, 0);
    p[2].colour = glm::vec3(0, 0, 1);
    p[0].reflectance = 0.0f;
    p[1].reflectance = 1.0f;
    p[2].reflectance = 0.5f;
    p[0].op_min = 0.2f;
    p[1].op_min = 0.6f;
    p[2].op_min = 0.0f;
    for (auto& q : p) q.op_max = 1.0f;
    stipple::TessellationParams prm = one_segment(0);
    prm.tol_z_px = 0.1f;
    Mesh mesh;
    stipple::tessellate_stroke(p, 3, {}, 0, camera(), prm, &mesh.m, nullptr);
    ASSERT_GT(mesh.m.segment_count, 6u);
    int interior = 0;
    for (uint32_t k = 0; k < mesh.m.vertex_count; k += 2) {
        // Centre of the ring = mean of its two edge vertices.
        const glm::vec3 centre = 0.5f * (vpos(mesh.v[k]) + vpos(mesh.v[k + 1]));
        const int m = centre.x < 0.0f ? 0 : 1;
        const float t = centre.x - (m == 0 ? -1.0f : 0.0f);
        interior += t > 0.01f && t < 0.99f;
        const auto lerp = [&](float a, float b) { return a + (b - a) * t; };
        EXPECT_NEAR(mesh.v[k].colour[0], lerp(p[m].colour.r, p[m + 1].colour.r), 1e-5f);
        EXPECT_NEAR(mesh.v[k].colour[1], lerp(p[m].colour.g, p[m + 1].colour.g), 1e-5f);
        EXPECT_NEAR(mesh.v[k].colour[2], lerp(p[m].colour.b, p[m + 1].colour.b), 1e-5f);
        EXPECT_NEAR(mesh.v[k].reflectance, lerp(p[m].reflectance, p[m + 1].reflectance), 1e-5f);
        const float alpha = std::fabs(glm::normalize(centre).x);  // eq. 3 for a path along x
        const float op_min = lerp(p[m].op_min, p[m + 1].op_min);
        EXPECT_NEAR(mesh.v[k].colour[3], alpha + (1 - alpha) * op_min, 1e-4f);
    }
    EXPECT_GT(interior, 4);
}

}  // namespace
