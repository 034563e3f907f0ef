// Unit tests of the paintstroke geometry (GI'98 §3-§4): the Catmull-Rom interpolants,
// lengthwise subdivision (Position Constraints I and II, radius constraint, inflections),
// breadthwise out vectors, silhouette width, cracks, head-on visibility, hidden back sides,
// buffer capacities and the mesh bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "runtime/paintstroke.h"
#include "runtime/paintstroke_breadthwise.h"
#include "runtime/paintstroke_curve.h"
#include "runtime/paintstroke_lengthwise.h"

namespace {

using stipple::StrokePoint;

StrokePoint pt(float x, float y, float z, float r) {
    StrokePoint p;
    p.position = glm::vec3(x, y, z);
    p.radius = r;
    p.colour = glm::vec3(0.5f);
    return p;
}

struct Mesh {
    std::vector<stipple::StrokeVertex> v;
    std::vector<uint32_t> i;
    std::vector<stipple::StrokeSegment> s;
    stipple::StrokeMesh m;
    Mesh(uint32_t nv, uint32_t ni, uint32_t ns) : v(nv), i(ni), s(ns) {
        m.vertices = v.data();
        m.vertex_capacity = nv;
        m.indices = i.data();
        m.index_capacity = ni;
        m.segments = s.data();
        m.segment_capacity = ns;
    }
};

stipple::StrokeCamera camera(float focal = 1000.0f) {
    stipple::StrokeCamera c;
    c.focal_px = focal;
    c.near_z = 0.01f;
    return c;
}

// Large tolerances: no subdivision beyond what is tested.
stipple::TessellationParams loose(int quality) {
    stipple::TessellationParams p;
    p.tol_theta_px = 1e9f;
    p.tol_z_px = 1e9f;
    p.quality = quality;
    p.end_caps = false;
    return p;
}

glm::vec2 project(const float* p, float f) {
    return glm::vec2(f * p[0] / -p[2], f * p[1] / -p[2]);
}

// Vertex range [lo, hi] used by one segment.
void segment_vertices(const Mesh& mesh, const stipple::StrokeSegment& s, uint32_t* lo,
                      uint32_t* hi) {
    *lo = 0xffffffffu;
    *hi = 0;
    for (uint32_t k = 0; k < s.index_count; ++k) {
        *lo = std::min(*lo, mesh.i[s.first_index + k]);
        *hi = std::max(*hi, mesh.i[s.first_index + k]);
    }
}

// Screen area of a segment's triangles (sum of |area|).
double projected_area(const Mesh& mesh, const stipple::StrokeSegment& s, float f) {
    double area = 0.0;
    for (uint32_t k = 0; k < s.index_count; k += 3) {
        const glm::vec2 a = project(mesh.v[mesh.i[s.first_index + k]].position, f);
        const glm::vec2 b = project(mesh.v[mesh.i[s.first_index + k + 1]].position, f);
        const glm::vec2 c = project(mesh.v[mesh.i[s.first_index + k + 2]].position, f);
        area += 0.5 * std::fabs(double((b - a).x) * (c - a).y - double((b - a).y) * (c - a).x);
    }
    return area;
}

TEST(PaintstrokeCurve, SectionsInterpolateControlPointsExactly) {
    const StrokePoint p[4] = {pt(0, 0, -5, 0.1f), pt(0.3f, 0.7f, -5.5f, 0.2f),
                              pt(1.1f, 0.2f, -4.7f, 0.05f), pt(1.7f, -0.3f, -6.1f, 0.3f)};
    for (uint32_t m = 0; m < 3; ++m) {
        const stipple::SectionCurve s = stipple::make_section_curve(p, 4, m);
        EXPECT_EQ(stipple::section_pos(s, 0.0f), p[m].position);
        EXPECT_EQ(stipple::section_pos(s, 1.0f), p[m + 1].position);
        EXPECT_EQ(stipple::section_rad(s, 0.0f), p[m].radius);
        EXPECT_EQ(stipple::section_rad(s, 1.0f), p[m + 1].radius);
        // The polynomial itself reaches the next control point (up to rounding).
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(stipple::cubic_value(s.pos[k], 1.0f), p[m + 1].position[k], 1e-5f);
        EXPECT_NEAR(glm::length(stipple::section_pos_d1(s, 1.0f) -
                                glm::vec3(stipple::cubic_d1(s.pos[0], 1.0f),
                                          stipple::cubic_d1(s.pos[1], 1.0f),
                                          stipple::cubic_d1(s.pos[2], 1.0f))),
                    0.0f, 1e-5f);
        if (m > 0) {
            // Joints: both sections give the same tangent bit for bit.
            const stipple::SectionCurve prev = stipple::make_section_curve(p, 4, m - 1);
            EXPECT_EQ(stipple::section_pos_d1(prev, 1.0f), stipple::section_pos_d1(s, 0.0f));
            EXPECT_EQ(stipple::section_rad_d1(prev, 1.0f), stipple::section_rad_d1(s, 0.0f));
        }
    }
    // Interior tangent: Catmull-Rom (cp_{m+1} - cp_{m-1}) / 2.
    const stipple::SectionCurve s1 = stipple::make_section_curve(p, 4, 1);
    const glm::vec3 expect = 0.5f * (p[2].position - p[0].position);
    EXPECT_NEAR(glm::length(stipple::section_pos_d1(s1, 1e-7f) - expect), 0.0f, 1e-4f);
    // Reflected end points: a two-point stroke is a uniformly parametrised straight line.
    const StrokePoint two[2] = {pt(0, 0, -5, 0.1f), pt(2, 1, -7, 0.3f)};
    const stipple::SectionCurve s = stipple::make_section_curve(two, 2, 0);
    for (float t : {0.25f, 0.5f, 0.8f}) {
        const glm::vec3 lin = two[0].position + t * (two[1].position - two[0].position);
        EXPECT_NEAR(glm::length(stipple::section_pos(s, t) - lin), 0.0f, 1e-5f);
        EXPECT_NEAR(stipple::section_rad(s, t), 0.1f + 0.2f * t, 1e-6f);
    }
}

// Simpson's rule with n (even) steps.
template <typename F>
double simpson(F f, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int k = 1; k < n; ++k) sum += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
    return sum * h / 3.0;
}

