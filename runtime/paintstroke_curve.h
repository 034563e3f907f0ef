// GI'98 §3 / §4.1: the per-section interpolants of a paintstroke. pos(t) and rad(t) are
// Catmull-Rom cubics, stored as polynomial coefficients with their derivatives and exact
// antiderivatives; t in [0, 1] spans one section, from cp_m (t = 0) to cp_{m+1} (t = 1).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/paintstroke.h"

namespace stipple {

// c[0] + c[1] t + c[2] t^2 + c[3] t^3 for one scalar component.
struct Cubic {
    float c[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

// One section's geometric interpolants (GI'98 §4.1). The end values and end derivatives are
// kept apart so that evaluation at t = 0 and t = 1 returns exactly the control point and the
// Catmull-Rom tangent shared with the neighbouring section (bit-identical, no cracks).
struct SectionCurve {
    Cubic pos[3];
    Cubic rad;
    glm::vec3 p0{0.0f}, p1{0.0f};    // cp_m, cp_{m+1}
    glm::vec3 dp0{0.0f}, dp1{0.0f};  // pos'(0), pos'(1)
    float r0 = 0.0f, r1 = 0.0f;      // rad(0), rad(1)
    float dr0 = 0.0f, dr1 = 0.0f;    // rad'(0), rad'(1)
};

// Builds section m (0 <= m < count - 1) of `points`. At the stroke ends the missing neighbour
// is the *reflected* end point (cp_{-1} = 2 cp_0 - cp_1, cp_n = 2 cp_{n-1} - cp_{n-2}), so the
// end tangent is cp_1 - cp_0 and a two-point stroke is exactly a straight, uniformly
// parametrised line with linearly varying radius.
SectionCurve make_section_curve(const StrokePoint* points, uint32_t count, uint32_t m);

// Catmull-Rom coefficients of p1 -> p2 with outer neighbours p0 and p3.
Cubic catmull_rom(float p0, float p1, float p2, float p3);

inline float cubic_value(const Cubic& q, float t) {
    return q.c[0] + t * (q.c[1] + t * (q.c[2] + t * q.c[3]));
}
inline float cubic_d1(const Cubic& q, float t) {
    return q.c[1] + t * (2.0f * q.c[2] + t * 3.0f * q.c[3]);
}
inline float cubic_d2(const Cubic& q, float t) {
    return 2.0f * q.c[2] + 6.0f * q.c[3] * t;
}
// Exact antiderivative, zero at t = 0.
inline float cubic_integral(const Cubic& q, float t) {
    return t * (q.c[0] + t * (q.c[1] * 0.5f + t * (q.c[2] * (1.0f / 3.0f) + t * q.c[3] * 0.25f)));
}
// Exact average of the cubic over [a, b] (a < b), from the antiderivative (GI'98 Fig. 4).
float cubic_average(const Cubic& q, float a, float b);

// Roots of the second derivative in the open interval (lo, hi): 0 or 1 (GI'98 §4.2.3).
int cubic_inflection(const Cubic& q, float lo, float hi, float* t);

// Real roots in (lo, hi) of a t^2 + b t + c, ascending; a degenerate (all ~0) polynomial has
// none. Returns the count (0..2).
int quadratic_roots(double a, double b, double c, float lo, float hi, float* t);
// The same, taking the polynomial as zero when |a| + |b| + |c| <= 1e-9 scale.
int quadratic_roots_scaled(double a, double b, double c, double scale, float lo, float hi,
                           float* t);

// Zeros in (lo, hi) of the curvature x' y'' - y' x'' of the orthographically projected path
// (eye x, y): a quadratic in t for cubics (GI'98 §4.2.3). Returns the count (0..2).
int screen_inflections(const SectionCurve& s, float lo, float hi, float* t);

// Section evaluation; t == 0 and t == 1 return the stored end values exactly.
glm::vec3 section_pos(const SectionCurve& s, float t);
glm::vec3 section_pos_d1(const SectionCurve& s, float t);
glm::vec3 section_pos_d2(const SectionCurve& s, float t);
float section_rad(const SectionCurve& s, float t);
float section_rad_d1(const SectionCurve& s, float t);
inline float section_rad_d2(const SectionCurve& s, float t) {
    return cubic_d2(s.rad, t);
}

// Linear interpolation that returns exactly a at t = 0 and exactly b at t = 1 (GI'98 §3:
// colour, opacity, reflectance and the global values are linear between control points).
inline float lerp_exact(float a, float b, float t) {
    return (1.0f - t) * a + t * b;
}

}  // namespace stipple
