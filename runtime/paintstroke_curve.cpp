#include "runtime/paintstroke_curve.h"

#include <cmath>

namespace stipple {

Cubic catmull_rom(float p0, float p1, float p2, float p3) {
    // GI'98 §3: p(t) = 1/2 [2 p1 + (p2 - p0) t + (2 p0 - 5 p1 + 4 p2 - p3) t^2
    //                      + (-p0 + 3 p1 - 3 p2 + p3) t^3]
    Cubic q;
    q.c[0] = p1;
    q.c[1] = 0.5f * (p2 - p0);
    q.c[2] = 0.5f * (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3);
    q.c[3] = 0.5f * (-p0 + 3.0f * p1 - 3.0f * p2 + p3);
    return q;
}

namespace {

// Control point i, with reflected phantom points one step past either end.
glm::vec3 cp_pos(const StrokePoint* p, uint32_t n, int64_t i) {
    if (i < 0) return 2.0f * p[0].position - p[1].position;
    if (i >= int64_t(n)) return 2.0f * p[n - 1].position - p[n - 2].position;
    return p[i].position;
}

float cp_rad(const StrokePoint* p, uint32_t n, int64_t i) {
    if (i < 0) return 2.0f * p[0].radius - p[1].radius;
    if (i >= int64_t(n)) return 2.0f * p[n - 1].radius - p[n - 2].radius;
    return p[i].radius;
}

}  // namespace

SectionCurve make_section_curve(const StrokePoint* points, uint32_t count, uint32_t m) {
    SectionCurve s;
    const int64_t i = m;
    const glm::vec3 a = cp_pos(points, count, i - 1), b = cp_pos(points, count, i),
                    c = cp_pos(points, count, i + 1), d = cp_pos(points, count, i + 2);
    for (int k = 0; k < 3; ++k) s.pos[k] = catmull_rom(a[k], b[k], c[k], d[k]);
    const float ra = cp_rad(points, count, i - 1), rb = cp_rad(points, count, i),
                rc = cp_rad(points, count, i + 1), rd = cp_rad(points, count, i + 2);
    s.rad = catmull_rom(ra, rb, rc, rd);
    s.p0 = b;
    s.p1 = c;
    // Catmull-Rom tangents at the joints, computed the same way by both sections that share
    // the joint: (cp_{m+1} - cp_{m-1}) / 2 and (cp_{m+2} - cp_m) / 2.
    s.dp0 = 0.5f * (c - a);
    s.dp1 = 0.5f * (d - b);
    s.r0 = rb;
    s.r1 = rc;
    s.dr0 = 0.5f * (rc - ra);
    s.dr1 = 0.5f * (rd - rb);
    return s;
}

float cubic_average(const Cubic& q, float a, float b) {
    // Integrate in double: the difference of two antiderivative values cancels badly in float
    // for short segments.
    const double qa = a, qb = b;
    const auto prim = [&](double t) {
        return t * (q.c[0] + t * (q.c[1] / 2.0 + t * (q.c[2] / 3.0 + t * q.c[3] / 4.0)));
    };
    return float((prim(qb) - prim(qa)) / (qb - qa));
}

int cubic_inflection(const Cubic& q, float lo, float hi, float* t) {
    // GI'98 §4.2.3: pos'' = 2 c2 + 6 c3 t = 0.
    // Rounding leaves a tiny cubic term on (mathematically) quadratic or linear pieces, e.g.
    // behind a reflected end point: ignore c3 below 1e-5 of the coefficients' magnitude.
    const float scale =
        std::fabs(q.c[0]) + std::fabs(q.c[1]) + std::fabs(q.c[2]) + std::fabs(q.c[3]);
    if (!(std::fabs(q.c[3]) > 1e-5f * scale)) return 0;
    const float r = -q.c[2] / (3.0f * q.c[3]);
    if (r > lo && r < hi) {
        *t = r;
        return 1;
    }
    return 0;
}

int quadratic_roots(double a, double b, double c, float lo, float hi, float* t) {
    const double scale = std::fabs(a) + std::fabs(b) + std::fabs(c);
    if (!(scale > 0.0)) return 0;
    return quadratic_roots_scaled(a, b, c, scale, lo, hi, t);
}

int quadratic_roots_scaled(double a, double b, double c, double scale, float lo, float hi,
                           float* t) {
    if (!(std::fabs(a) + std::fabs(b) + std::fabs(c) > 1e-9 * scale)) return 0;
    double r[2];
    int n = 0;
    if (std::fabs(a) <= 1e-9 * scale) {
        if (std::fabs(b) <= 1e-9 * scale) return 0;
        r[n++] = -c / b;
    } else {
        const double disc = b * b - 4.0 * a * c;
        if (disc < 0.0) return 0;
        // Numerically stable pair (no cancellation between -b and sqrt(disc)).
        const double qq = -0.5 * (b + (b >= 0.0 ? std::sqrt(disc) : -std::sqrt(disc)));
        r[n++] = qq / a;
        if (qq != 0.0) r[n++] = c / qq;
    }
    if (n == 2 && r[1] < r[0]) {
        const double tmp = r[0];
        r[0] = r[1];
        r[1] = tmp;
    }
    int out = 0;
    for (int i = 0; i < n; ++i) {
        const float f = float(r[i]);
        if (f > lo && f < hi && (out == 0 || f != t[out - 1])) t[out++] = f;
    }
    return out;
}

int screen_inflections(const SectionCurve& s, float lo, float hi, float* t) {
    // GI'98 §4.2.3 under an orthographic projection: with x = sum a_k t^k, y = sum b_k t^k,
    // x' y'' - y' x'' = 6 (a2 b3 - a3 b2) t^2 + 6 (a1 b3 - a3 b1) t + 2 (a1 b2 - a2 b1).
    const double a1 = s.pos[0].c[1], a2 = s.pos[0].c[2], a3 = s.pos[0].c[3];
    const double b1 = s.pos[1].c[1], b2 = s.pos[1].c[2], b3 = s.pos[1].c[3];
    // A straight path has x' y'' - y' x'' = 0 up to rounding of the float coefficients:
    // coefficients below 1e-5 of the squared path magnitude are taken as zero.
    double m = 0.0;
    for (int k = 0; k < 4; ++k)
        m += std::fabs(double(s.pos[0].c[k])) + std::fabs(double(s.pos[1].c[k]));
    return quadratic_roots_scaled(6.0 * (a2 * b3 - a3 * b2), 6.0 * (a1 * b3 - a3 * b1),
                                  2.0 * (a1 * b2 - a2 * b1), 1e4 * m * m, lo, hi, t);
}

glm::vec3 section_pos(const SectionCurve& s, float t) {
    if (t == 0.0f) return s.p0;
    if (t == 1.0f) return s.p1;
    return glm::vec3(cubic_value(s.pos[0], t), cubic_value(s.pos[1], t), cubic_value(s.pos[2], t));
}

glm::vec3 section_pos_d1(const SectionCurve& s, float t) {
    if (t == 0.0f) return s.dp0;
    if (t == 1.0f) return s.dp1;
    return glm::vec3(cubic_d1(s.pos[0], t), cubic_d1(s.pos[1], t), cubic_d1(s.pos[2], t));
}

glm::vec3 section_pos_d2(const SectionCurve& s, float t) {
    return glm::vec3(cubic_d2(s.pos[0], t), cubic_d2(s.pos[1], t), cubic_d2(s.pos[2], t));
}

float section_rad(const SectionCurve& s, float t) {
    if (t == 0.0f) return s.r0;
    if (t == 1.0f) return s.r1;
    return cubic_value(s.rad, t);
}

float section_rad_d1(const SectionCurve& s, float t) {
    if (t == 0.0f) return s.dr0;
    if (t == 1.0f) return s.dr1;
    return cubic_d1(s.rad, t);
}

}  // namespace stipple