TEST(PaintstrokeLengthwise, LinearityIntegralsMatchNumericIntegration) {
    const StrokePoint p[4] = {pt(0, 0, -3, 0.1f), pt(0.2f, 0.5f, -4.5f, 0.4f),
                              pt(0.9f, 0.1f, -3.2f, 0.05f), pt(1.4f, 0.3f, -6.0f, 0.3f)};
    const float f = 800.0f;
    for (uint32_t m = 0; m < 3; ++m) {
        const stipple::SectionCurve s = stipple::make_section_curve(p, 4, m);
        for (const auto& ab : {std::make_pair(0.0f, 1.0f), std::make_pair(0.1f, 0.35f),
                               std::make_pair(0.5f, 0.75f), std::make_pair(0.625f, 1.0f)}) {
            const float a = ab.first, b = ab.second;
            const double za = stipple::section_pos(s, a).z, zb = stipple::section_pos(s, b).z;
            const double zavg =
                simpson([&](double t) { return double(stipple::cubic_value(s.pos[2], float(t))); },
                        a, b, 2000) /
                (b - a);
            const double expect_z = f / std::fabs(za) * std::fabs(zavg - 0.5 * (za + zb));
            EXPECT_NEAR(stipple::z_nonlinearity_px(s, a, b, f), expect_z, 1e-3 + 1e-4 * expect_z);
            const double ra = stipple::section_rad(s, a), rb = stipple::section_rad(s, b);
            const double ravg =
                simpson([&](double t) { return double(stipple::cubic_value(s.rad, float(t))); }, a,
                        b, 2000) /
                (b - a);
            const double expect_r = f / std::fabs(za) * std::fabs(ravg - 0.5 * (ra + rb));
            EXPECT_NEAR(stipple::rad_nonlinearity_px(s, a, b, f), expect_r, 1e-3 + 1e-4 * expect_r);
            EXPECT_GT(expect_z + expect_r, 0.0);  // non-trivial sections
        }
    }
}

// Screen position of the outside boundary, computed by finite differences (independent of the
// analytic derivatives in the library).
glm::dvec2 scr(const stipple::SectionCurve& s, double t, double f) {
    double p[3];
    for (int k = 0; k < 3; ++k) {
        const float* c = s.pos[k].c;
        p[k] = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    }
    return glm::dvec2(f * p[0] / -p[2], f * p[1] / -p[2]);
}

glm::dvec2 outside_numeric(const stipple::SectionCurve& s, double t, double f, glm::dvec2* tan) {
    const double h = 1e-4, t0 = t;
    const glm::dvec2 d1 = (scr(s, t0 + h, f) - scr(s, t0 - h, f)) / (2 * h);
    const glm::dvec2 d2 = (scr(s, t0 + h, f) - 2.0 * scr(s, t0, f) + scr(s, t0 - h, f)) / (h * h);
    *tan = d1;
    glm::dvec2 n = glm::normalize(glm::dvec2(d1.y, -d1.x));
    if (glm::dot(n, d2) > 0) n = -n;
    const glm::vec3 p = stipple::section_pos(s, float(t));
    return scr(s, t, f) + n * (f * stipple::section_rad(s, float(t)) / -p.z);
}

