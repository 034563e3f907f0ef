// The per-view half of runtime/particle_temporary.h: each frame, the ranks of each triangle in
// view that the style's spacing asks for (GI'01 §5's temporary particles, GI'01 §2's
// view-dependent criterion), into the fixed pool of slots.
#include <algorithm>
#include <cmath>

#include "runtime/particle_style.h"
#include "runtime/particle_temporary.h"
#include "runtime/particle_transform.h"
#include "runtime/refinement_sequence.h"
#include "runtime/stipple_size.h"

namespace stipple {

namespace {

// A rank keeps its state within 5% of the target, so one that sits at the threshold does not
// come and go every frame. The tree's nodes use 15% (runtime/particle_style.cpp), but a node
// moves a whole level's worth of particles at once, while the ranks' thresholds are
// continuous: one rank crosses at a time, and a band of +-15% would show (1.15 / 0.85)^2 =
// 1.8x more ranks after a zoom out than after the same zoom in (0.76x the target density after
// a zoom in, measured: bunny 43.8 strokes per 1,000 px at zoom 8 against 51.4 at zoom 1).
constexpr float kHysteresis = 0.05f;
// Triangles whose corners all face away by more than this stay empty (the per-particle
// horizon is dithered by +-0.1, runtime/particle_stage.cpp, so those a little past the
// outline still fade out in the set rather than drop out of it).
constexpr float kFacingMin = -0.15f;
// Ranks one triangle may ask for (the budget bounds the sum anyway).
constexpr double kMaxRanks = double(1u << 24);
enum : uint8_t { kLeft = 1, kRight = 2, kBelow = 4, kAbove = 8, kBehind = 16 };

// Clip position, frustum outcode (widened by `margin` pixels) and N.V of every vertex.
void vertex_pass(TemporaryParticles* t, const ParticleFrame& f, float margin) {
    const float mx = 1.0f + 2.0f * margin / float(std::max(f.width, 1));
    const float my = 1.0f + 2.0f * margin / float(std::max(f.height, 1));
    for (uint32_t v = 0; v < t->vertex_count; ++v) {
        const glm::vec3 p(f.positions[size_t(v) * 3], f.positions[size_t(v) * 3 + 1],
                          f.positions[size_t(v) * 3 + 2]);
        const glm::vec3 n(f.normals[size_t(v) * 3], f.normals[size_t(v) * 3 + 1],
                          f.normals[size_t(v) * 3 + 2]);
        const glm::vec4 c = f.view_projection * glm::vec4(p, 1.0f);
        const glm::vec3 to_eye = f.eye - p;
        const float len = glm::length(n) * glm::length(to_eye);
        t->facing[v] = len > 0.0f ? glm::dot(n, to_eye) / len : 1.0f;
        t->clip[v] = c;
        uint8_t o = 0;
        if (!(c.w > 1e-6f)) {
            o = kBehind;
        } else {
            o |= c.x < -mx * c.w ? kLeft : 0;
            o |= c.x > mx * c.w ? kRight : 0;
            o |= c.y < -my * c.w ? kBelow : 0;
            o |= c.y > my * c.w ? kAbove : 0;
        }
        t->outside[v] = o;
    }
}

// A triangle's need: the density (points per unit bind area) below which its ranks show at a
// spacing of 1 px, or 0 when it needs none (outside the view, facing away, or off the
// silhouette for silhouette-only styles). Ranks show while radius * focal / w > spacing, the
// radius scale * sqrt(region / K), region = 1 / density: density < (focal scale / (w
// spacing))^2 / K, at the corner nearest the eye.
float triangle_need(const TemporaryParticles& t, const ParticleFrame& f, const ParticleStyle& s,
                    uint32_t tri) {
    const uint32_t* c = f.indices + size_t(tri) * 3;
    if (t.outside[c[0]] & t.outside[c[1]] & t.outside[c[2]]) return 0.0f;
    float most = -2.0f, least_abs = 2.0f, w = INFINITY;
    bool front = false, back = false;
    for (int k = 0; k < 3; ++k) {
        const float fa = t.facing[c[k]];
        most = std::max(most, fa);
        least_abs = std::min(least_abs, std::abs(fa));
        front |= fa > 0.0f;
        back |= fa <= 0.0f;
        if (t.clip[c[k]].w > 1e-6f) w = std::min(w, t.clip[c[k]].w);
    }
    if (most < kFacingMin || !std::isfinite(w)) return 0.0f;
    const bool silhouette =
        s.silhouette_band > 0.0f && (least_abs < s.silhouette_band || (front && back));
    if (s.silhouette_only && !silhouette) return 0.0f;
    const float spacing = silhouette ? s.silhouette_spacing_px : s.spacing_px;
    const float g = f.focal_px * t.radius_scale / (w * spacing);
    return g * g / kRegionPerRadiusSquared;
}

// Ranks of triangle `tri` whose density lies below `density`: [0, n).
uint32_t ranks_below(const TemporaryParticles& t, uint32_t tri, double density) {
    const double a = t.mesh.bind_area[tri];
    const double n = (density - double(t.mesh.density[tri])) * a - double(t.mesh.phase[tri]);
    return n > 0.0 ? uint32_t(std::min(std::ceil(n), kMaxRanks)) : 0u;
}

// Ranks triangle `tri` shows with the spacing times `m`, with hysteresis about what it shows.
uint32_t target(const TemporaryParticles& t, uint32_t tri, double m) {
    const double need = t.need[tri];
    if (!(need > 0.0)) return 0;
    const double up = m * (1.0 + kHysteresis), down = m * (1.0 - kHysteresis);
    const uint32_t grow = ranks_below(t, tri, need / (up * up));
    const uint32_t keep = ranks_below(t, tri, need / (down * down));
    const uint32_t s = t.shown[tri];
    return s <= grow ? grow : (s > keep ? keep : s);
}

// Slots the touched triangles hold at spacing factor m: those shown and those fading out.
uint64_t slots_needed(const TemporaryParticles& t, double m, uint64_t* wanted) {
    uint64_t n = 0, w = 0;
    for (uint32_t k = 0; k < t.touched_count; ++k) {
        const uint32_t tri = t.touched[k];
        const uint32_t c = target(t, tri, m);
        w += c;
        n += std::max(c, t.linked[tri]);
    }
    if (wanted) *wanted = w;
    return n;
}

// The smallest spacing factor >= 1 whose slots fit `limit` (bisection in log m).
double budget_factor(const TemporaryParticles& t, uint64_t limit) {
    if (slots_needed(t, 1.0, nullptr) <= limit) return 1.0;
    double lo = 1.0, hi = 2.0;
    while (hi < 65536.0 && slots_needed(t, hi, nullptr) > limit) {
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 20; ++i) {
        const double mid = std::sqrt(lo * hi);
        if (slots_needed(t, mid, nullptr) > limit)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

// Ranks [lo, hi) of triangle tri, held in slots (hi <= linked): join when `show`, else leave.
// Returns the first rank that could not join (hi when all did).
uint32_t set_held(TemporaryParticles* t, ParticleSet* set, uint32_t tri, uint32_t lo, uint32_t hi,
                  bool show) {
    uint32_t slot = t->tail[tri], failed = hi;
    for (uint32_t r = t->linked[tri]; r-- > lo;) {
        if (r < hi) {
            const uint32_t id = t->baked + slot;
            if (!show)
                particle_set_leave(set, id);
            else if (!particle_set_join(set, id))
                failed = r;
        }
        slot = t->prev[slot];
    }
    return failed;
}

// Takes a slot for rank k of triangle tri and joins it; false when no slot or no room.
bool take_slot(TemporaryParticles* t, ParticleSet* set, uint32_t tri, uint32_t k) {
    if (t->free_count == 0) return false;
    const uint32_t slot = t->free_slots[t->free_count - 1], id = t->baked + slot;
    if (!particle_set_join(set, id)) return false;
    --t->free_count;
    const RefinementMesh& r = t->mesh;
    const glm::vec2 uv = refinement_barycentric(r.frame.get() + size_t(tri) * 3, r.root_depth[tri],
                                                triangle_variant(tri), k);
    const double density =
        double(r.density[tri]) + (double(k) + double(r.phase[tri])) / double(r.bind_area[tri]);
    t->host_triangle[id] = tri;
    t->bary_u[id] = uv.x;
    t->bary_v[id] = uv.y;
    t->radius[id] = t->radius_scale * std::sqrt(float(1.0 / density) / kRegionPerRadiusSquared);
    t->triangle[slot] = tri;
    t->rank[slot] = k;
    t->prev[slot] = t->tail[tri];
    t->tail[tri] = slot;
    ++t->linked[tri];
    return true;
}

// Triangle tri goes from showing shown[tri] ranks to c.
void apply(TemporaryParticles* t, ParticleSet* set, uint32_t tri, uint32_t c) {
    const uint32_t s = t->shown[tri], held = t->linked[tri];
    if (c < s) {
        set_held(t, set, tri, c, std::min(s, held), false);
    } else if (c > s) {
        const uint32_t hi = std::min(c, held), failed = set_held(t, set, tri, s, hi, true);
        if (failed < hi) {  // no room in the list: a prefix joined, the rest leaves again
            set_held(t, set, tri, failed, hi, false);
            c = failed;
        }
        for (uint32_t k = held; k < c; ++k)
            if (!take_slot(t, set, tri, k)) c = k;
    }
    t->shown[tri] = c;
}

}  // namespace

void temporary_particles_update(TemporaryParticles* t, ParticleSet* set, const ParticleFrame& f,
                                const ParticleStyle& style) {
    if (t->slots == 0) return;
    const float margin =
        0.5f * style.length * std::max(style.spacing_px, style.silhouette_spacing_px);
    vertex_pass(t, f, margin);
    t->touched_count = 0;
    for (uint32_t tri = 0; tri < t->mesh.triangle_count; ++tri) {
        t->need[tri] = triangle_need(*t, f, style, tri);
        if (t->need[tri] > 0.0f || t->linked[tri] > 0) t->touched[t->touched_count++] = tri;
    }
    const uint64_t held = t->slots - t->free_count;
    const uint64_t limit = std::min<uint64_t>(t->slots, held + particle_set_room(*set));
    const double m = budget_factor(*t, limit);
    slots_needed(*t, 1.0, &t->stats.wanted);
    uint32_t shown = 0;
    for (uint32_t k = 0; k < t->touched_count; ++k) {
        const uint32_t tri = t->touched[k];
        apply(t, set, tri, target(*t, tri, m));
        shown += t->shown[tri];
    }
    t->stats.shown = shown;
    t->stats.triangles = t->touched_count;
    t->stats.budget_scale = float(m);
}

void temporary_particles_release(TemporaryParticles* t, ParticleSet* set) {
    if (t->slots == 0) return;
    for (uint32_t k = 0; k < t->touched_count; ++k) {
        const uint32_t tri = t->touched[k];
        while (t->linked[tri] > 0) {
            const uint32_t slot = t->tail[tri];
            if (set->state[t->baked + slot] & kParticleListed) break;
            t->tail[tri] = t->prev[slot];
            t->triangle[slot] = kFreeSlot;
            t->prev[slot] = kFreeSlot;
            t->free_slots[t->free_count++] = slot;
            --t->linked[tri];
        }
    }
    t->stats.live = t->slots - t->free_count;
}

}  // namespace stipple
