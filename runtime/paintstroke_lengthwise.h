// GI'98 §4.2: lengthwise subdivision of one paintstroke section into segments [a, b] of its
// parameter, by recursive parametric midpoint splits under Position Constraints I and II, the
// radius constraint, and after splitting at the inflection points of §4.2.3. No allocation:
// the recursion runs on a fixed-size explicit stack, bounded by the depth limit.
#pragma once
#include <cstdint>

#include "runtime/paintstroke.h"
#include "runtime/paintstroke_curve.h"

namespace stipple {

constexpr int kMaxLengthwiseDepth = 16;  // params.max_depth is clamped to [0, this]
// §4.2.3 splits a section at most at 4 points first: pos_z'' = 0, rad'' = 0 and the two zeros
// of the projected path's curvature; then each piece recurses to the depth limit.
constexpr int kMaxInflectionSplits = 4;

// Clamped depth limit and the worst-case number of segments of one section.
int lengthwise_depth_limit(const TessellationParams& params);
uint64_t max_segments_per_section(const TessellationParams& params);

// GI'98 §4.2.1 Position Constraint I on [a, b], with everything it computes (for tests).
struct PositionConstraint1 {
    bool defined = false;    // both screen tangents non-zero
    float cos_theta = 1.0f;  // between the normalised screen tangents at a and b
    float d = 0.0f;          // distance between the outside points o_a, o_b (pixels)
    float cos2_max = 0.0f;   // cos^2(theta_max) = d^2 / (d^2 + tol_theta^2)
    bool split = false;      // cos_theta < 0, or cos^2(theta) < cos^2(theta_max)
};
PositionConstraint1 position_constraint_1(const SectionCurve& s, float a, float b, float focal_px,
                                          float tol_theta_px);

// Screen projection (pixels from the image centre) of pos(t) and its first two derivatives,
// by analytic differentiation of x_px = focal x / -z (GI'98 §4.2.1).
void project_path(const SectionCurve& s, float t, float focal_px, glm::vec2* p, glm::vec2* d1,
                  glm::vec2* d2);

// GI'98 §4.2.2: (d_proj / |pos_z(a)|) |avg_[a,b] f - (f(a) + f(b)) / 2| in pixels, for
// f = pos_z (Position Constraint II) and f = rad (radius constraint).
float z_nonlinearity_px(const SectionCurve& s, float a, float b, float focal_px);
float rad_nonlinearity_px(const SectionCurve& s, float a, float b, float focal_px);

// Whether [a, b] must be split at its midpoint (any of the three constraints fails). A piece
// with both ends nearer than camera.near_z (or behind the eye) is never split.
bool segment_needs_split(const SectionCurve& s, float a, float b, const StrokeCamera& camera,
                         const TessellationParams& params);

// Iterates one section's segments in increasing t.
struct LengthwiseState {
    static constexpr int kStack = kMaxInflectionSplits + 2 * kMaxLengthwiseDepth + 4;
    const SectionCurve* curve = nullptr;
    StrokeCamera camera;
    TessellationParams params;
    int depth_limit = 0;
    int top = 0;
    float a[kStack], b[kStack];
    uint8_t depth[kStack];
    uint32_t inflection_splits = 0;  // §4.2.3 split points of this section
};

// Splits the section at its §4.2.3 inflection points and readies the midpoint recursion.
void lengthwise_begin(LengthwiseState* st, const SectionCurve& s, const StrokeCamera& camera,
                      const TessellationParams& params);
// The next segment [*a, *b]; false when the section is done. Consecutive segments share
// their boundary t exactly.
bool lengthwise_next(LengthwiseState* st, float* a, float* b);

// The §4.2.3 split points of a section in (0, 1), ascending and distinct (at most
// kMaxInflectionSplits). Returns the count. An inflection of pos_z, rad or the projected path
// is kept only where that function can stray from its chord by its tolerance (tol_z; for the
// path tol_theta / 8, Constraint I's sagitta) somewhere in the section: below that, the
// constraints it protects hold whatever the split.
int section_inflection_points(const SectionCurve& s, const StrokeCamera& camera,
                              const TessellationParams& params, float* t);

}  // namespace stipple