TEST(PaintstrokeLengthwise, PositionConstraintOneSplitsExactlyBeyondThetaMax) {
    // A bend in the screen plane: theta between the end tangents of [a, b] is known
    // numerically; cos^2(theta_max) = d^2 / (d^2 + tol^2) puts the threshold at
    // tol = d tan(theta).
    const StrokePoint p[3] = {pt(-1, 0, -6, 0.08f), pt(0, 0.6f, -6, 0.1f), pt(1, 0, -6, 0.08f)};
    const float f = 500.0f;
    const stipple::SectionCurve s = stipple::make_section_curve(p, 3, 0);
    for (const auto& ab :
         {std::make_pair(0.0f, 1.0f), std::make_pair(0.25f, 0.5f), std::make_pair(0.5f, 0.625f)}) {
        glm::dvec2 ta, tb;
        const glm::dvec2 oa = outside_numeric(s, ab.first, f, &ta);
        const glm::dvec2 ob = outside_numeric(s, ab.second, f, &tb);
        const double cos_t = glm::dot(glm::normalize(ta), glm::normalize(tb));
        ASSERT_GT(cos_t, 0.0);
        const double theta = std::acos(std::min(cos_t, 1.0));
        const double d = glm::length(ob - oa);
        const double tol_at_threshold = d * std::tan(theta);
        const stipple::PositionConstraint1 below = stipple::position_constraint_1(
            s, ab.first, ab.second, f, float(0.97 * tol_at_threshold));
        const stipple::PositionConstraint1 above = stipple::position_constraint_1(
            s, ab.first, ab.second, f, float(1.03 * tol_at_threshold));
        EXPECT_NEAR(below.d, d, 1e-3 * d);
        EXPECT_NEAR(below.cos_theta, cos_t, 1e-4);
        EXPECT_TRUE(below.split) << "theta exceeds theta_max for the smaller tolerance";
        EXPECT_FALSE(above.split) << "theta below theta_max for the larger tolerance";
        const double cos2_max = d * d / (d * d + 0.97 * 0.97 * tol_at_threshold * tol_at_threshold);
        EXPECT_NEAR(below.cos2_max, cos2_max, 1e-4);
    }
    // A U-turn (negative cosine) splits whatever the tolerance.
    const StrokePoint u[4] = {pt(-1, -3, -6, 0.05f), pt(-1, 0.5f, -6, 0.05f),
                              pt(1, 0.5f, -6, 0.05f), pt(1, -3, -6, 0.05f)};
    const stipple::SectionCurve su = stipple::make_section_curve(u, 4, 1);
    const stipple::PositionConstraint1 r = stipple::position_constraint_1(su, 0, 1, f, 1e9f);
    EXPECT_LT(r.cos_theta, 0.0f);
    EXPECT_TRUE(r.split);
}

std::vector<float> boundaries(const stipple::SectionCurve& s, const stipple::TessellationParams& p,
                              uint32_t* inflections) {
    stipple::LengthwiseState st;
    stipple::lengthwise_begin(&st, s, camera(), p);
    std::vector<float> t;
    float a, b;
    while (stipple::lengthwise_next(&st, &a, &b)) {
        if (t.empty()) t.push_back(a);
        EXPECT_EQ(a, t.back());  // contiguous
        t.push_back(b);
    }
    *inflections = st.inflection_splits;
    return t;
}

// Catmull-Rom: the zero of p'' = (2 p0 - 5 p1 + 4 p2 - p3) + 3 (-p0 + 3 p1 - 3 p2 + p3) t.
double cr_inflection(double p0, double p1, double p2, double p3) {
    return -(2 * p0 - 5 * p1 + 4 * p2 - p3) / (3 * (-p0 + 3 * p1 - 3 * p2 + p3));
}

// Tight tolerances, so every inflection matters, but no midpoint recursion: only §4.2.3
// splits.
stipple::TessellationParams inflections_only() {
    stipple::TessellationParams p = loose(2);
    p.tol_theta_px = 1e-4f;
    p.tol_z_px = 1e-4f;
    p.max_depth = 0;
    return p;
}

TEST(PaintstrokeLengthwise, InflectionSplitsAtAnalyticZeros) {
    // pos_z has an inflection inside section 1; x = 0 keeps the path in a plane through the
    // eye (a straight screen line), and constant radius.
    const float z[4] = {-4.0f, -4.2f, -5.5f, -5.6f};
    StrokePoint p[4];
    for (int k = 0; k < 4; ++k) p[k] = pt(0.0f, 0.4f * k, z[k], 0.1f);
    const stipple::SectionCurve s = stipple::make_section_curve(p, 4, 1);
    const double tz = cr_inflection(z[0], z[1], z[2], z[3]);
    ASSERT_GT(tz, 0.05);
    ASSERT_LT(tz, 0.95);
    uint32_t n = 0;
    std::vector<float> t = boundaries(s, inflections_only(), &n);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(n, 1u);
    EXPECT_EQ(t[0], 0.0f);
    EXPECT_NEAR(t[1], tz, 1e-6);
    EXPECT_EQ(t[2], 1.0f);
    EXPECT_NEAR(stipple::section_pos_d2(s, t[1]).z, 0.0f, 1e-5f);

    // rad'' zero: a straight line (y linear, z const) with an S-shaped radius profile.
    const float r[4] = {0.1f, 0.12f, 0.3f, 0.31f};
    for (int k = 0; k < 4; ++k) p[k] = pt(0.0f, 0.4f * k, -5.0f, r[k]);
    const stipple::SectionCurve sr = stipple::make_section_curve(p, 4, 1);
    const double tr = cr_inflection(r[0], r[1], r[2], r[3]);
    t = boundaries(sr, inflections_only(), &n);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(t[1], tr, 1e-6);
    EXPECT_NEAR(stipple::section_rad_d2(sr, t[1]), 0.0f, 1e-5f);

    // Screen-path inflection (orthographic): an S curve in the image plane at constant z.
    // x' y'' - y' x'' changes sign at the split point.
    const float ys[4] = {0.0f, 0.1f, 0.8f, 0.85f};
    for (int k = 0; k < 4; ++k) p[k] = pt(0.5f * k, ys[k], -5.0f, 0.1f);
    const stipple::SectionCurve ss = stipple::make_section_curve(p, 4, 1);
    t = boundaries(ss, inflections_only(), &n);
    ASSERT_EQ(t.size(), 3u);
    const auto curvature = [&](float u) {
        const glm::vec3 d1 = stipple::section_pos_d1(ss, u), d2 = stipple::section_pos_d2(ss, u);
        return d1.x * d2.y - d1.y * d2.x;
    };
    EXPECT_NEAR(curvature(t[1]), 0.0f, 1e-5f);
    EXPECT_LT(curvature(t[1] - 0.01f) * curvature(t[1] + 0.01f), 0.0f);
    EXPECT_NEAR(t[1], cr_inflection(ys[0], ys[1], ys[2], ys[3]), 1e-5);  // x linear: y'' = 0
}

// An inflection that cannot matter is not split: where the function cannot stray from its
// chord by the tolerance anywhere in the section, the constraints it protects already hold.
TEST(PaintstrokeLengthwise, InflectionsBelowTheToleranceAreNotSplit) {
    const float z[4] = {-4.0f, -4.2f, -5.5f, -5.6f};
    StrokePoint p[4];
    for (int k = 0; k < 4; ++k) p[k] = pt(0.0f, 0.4f * k, z[k], 0.1f);
    const stipple::SectionCurve s = stipple::make_section_curve(p, 4, 1);
    uint32_t n = 0;
    stipple::TessellationParams prm = inflections_only();
    EXPECT_EQ(boundaries(s, prm, &n).size(), 3u);  // tol 1e-4 px: split
    prm.tol_z_px = 1e3f;  // far above the z deviation bound of this section
    prm.tol_theta_px = 1e3f;
    EXPECT_EQ(boundaries(s, prm, &n).size(), 2u);
    EXPECT_EQ(n, 0u);
}

TEST(PaintstrokeLengthwise, RespectsDepthLimit) {
    const StrokePoint p[3] = {pt(-1, 0, -3, 0.1f), pt(0, 1.5f, -2, 0.3f), pt(1, 0, -6, 0.02f)};
    const stipple::SectionCurve s = stipple::make_section_curve(p, 3, 0);
    for (int depth : {0, 1, 3, 6}) {
        stipple::TessellationParams prm;
        prm.tol_theta_px = 1e-6f;
        prm.tol_z_px = 1e-9f;
        prm.max_depth = depth;
        uint32_t n = 0;
        const std::vector<float> t = boundaries(s, prm, &n);
        EXPECT_EQ(t.size() - 1, size_t(n + 1) << depth);
        EXPECT_LE(t.size() - 1, stipple::max_segments_per_section(prm));
    }
}

TEST(PaintstrokeLengthwise, PiecesBehindTheEyeAreNotRefined) {
    // A curled section entirely behind the viewer: one segment (later skipped), not 2^depth.
    const StrokePoint p[3] = {pt(-1, 0, 3, 0.1f), pt(0, 1.5f, 2, 0.3f), pt(1, 0, 6, 0.02f)};
    const stipple::SectionCurve s = stipple::make_section_curve(p, 3, 0);
    stipple::TessellationParams prm;
    prm.tol_theta_px = 1e-6f;
    prm.tol_z_px = 1e-9f;
    uint32_t n = 0;
    const size_t segments = boundaries(s, prm, &n).size() - 1;
    EXPECT_EQ(segments, size_t(n + 1));
    Mesh mesh(1024, 4096, 128);
    stipple::tessellate_stroke(p, 3, {}, 0, camera(), prm, &mesh.m, nullptr);
    EXPECT_EQ(mesh.m.segment_count, 0u);
}

TEST(PaintstrokeBreadthwise, OutVectorsPerpendicularToViewAndTangent) {
    const StrokePoint p[4] = {pt(-0.5f, 0.2f, -3, 0.1f), pt(0.3f, 0.9f, -4.5f, 0.4f),
                              pt(0.9f, -0.4f, -2.2f, 0.05f), pt(1.4f, 0.3f, -6.0f, 0.3f)};
    for (uint32_t m = 0; m < 3; ++m) {
        const stipple::SectionCurve s = stipple::make_section_curve(p, 4, m);
        for (float t = 0.0f; t <= 1.0f; t += 0.125f) {
            const stipple::RingFrame f = stipple::ring_frame(s, t);
            const glm::vec3 tu = glm::normalize(f.tangent);
            EXPECT_NEAR(glm::dot(f.edge, tu), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::dot(f.edge, f.view), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::dot(f.centre, tu), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::dot(f.centre, f.edge), 0.0f, 1e-5f);
            EXPECT_GT(glm::dot(f.centre, -f.view), 0.0f);  // toward the viewer
            EXPECT_NEAR(glm::length(f.edge), 1.0f, 1e-5f);
            // Quality-2 ring: every vertex at distance rad from pos(t), in the normal plane;
            // the mids halfway in angle between edge and centre.
            glm::vec3 dirs[8];
            const int n = stipple::ring_directions(f, 2, true, dirs);
            ASSERT_EQ(n, 8);
            for (int k = 0; k < n; ++k) {
                EXPECT_NEAR(glm::length(dirs[k]), 1.0f, 1e-5f);
                EXPECT_NEAR(glm::dot(dirs[k], tu), 0.0f, 1e-5f);
                EXPECT_NEAR(std::acos(glm::clamp(glm::dot(dirs[k], dirs[(k + 1) % 8]), -1.f, 1.f)),
                            0.785398f, 1e-3f);
            }
        }
    }
}

TEST(PaintstrokeBreadthwise, SilhouetteWidthMatchesProjectedDiameter) {
    // A straight tube along x seen from the side at several distances: the edge vertices
    // project 2 focal r / dist apart (within 1 px).
    const float f = 1000.0f, r = 0.1f;
    for (float dist : {1.5f, 3.0f, 8.0f, 25.0f}) {
        for (int q : {0, 1, 2}) {
            const StrokePoint p[3] = {pt(-0.5f, 0.1f, -dist, r), pt(0.0f, 0.1f, -dist, r),
                                      pt(0.5f, 0.1f, -dist, r)};
            Mesh mesh(4096, 16384, 512);
            stipple::TessellationParams prm;
            prm.quality = q;
            prm.end_caps = false;
            stipple::tessellate_stroke(p, 3, {}, 0, camera(f), prm, &mesh.m, nullptr);
            ASSERT_GT(mesh.m.segment_count, 0u);
            const int ring = stipple::ring_size(q, false);
            const int front = stipple::ring_front_count(q);
            ASSERT_EQ(mesh.m.vertex_count, mesh.m.segment_count * 2u * ring);  // no back side
            for (uint32_t k = 0; k < mesh.m.vertex_count; k += ring) {
                const glm::vec2 a = project(mesh.v[k].position, f);
                const glm::vec2 b = project(mesh.v[k + front - 1].position, f);
                EXPECT_NEAR(glm::length(a - b), 2.0f * f * r / dist, 1.0f) << dist << " " << q;
            }
        }
    }
}

TEST(PaintstrokeBreadthwise, NoCracksBetweenSegmentsAndSections) {
    const StrokePoint p[5] = {pt(-1, 0, -4, 0.1f), pt(-0.4f, 0.6f, -4.5f, 0.2f),
                              pt(0.2f, -0.1f, -3.6f, 0.15f), pt(0.9f, 0.5f, -5.0f, 0.05f),
                              pt(1.3f, -0.2f, -4.0f, 0.12f)};
    for (int q : {0, 1, 2}) {
        Mesh mesh(1 << 16, 1 << 18, 1 << 12);
        stipple::TessellationParams prm;
        prm.quality = q;
        prm.end_caps = false;
        prm.tol_theta_px = 0.5f;
        stipple::TessellationStats stats;
        stipple::tessellate_stroke(p, 5, {}, 7, camera(), prm, &mesh.m, &stats);
        ASSERT_GT(mesh.m.segment_count, 8u);
        EXPECT_EQ(stats.sections, 4u);
        const int front = stipple::ring_front_count(q);
        int joints = 0;
        for (uint32_t k = 0; k + 1 < mesh.m.segment_count; ++k) {
            uint32_t lo0, hi0, lo1, hi1;
            segment_vertices(mesh, mesh.s[k], &lo0, &hi0);
            segment_vertices(mesh, mesh.s[k + 1], &lo1, &hi1);
            const uint32_t ring0 = (hi0 - lo0 + 1) / 2;
            // Ring B of segment k and ring A of segment k + 1: identical bits.
            for (int j = 0; j < front; ++j) {
                EXPECT_EQ(std::memcmp(&mesh.v[lo0 + ring0 + j], &mesh.v[lo1 + j],
                                      sizeof(stipple::StrokeVertex)),
                          0)
                    << "quality " << q << " segment " << k << " vertex " << j;
            }
            ++joints;
        }
        // Control points are ring vertices' centres: every section boundary was among them.
        EXPECT_GT(joints, 4);
    }
}

TEST(PaintstrokeBreadthwise, HeadOnQualityOneAndTwoStayVisible) {
    const float f = 1000.0f;
    for (float off : {0.0f, 0.002f}) {
        // Straight tube along the view axis.
        const StrokePoint p[2] = {pt(off, 0, -5, 0.1f), pt(off, 0, -6, 0.1f)};
        double area[3];
        for (int q : {0, 1, 2}) {
            Mesh mesh(1024, 4096, 128);
            stipple::tessellate_stroke(p, 2, {}, 0, camera(f), loose(q), &mesh.m, nullptr);
            area[q] = 0.0;
            for (uint32_t k = 0; k < mesh.m.segment_count; ++k)
                area[q] += projected_area(mesh, mesh.s[k], f);
        }
        // Quality 0 vanishes exactly head-on, and is a sliver just off the axis (the true
        // projection is a 20 px disc).
        if (off == 0.0f) {
            EXPECT_LT(area[0], 1e-2) << "quality 0 vanishes head-on";
        }
        EXPECT_LT(area[0], 0.05 * area[1]);
        // The front half-ring of the near end (radius 20 px) spans a large part of a disc.
        EXPECT_GT(area[1], 50.0);
        EXPECT_GT(area[2], area[1]);
    }
}

TEST(PaintstrokeBreadthwise, HiddenBackSideSuppressed) {
    stipple::TessellationParams prm = loose(2);
    // Straight tube from the side: back side hidden.
    {
        const StrokePoint p[2] = {pt(-1, 0, -5, 0.1f), pt(1, 0, -5, 0.1f)};
        Mesh mesh(1024, 4096, 128);
        stipple::TessellationStats stats;
        stipple::tessellate_stroke(p, 2, {}, 0, camera(), prm, &mesh.m, &stats);
        EXPECT_EQ(stats.back_sides_suppressed, stats.segments);
        EXPECT_EQ(mesh.m.vertex_count, 2u * 5u);
        EXPECT_EQ(mesh.m.index_count, 4u * 6u);
    }
    // Strongly widening away from the viewer, seen along its axis: the far side shows.
    {
        const StrokePoint p[2] = {pt(0.01f, 0, -5, 0.05f), pt(0.01f, 0, -6, 0.8f)};
        Mesh mesh(1024, 4096, 128);
        stipple::TessellationStats stats;
        stipple::tessellate_stroke(p, 2, {}, 0, camera(), prm, &mesh.m, &stats);
        EXPECT_EQ(stats.back_sides_suppressed, 0u);
        EXPECT_EQ(mesh.m.vertex_count, 2u * 8u);
        EXPECT_EQ(mesh.m.index_count, 8u * 6u);
        // Check with the cone's true normals: a far-side vertex faces the eye.
        bool some_far_vertex_faces_eye = false;
        for (int k = 5; k < 8; ++k) {
            const glm::vec3 pos(mesh.v[k].position[0], mesh.v[k].position[1],
                                mesh.v[k].position[2]);
            const glm::vec3 n(mesh.v[k].normal[0], mesh.v[k].normal[1], mesh.v[k].normal[2]);
            some_far_vertex_faces_eye |= glm::dot(n, -pos) > 0.0f;
        }
        EXPECT_TRUE(some_far_vertex_faces_eye);
    }
    // Narrowing away from the viewer: the far side stays hidden.
    {
        const StrokePoint p[2] = {pt(0.01f, 0, -5, 0.8f), pt(0.01f, 0, -6, 0.05f)};
        Mesh mesh(1024, 4096, 128);
        stipple::TessellationStats stats;
        stipple::tessellate_stroke(p, 2, {}, 0, camera(), prm, &mesh.m, &stats);
        EXPECT_EQ(stats.back_sides_suppressed, stats.segments);
    }
}

TEST(PaintstrokeTessellation, EndCapsCloseVisibleEnds) {
    stipple::TessellationParams prm = loose(2);
    prm.end_caps = true;
    // Tube pointing away from the viewer: only the start cap (nearest end) shows.
    const StrokePoint p[2] = {pt(0.3f, 0, -5, 0.1f), pt(0.5f, 0, -6, 0.1f)};
    Mesh mesh(1024, 4096, 128);
    stipple::tessellate_stroke(p, 2, {}, 0, camera(), prm, &mesh.m, nullptr);
    ASSERT_EQ(mesh.m.segment_count, 2u);  // cap + one segment
    EXPECT_EQ(mesh.s[0].index_count, 24u);
    // The cap's vertices lie on the start disc: distance rad from cp_0, perpendicular to pos'.
    const glm::vec3 tan = p[1].position - p[0].position;
    for (uint32_t k = 0; k < 8; ++k) {
        const glm::vec3 v(mesh.v[k].position[0], mesh.v[k].position[1], mesh.v[k].position[2]);
        EXPECT_NEAR(glm::length(v - p[0].position), 0.1f, 1e-5f);
        EXPECT_NEAR(glm::dot(v - p[0].position, tan), 0.0f, 1e-5f);
    }
    // Reversed: the cap is at the end.
    const StrokePoint r[2] = {p[1], p[0]};
    Mesh mesh2(1024, 4096, 128);
    stipple::tessellate_stroke(r, 2, {}, 0, camera(), prm, &mesh2.m, nullptr);
    ASSERT_EQ(mesh2.m.segment_count, 2u);
    EXPECT_EQ(mesh2.s[1].index_count, 24u);
}

TEST(PaintstrokeTessellation, RejectsInvalidInputAndSkipsNearPlane) {
    Mesh mesh(1024, 4096, 128);
    const StrokePoint good[2] = {pt(0, 0, -5, 0.1f), pt(1, 0, -5, 0.1f)};
    StrokePoint bad[2] = {good[0], good[1]};
    stipple::tessellate_stroke(good, 1, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    bad[1].radius = -0.1f;
    stipple::tessellate_stroke(bad, 2, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    bad[1] = good[1];
    bad[0].position.x = NAN;
    stipple::tessellate_stroke(bad, 2, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    bad[0] = good[0];
    bad[0].op_max = INFINITY;
    stipple::tessellate_stroke(bad, 2, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    EXPECT_EQ(mesh.m.vertex_count, 0u);
    EXPECT_EQ(mesh.m.segment_count, 0u);
    // Crossing the near plane: the segment with a point at -z < near_z is not drawn.
    const StrokePoint cross[2] = {pt(0, 0, -0.005f, 0.001f), pt(0, 1, -5, 0.1f)};
    stipple::tessellate_stroke(cross, 2, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    EXPECT_EQ(mesh.m.segment_count, 0u);
    stipple::tessellate_stroke(good, 2, {}, 0, camera(), loose(2), &mesh.m, nullptr);
    EXPECT_EQ(mesh.m.segment_count, 1u);
    EXPECT_FALSE(mesh.m.overflow);
}

// A tightly curled stroke under tiny tolerances: every piece splits to the depth limit.
std::vector<StrokePoint> curl(int n) {
    std::vector<StrokePoint> p;
    for (int k = 0; k < n; ++k)
        p.push_back(pt(0.5f * std::cos(1.9f * k), 0.5f * std::sin(1.3f * k),
                       -3.0f - std::sin(0.7f * k), 0.05f + 0.2f * (k % 3)));
    return p;
}

TEST(PaintstrokeTessellation, CapacityOverflowNeverWritesPastBuffers) {
    const std::vector<StrokePoint> p = curl(6);
    stipple::TessellationParams prm;
    prm.quality = 2;
    prm.tol_theta_px = 0.2f;
    prm.max_depth = 4;
    const uint32_t guard = 64;
    const uint32_t kGuardIndex = 0xdeadbeefu;
    int overflows = 0;
    for (uint32_t cap = 0; cap < 600; cap += 7) {
        Mesh mesh(cap + guard, cap * 3 + guard, cap / 8 + guard);
        stipple::StrokeVertex gv;
        std::memset(&gv, 0xab, sizeof gv);
        for (auto& v : mesh.v) v = gv;
        for (auto& i : mesh.i) i = kGuardIndex;
        for (auto& s : mesh.s) s = stipple::StrokeSegment{1, 2, 3.0f, 4};
        mesh.m.vertex_capacity = cap;
        mesh.m.index_capacity = cap * 3;
        mesh.m.segment_capacity = cap / 8;
        stipple::tessellate_stroke(p.data(), uint32_t(p.size()), {}, 0, camera(), prm, &mesh.m,
                                   nullptr);
        overflows += mesh.m.overflow;
        EXPECT_LE(mesh.m.vertex_count, cap);
        EXPECT_LE(mesh.m.index_count, cap * 3);
        EXPECT_LE(mesh.m.segment_count, cap / 8);
        for (uint32_t k = cap; k < cap + guard; ++k)
            ASSERT_EQ(std::memcmp(&mesh.v[k], &gv, sizeof gv), 0) << cap;
        for (uint32_t k = cap * 3; k < cap * 3 + guard; ++k) ASSERT_EQ(mesh.i[k], kGuardIndex);
        for (uint32_t k = cap / 8; k < cap / 8 + guard; ++k) ASSERT_EQ(mesh.s[k].stroke, 4u);
        // What was written is whole: every index refers to a written vertex.
        for (uint32_t k = 0; k < mesh.m.index_count; ++k) ASSERT_LT(mesh.i[k], mesh.m.vertex_count);
        uint32_t sum = 0;
        for (uint32_t k = 0; k < mesh.m.segment_count; ++k) sum += mesh.s[k].index_count;
        EXPECT_EQ(sum, mesh.m.index_count);
    }
    EXPECT_GT(overflows, 10);
}

TEST(PaintstrokeTessellation, MeshBoundCoversWorstCase) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    uint64_t most_segments = 0;
    for (int depth : {0, 2, 4, 6}) {
        for (int n : {2, 3, 7}) {
            for (int trial = 0; trial < 12; ++trial) {
                // Curled strokes, and random ones with strongly varying radii seen near their
                // axis (far sides drawn), all at quality 2 with caps and tiny tolerances.
                std::vector<StrokePoint> p = curl(n);
                if (trial > 0)
                    for (int k = 0; k < n; ++k)
                        p[k] = pt(0.3f * u(rng), 0.3f * u(rng), -3.0f - 0.8f * k + 0.3f * u(rng),
                                  0.05f + 0.45f * (u(rng) + 1.0f));
                stipple::TessellationParams prm;
                prm.quality = 2;
                prm.tol_theta_px = 1e-6f;
                prm.tol_z_px = 1e-9f;
                prm.max_depth = depth;
                prm.end_caps = true;
                const stipple::StrokeMeshBound bound = stipple::stroke_mesh_bound(uint32_t(n), prm);
                Mesh mesh(uint32_t(bound.vertices), uint32_t(bound.indices),
                          uint32_t(bound.segments));
                stipple::TessellationStats stats;
                stipple::tessellate_stroke(p.data(), uint32_t(n), {}, 0, camera(), prm, &mesh.m,
                                           &stats);
                EXPECT_FALSE(mesh.m.overflow);
                EXPECT_LE(mesh.m.vertex_count, bound.vertices);
                EXPECT_LE(mesh.m.index_count, bound.indices);
                EXPECT_LE(mesh.m.segment_count, bound.segments);
                // Per section at most (1 + its inflection splits) << depth segments.
                uint32_t caps = 0;
                for (uint32_t k = 0; k < mesh.m.segment_count; ++k) {
                    uint32_t lo, hi;
                    segment_vertices(mesh, mesh.s[k], &lo, &hi);
                    caps += (hi - lo + 1) % 2;  // caps: the only odd vertex counts
                }
                EXPECT_LE(mesh.m.segment_count - caps, (uint64_t(n - 1) + stats.inflection_splits)
                                                           << depth);
                most_segments = std::max<uint64_t>(most_segments, mesh.m.segment_count);
            }
        }
    }
    EXPECT_GT(most_segments, 200u);  // the trials did reach deep subdivisions
    // The bound itself: all sections at the most inflection pieces, both sides, both caps.
    stipple::TessellationParams prm;
    prm.max_depth = 3;
    const stipple::StrokeMeshBound b = stipple::stroke_mesh_bound(4, prm);
    EXPECT_EQ(b.segments, 3u * 5u * 8u + 2u);
    EXPECT_EQ(b.vertices, 3u * 5u * 8u * 16u + 18u);
    EXPECT_EQ(b.indices, 3u * 5u * 8u * 48u + 48u);
}

}  // namespace
