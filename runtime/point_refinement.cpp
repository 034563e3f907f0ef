#include "runtime/point_refinement.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <new>

#include "runtime/refinement_order.h"
#include "runtime/refinement_sequence.h"
#include "runtime/thread_pool.h"

namespace stipple {

namespace {

struct Traversal {
    const RefinementMesh* r;
    const MeshView* mesh;
    const float* positions;
    const float* normals;
    const RefinementVertex* vertex;
    const uint8_t* double_sided;  // per triangle, or null
    glm::vec3 eye;
    float near_w;
    float focal2_over_dot;  // focal^2 / dot area
    float scale;            // budget scale applied to every count
    RefinedPoints* out;
    uint64_t wanted;
    uint64_t limit;  // the pass stops counting here (a multiple of the budget)
    uint64_t work;   // points generated or culled by emit() in this pass
    uint64_t work_limit;
    bool full() const { return wanted >= limit || work >= work_limit; }
    uint8_t* probe = nullptr;  // set: refine_one_triangle marks the triangles it would refine
    // Current triangle.
    uint32_t t;
    const uint32_t* tri;
    float area;        // bind area
    float stretch;     // current / bind area
    float density;     // rho0
    float phase;       // rank offset of the triangle's first extra point, in (0, 1]
    bool two_sided;    // the triangle is double-sided
    uint32_t variant;  // the triangle's pattern and corner order
    glm::mat2 to_2d;   // the triangle's isometric frame
};

// Largest number of the triangle's extra points the size rule could draw inside `cell`, from
// the largest density factor at its corners (1/w^2, N.V and ink are each largest at a corner).
// Returns -1 when the cell lies outside the view frustum or faces away.
double cell_count(const Traversal& s, const Cell& cell) {
    const RefinementVertex& a = s.vertex[s.tri[0]];
    const RefinementVertex& b = s.vertex[s.tri[1]];
    const RefinementVertex& c = s.vertex[s.tri[2]];
    unsigned outside = 0x3F;
    float w_min = 1e30f, need = 0.0f;
    for (int i = 0; i < 3; ++i) {
        const float u = cell.c[i].x, v = cell.c[i].y, w = 1.0f - u - v;
        const glm::vec4 p = u * a.clip + v * b.clip + w * c.clip;
        unsigned code = (p.x < -p.w) | (p.x > p.w) << 1 | (p.y < -p.w) << 2 | (p.y > p.w) << 3 |
                        (p.z < -p.w) << 4 | (p.z > p.w) << 5;
        outside &= code;
        w_min = std::min(w_min, p.w);
        need = std::max(need, u * a.need + v * b.need + w * c.need);
        if (s.two_sided) need = std::max(need, u * a.need_back + v * b.need_back + w * c.need_back);
    }
    if (outside || need <= 0.0f) return -1.0;
    w_min = std::max(w_min, s.near_w);
    const double density = double(s.stretch) * need * s.focal2_over_dot / (double(w_min) * w_min);
    return double(s.scale) * double(s.area) * (density - s.density);
}

void emit(Traversal* s, uint32_t k, const glm::vec2& bary) {
    ++s->work;
    const float u = bary.x, v = bary.y, w = 1.0f - u - v;
    // Outside the view: never drawn, so neither generated nor counted against the budget.
    const glm::vec4 clip = u * s->vertex[s->tri[0]].clip + v * s->vertex[s->tri[1]].clip +
                           w * s->vertex[s->tri[2]].clip;
    if (!(std::fabs(clip.x) <= clip.w && std::fabs(clip.y) <= clip.w &&
          std::fabs(clip.z) <= clip.w))
        return;
    RefinedPoints* o = s->out;
    ++s->wanted;
    if (o->count >= o->capacity) return;
    const uint32_t i = o->count++;
    const float* pa = s->positions + size_t(s->tri[0]) * 3;
    const float* pb = s->positions + size_t(s->tri[1]) * 3;
    const float* pc = s->positions + size_t(s->tri[2]) * 3;
    const float* na = s->normals + size_t(s->tri[0]) * 3;
    const float* nb = s->normals + size_t(s->tri[1]) * 3;
    const float* nc = s->normals + size_t(s->tri[2]) * 3;
    float n[3];
    for (int d = 0; d < 3; ++d) {
        o->positions[size_t(i) * 3 + d] = u * pa[d] + v * pb[d] + w * pc[d];
        n[d] = u * na[d] + v * nb[d] + w * nc[d];
    }
    const float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    float inv = len2 > 1e-20f ? 1.0f / std::sqrt(len2) : 0.0f;
    if (s->two_sided) {  // seen from behind: the normal turns toward the viewer
        const float* p = o->positions + size_t(i) * 3;
        const float facing =
            n[0] * (s->eye.x - p[0]) + n[1] * (s->eye.y - p[1]) + n[2] * (s->eye.z - p[2]);
        if (facing < 0.0f) inv = -inv;
    }
    for (int d = 0; d < 3; ++d) o->normals[size_t(i) * 3 + d] = n[d] * inv;
    // The hierarchy's law, continued: region = 1 / (rho0 + rank / a), times the stretch.
    const float region = s->stretch / (s->density + (float(k) + s->phase) / s->area);
    o->radius[i] = std::sqrt(region / kRegionPerRadiusSquared);
    o->triangle[i] = s->t;
    o->index[i] = k;
}

// Hand-over from the baked points to the run-time sequence, as a function of how many times
// denser than the bake the size rule wants the surface: none below kHandOverStart, complete
// above kHandOverEnd, smooth in between (in log density). Two even point sets laid over each
// other are not even (measured: 10-15% of dots closer than half the median spacing where
// both are drawn at full strength); after the hand-over the frame is one even set.
constexpr float kHandOverStart = 1.1f, kHandOverEnd = 1.4f;

float hand_over(float ratio) {
    if (ratio <= kHandOverStart) return 0.0f;
    if (ratio >= kHandOverEnd) return 1.0f;
    const float x = std::log(ratio / kHandOverStart) / std::log(kHandOverEnd / kHandOverStart);
    return x * x * (3.0f - 2.0f * x);
}

// A cell's points have indices base + stride * i. Its own points are the pattern's points from
// `start` (0 in a root cell, sub_cell_start() in a sub-cell); the rest continue in its four
// sub-cells: local index own + d + 4 i' is point i' of sub-cell d.
void visit(Traversal* s, const Cell& cell, uint64_t base, uint64_t stride, uint32_t start) {
    if (base > 0xFFFFFFFFull || s->full()) return;
    const double count = cell_count(*s, cell) - s->phase;  // ranks k + phase <= count
    // Nothing here the size rule could draw; NaN (a pose gone non-finite) draws nothing too.
    if (!(count >= double(base))) return;
    const uint32_t own = pattern_points() - start;
    const double fit = std::floor((count - double(base)) / double(stride)) + 1.0;
    const uint32_t n = fit >= double(own) ? own : uint32_t(fit);
    for (uint32_t i = 0; i < n; ++i) {
        const uint64_t k = base + stride * i;
        if (k > 0xFFFFFFFFull || s->full()) return;
        emit(s, uint32_t(k), pattern_point(cell, s->variant, start + i));
    }
    if (n < own) return;
    for (uint32_t d = 0; d < 4; ++d) {
        const uint64_t child_base = base + stride * (own + d);
        if (double(child_base) > count) break;  // children's bases only grow with d
        visit(s, quarter(cell, d), child_base, stride * 4, sub_cell_start());
    }
}

// A node of the root cells' bisection tree, `levels` above the root cells: its points are
// base + stride * i, split between its two children by the next bit of k. Subtrees outside
// the view, or with nothing the size rule could draw, are skipped whole.
void visit_roots(Traversal* s, const Cell& cell, uint32_t levels, uint64_t base, uint64_t stride) {
    if (levels == 0) return visit(s, cell, base, stride, 0);
    if (s->full()) return;
    const double count = cell_count(*s, cell) - s->phase;
    if (!(count >= double(base))) return;  // also NaN
    visit_roots(s, bisect(cell, s->to_2d, 0), levels - 1, base, stride * 2);
    visit_roots(s, bisect(cell, s->to_2d, 1), levels - 1, base + stride, stride * 2);
}

void refine_triangle(Traversal* s, uint32_t t) {
    const RefinementMesh& r = *s->r;
    s->t = t;
    s->tri = s->mesh->indices + size_t(t) * 3;
    s->area = r.bind_area[t];
    if (s->area <= 0.0f) return;
    s->phase = r.phase[t];
    s->two_sided = s->double_sided && s->double_sided[t];
    s->variant = triangle_variant(t);
    s->to_2d = isometric(r.frame.get() + size_t(t) * 3);
    visit_roots(s, kWholeTriangle, r.root_depth[t], 0, 1);
}

}  // namespace

namespace {

Status refinement_no_memory(uint32_t n) {
    return make_status(StatusCode::out_of_memory,
                       "out of memory for the run-time refinement of %u triangles", n);
}

}  // namespace

Status refinement_init(RefinementMesh* r, const MeshView& mesh, const PointsView& points,
                       const float* bind_point_positions, RefinementDomain domain,
                       const MeshView* host) {
    *r = RefinementMesh();
    const uint32_t n = mesh.triangle_count;
    r->triangle_count = n;
    Buffer<float> longest = make_buffer<float>(size_t(n) + 1);
    Buffer<float> first = make_buffer<float>(size_t(n) * 3 + 3);
    if (!longest || !first || !alloc(&r->bind_area, n) || !alloc(&r->frame, size_t(n) * 3) ||
        !alloc(&r->root_depth, n) || !alloc(&r->density, n) || !alloc(&r->phase, n) ||
        !alloc(&r->fade, n) || !alloc(&r->vertex, mesh.vertex_count) ||
        !alloc(&r->vertex_outside, mesh.vertex_count) ||
        !alloc(&r->vertex_need, mesh.vertex_count) || !alloc(&r->vertex_w, mesh.vertex_count))
        return refinement_no_memory(n);
    // Bind-pose area and isometric frame (A at the origin, B on the x axis) per triangle.
    double total_area = 0.0;
    for (uint32_t t = 0; t < n; ++t) {
        r->fade[t] = 1.0f;
        const uint32_t* tri = mesh.indices + size_t(t) * 3;
        const glm::vec3 a = glm::make_vec3(mesh.positions + size_t(tri[0]) * 3);
        const glm::vec3 b = glm::make_vec3(mesh.positions + size_t(tri[1]) * 3);
        const glm::vec3 c = glm::make_vec3(mesh.positions + size_t(tri[2]) * 3);
        const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
        const float ab = glm::length(b - a);
        float* f = r->frame.get() + size_t(t) * 3;
        const bool ok = std::isfinite(area) && area > 1e-20f && ab > 0.0f;
        r->bind_area[t] = ok ? area : 0.0f;
        f[0] = ok ? ab : 0.0f;
        f[1] = ok ? glm::dot(c - a, (b - a) / ab) : 0.0f;
        f[2] = ok ? 2.0f * area / ab : 0.0f;
        longest[t] =
            std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
        total_area += r->bind_area[t];
    }
    // rho0: the baked points' mean density over the surface (bind pose). The region of the
    // i-th point of an even hierarchy is A / i, so after all N baked points the next rank's
    // region is A / N. (The last baked radii are no guide: their tail runs up to 2.4x denser.)
    const double rho0 = total_area > 0.0 ? double(points.point_count) / total_area : 0.0;
    r->finest_density = float(rho0);
    r->hand_over = domain == RefinementDomain::mesh;
    if (domain == RefinementDomain::points) {
        // Triangles between the points of an even bake: the baked density is the bake's mean.
        // (Half a point per triangle, 0.5 / area, would read a triangle spanning a gap of the
        // triangulation as a sparse patch and fill it early: measured +12% tone at the
        // hierarchy's end.)
        for (uint32_t t = 0; t < n; ++t) {
            r->density[t] = float(rho0);
            r->root_depth[t] = uint8_t(root_depth(r->bind_area[t], longest[t], r->density[t]));
        }
    } else {
        // Per triangle, the density of the baked points it hosts, shrunk towards rho0 by a
        // prior of kPrior points: large triangles the bake left short of points are filled to
        // the law, small ones (under one point each) follow the mean.
        constexpr double kPrior = 4.0;
        for (uint32_t t = 0; t < n; ++t) r->density[t] = 0.0f;
        for (uint32_t i = 0; i < points.point_count; ++i)
            r->density[points.host_triangle[i]] += 1.0f;
        for (uint32_t t = 0; t < n; ++t) {
            const double hosted = r->density[t];
            r->density[t] =
                rho0 > 0.0 ? float((hosted + kPrior) / (r->bind_area[t] + kPrior / rho0)) : 0.0f;
            r->root_depth[t] = uint8_t(root_depth(r->bind_area[t], longest[t], r->density[t]));
        }
    }
    // The order in which triangles get their first extra point (runtime/refinement_order.h).
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t* tri = mesh.indices + size_t(t) * 3;
        const glm::vec2 b = refinement_barycentric(r->frame.get() + size_t(t) * 3, r->root_depth[t],
                                                   triangle_variant(t), 0);
        for (int d = 0; d < 3; ++d)
            first[size_t(t) * 3 + d] = b.x * mesh.positions[tri[0] * 3 + d] +
                                       b.y * mesh.positions[tri[1] * 3 + d] +
                                       (1.0f - b.x - b.y) * mesh.positions[tri[2] * 3 + d];
    }
    if (!first_point_phases(n, first.get(), r->bind_area.get(), points.point_count,
                            bind_point_positions, r->phase.get()))
        return refinement_no_memory(n);
    return domain == RefinementDomain::points && host
               ? refinement_cull_init(&r->cull, mesh, *host, points, r->bind_area.get(),
                                      r->density.get(), r->phase.get())
               : Status{};
}

namespace {

// Clip-space w where a point lies on the near plane: clip z is affine in w along every
// view ray (z = alpha w + beta, beta = z at the eye where w = 0), and the near plane is z = -w.
float near_plane_w(const SizeParams& params) {
    const glm::mat4& m = params.view_projection;
    const glm::vec4 row_z(m[0][2], m[1][2], m[2][2], m[3][2]);
    const glm::vec4 row_w(m[0][3], m[1][3], m[2][3], m[3][3]);
    const glm::vec3 forward(row_w);
    const glm::vec4 eye(params.eye, 1.0f), ahead(params.eye + forward, 1.0f);
    const float beta = glm::dot(row_z, eye);
    const float w = glm::dot(row_w, ahead);
    if (!(w > 0.0f)) return 1e-6f;
    const float alpha = (glm::dot(row_z, ahead) - beta) / w;
    const float near_w = -beta / (alpha + 1.0f);
    return std::isfinite(near_w) && near_w > 1e-6f ? near_w : 1e-6f;
}

// Per posed vertex: clip position, which frustum planes it lies outside, and the ink the
// size rule needs there for each side (N.V times the ink of its lighting); the back side's
// only with `back` (a mesh with double-sided triangles: the points domain has none, 0 there).
void classify_vertex(RefinementMesh* r, const float* positions, const float* normals,
                     const SizeParams& params, const InkTable& ink, bool back, uint32_t i) {
    const glm::mat4& m = params.view_projection;
    const glm::vec3 p(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
    const glm::vec3 n(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
    const glm::vec3 to_eye = params.eye - p;
    const float len = glm::length(to_eye);
    const float n_dot_v = len > 0.0f ? glm::dot(n, to_eye) / len : 0.0f;
    const glm::vec4 c = m * glm::vec4(p, 1.0f);
    r->vertex[i].clip = c;
    r->vertex[i].outside = uint32_t(c.x < -c.w) | uint32_t(c.x > c.w) << 1 |
                           uint32_t(c.y < -c.w) << 2 | uint32_t(c.y > c.w) << 3 |
                           uint32_t(c.z < -c.w) << 4 | uint32_t(c.z > c.w) << 5;
    r->vertex[i].need = n_dot_v > 0.0f ? n_dot_v * ink.at(lighting(params, n)) : 0.0f;
    r->vertex[i].need_back =
        back && n_dot_v < 0.0f ? -n_dot_v * ink.at(lighting(params, -n)) : 0.0f;
    r->vertex_outside[i] = uint8_t(r->vertex[i].outside);
    r->vertex_need[i] = r->vertex[i].need;
    r->vertex_w[i] = c.w;
}

void classify_vertices(RefinementMesh* r, const MeshView& mesh, const float* positions,
                       const float* normals, const SizeParams& params, bool back) {
    const InkTable ink(params);
    for (uint32_t i = 0; i < mesh.vertex_count; ++i)
        classify_vertex(r, positions, normals, params, ink, back, i);
}

// The same over the listed vertices (the points domain: no back side), in ranges over the
// thread pool (each writes only its own vertices' entries: byte-identical for any thread count).
struct ClassifyTask {
    RefinementMesh* r;
    const float* positions;
    const float* normals;
    const SizeParams* params;
    const InkTable* ink;
    const uint32_t* list;
};

void classify_range(void* context, uint32_t begin, uint32_t end) {
    const ClassifyTask& k = *static_cast<const ClassifyTask*>(context);
    for (uint32_t j = begin; j < end; ++j)
        classify_vertex(k.r, k.positions, k.normals, *k.params, *k.ink, false, k.list[j]);
}

// Triangle t for one pass: skips it when the wanted density stays under what the bake already
// draws there, else sets its fade (hand-over) and generates its extra points.
void refine_one_triangle(RefinementMesh* r, Traversal* s, bool stretch, uint32_t t) {
    r->fade[t] = 1.0f;
    // Early out, without a square root: nothing to do while stretch * density stays
    // under both the first extra point's threshold and the hand-over's start.
    const float area = r->bind_area[t];
    if (!(area > 0.0f)) return;
    const MeshView& mesh = *s->mesh;
    const float* positions = s->positions;
    const uint32_t* tri = mesh.indices + size_t(t) * 3;
    // The tests read the small per-vertex arrays (cache resident at 100k vertices), the
    // whole RefinementVertex only where a triangle may refine.
    const uint8_t* outside = r->vertex_outside.get();
    if (outside[tri[0]] & outside[tri[1]] & outside[tri[2]]) return;  // off one side of the view
    const bool two_sided = s->double_sided && s->double_sided[t];
    const float* vneed = r->vertex_need.get();
    float need = std::max({vneed[tri[0]], vneed[tri[1]], vneed[tri[2]]});
    if (two_sided) {
        const RefinementVertex* v = r->vertex.get();
        need = std::max({need, v[tri[0]].need_back, v[tri[1]].need_back, v[tri[2]].need_back});
    }
    if (!(need > 0.0f)) return;
    const float baked = r->density[t];
    const float first = r->phase[t] / (area * s->scale);
    const float lower =
        r->hand_over ? std::min(baked + first, kHandOverStart * r->finest_density) : baked + first;
    const float* vw = r->vertex_w.get();
    const float w = std::max(std::min({vw[tri[0]], vw[tri[1]], vw[tri[2]]}), s->near_w);
    const float density = need * s->focal2_over_dot / (w * w);
    float stretched = density;
    if (!stretch) {
        if (density < lower) return;
        s->stretch = 1.0f;
    } else {
        const glm::vec3 pa = glm::make_vec3(positions + size_t(tri[0]) * 3);
        const glm::vec3 e1 = glm::make_vec3(positions + size_t(tri[1]) * 3) - pa;
        const glm::vec3 e2 = glm::make_vec3(positions + size_t(tri[2]) * 3) - pa;
        const glm::vec3 n = glm::cross(e1, e2);
        const float twice2 = glm::dot(n, n);  // (2 * current area)^2
        if (density * density * twice2 < 4.0f * area * area * lower * lower) return;
        s->stretch = 0.5f * std::sqrt(twice2) / area;
        stretched = s->stretch * density;
    }
    // Hand-over: the baked points here fade (ink x (1 - h)) and the sequence takes
    // their share of the density, so deep close-ups are one even set of points. h
    // follows the wanted density over the bake's mean density, smooth over the
    // surface, so a baked point and the extra points around it agree on it.
    const float mean = r->finest_density;
    const float h = r->hand_over ? hand_over(mean > 0.0f ? stretched / mean : 1e30f) : 0.0f;
    r->fade[t] = std::sqrt(1.0f - h);
    s->density = (1.0f - h) * baked;
    if (stretched < s->density + first) return;
    if (s->probe) {
        s->probe[t] = 1;
        return;
    }
    refine_triangle(s, t);
}

}  // namespace

namespace {

// The per-triangle tests of refine_one_triangle at scale 1 over the active clusters'
// triangles, in ranges over the pool: cull->candidate[t] = 1 where the triangle would refine.
// Each range writes only its triangles' marks (and fades: 1 in the points domain).
struct ProbeTask {
    RefinementMesh* r;
    const Traversal* s;
    bool stretch;
    RefinementCull* cull;
};

// Whether no triangle of active cluster k can pass refine_one_triangle's density test: the
// cull's bound on stretch_t / lower_t (ratio_bound) times the density its classified corners
// give, their largest need and nearest w (a triangle's need is the largest at its corners, its
// w the nearest one's), with the cull's slack against rounding. The cull bounded the need by
// the hosts' normals and the w by their box; the corners' own values are what the triangles
// read, so this is the cull's test, tighter (runtime/refinement_cull.h).
bool cluster_cannot_refine(const RefinementMesh& r, const Traversal& s, const RefinementCull& c,
                           uint32_t k) {
    float need = 0.0f, w = INFINITY;
    const float* vneed = r.vertex_need.get();
    const float* vw = r.vertex_w.get();
    for (uint32_t j = c.corner_begin[k]; j < c.corner_begin[k + 1]; ++j) {
        need = std::max(need, vneed[c.corner[j]]);
        w = std::min(w, vw[c.corner[j]]);
    }
    w = std::max(w, s.near_w);
    const float density = (1.0f + kCullSlack) * need * s.focal2_over_dot / (w * w);
    return density * c.ratio_bound[k] < 1.0f;
}

void probe_range(void* context, uint32_t begin, uint32_t end) {
    const ProbeTask& k = *static_cast<const ProbeTask*>(context);
    Traversal s = *k.s;
    s.scale = 1.0f;
    s.probe = k.cull->candidate.get();
    RefinementCull& c = *k.cull;
    for (uint32_t j = begin; j < end; ++j) {
        const uint32_t cluster = c.active_list[j];
        c.probed[cluster] = !cluster_cannot_refine(*k.r, s, c, cluster);
        if (!c.probed[cluster]) continue;
        for (uint32_t i = c.tri_begin[cluster]; i < c.tri_begin[cluster + 1]; ++i) {
            const uint32_t t = c.triangles[i];
            s.probe[t] = 0;
            refine_one_triangle(k.r, &s, k.stretch, t);
        }
    }
}

// Probes the active clusters' triangles over the pool, then lists those marked, ascending
// (the order refine_points visits them in); returns how many.
uint32_t probe_triangles(RefinementMesh* r, const Traversal& s, bool stretch, RefinementCull* cull,
                         ThreadPool* pool) {
    ProbeTask task{r, &s, stretch, cull};
    constexpr uint32_t kMinClustersPerThread = 16;
    if (pool)
        thread_pool_run(pool, cull->active_count, kMinClustersPerThread, probe_range, &task);
    else
        probe_range(&task, 0, cull->active_count);
    uint32_t n = 0;
    for (uint32_t j = 0; j < cull->active_count; ++j) {
        const uint32_t cluster = cull->active_list[j];
        if (!cull->probed[cluster]) continue;
        for (uint32_t i = cull->tri_begin[cluster]; i < cull->tri_begin[cluster + 1]; ++i)
            if (cull->candidate[cull->triangles[i]]) cull->refine_list[n++] = cull->triangles[i];
    }
    std::sort(cull->refine_list.get(), cull->refine_list.get() + n);
    return n;
}

// The passes of refine_points over every triangle, or over the active clusters' (cull).
void refine_passes(RefinementMesh* r, const MeshView& mesh, const float* positions,
                   const float* normals, const uint8_t* double_sided, const SizeParams& params,
                   bool stretch, RefinedPoints* out, RefinementStats* stats, RefinementCull* cull,
                   ThreadPool* pool) {
    const float focal = focal_pixels(params);
    const float dot_area = 0.785398163f * params.max_point_size * params.max_point_size;
    Traversal s;
    s.r = r;
    s.mesh = &mesh;
    s.positions = positions;
    s.normals = normals;
    s.vertex = r->vertex.get();
    s.double_sided = double_sided;
    s.eye = params.eye;
    s.near_w = near_plane_w(params);
    s.focal2_over_dot = focal * focal / dot_area;
    s.out = out;
    // Once with every count whole; if the budget binds, again with every count scaled so the
    // frame fits (each triangle keeps its coarsest extra points). A pass stops counting at
    // kCountLimit budgets, or 4 times that of points generated or culled by the view (a hostile
    // pose can make one triangle want 2^32 points; a close-up with a tenth of the budget it
    // wants is ordinary): the next pass then scales by
    // saturated_step, an underestimate of the need corrected by one pass from its count; at
    // most kMaxPasses. So a frame's work is O(triangles + budget) whatever the pose, and a
    // frame that asks for under kCountLimit budgets runs the two passes as before.
    constexpr uint64_t kCountLimit = 16;
    constexpr int kMaxPasses = 4;
    const uint64_t capacity = out->capacity;
    s.limit = std::max<uint64_t>(kCountLimit * capacity, 1024);
    s.work_limit = 4 * s.limit;  // points culled by the view count too: they cost alike
    const float saturated_step = 0.98f * float(capacity) / float(s.limit) / 16.0f;
    s.scale = 1.0f;
    bool from_count = false;  // the scale came from a whole count: that pass is the last
    uint32_t marked = 0;      // culled: the triangles the probe marked
    for (int pass = 0;; ++pass) {
        out->count = 0;
        s.wanted = s.work = 0;
        if (cull) {  // the triangles the probe marked (a superset at any scale <= 1)
            if (pass == 0) marked = probe_triangles(r, s, stretch, cull, pool);
            for (uint32_t j = 0; j < marked; ++j)
                refine_one_triangle(r, &s, stretch, cull->refine_list[j]);
        } else {
            for (uint32_t t = 0; t < r->triangle_count; ++t) refine_one_triangle(r, &s, stretch, t);
        }
        if (stats && pass == 0) stats->wanted = s.wanted;
        const bool saturated = s.full();
        if (from_count || pass + 1 == kMaxPasses || s.wanted == 0) break;
        if (!saturated && pass == 0 && s.wanted <= capacity) break;
        if (saturated) {
            s.scale *= saturated_step;
        } else {
            s.scale *= 0.98f * float(capacity) / float(s.wanted);
            from_count = true;
        }
    }
    if (stats) {
        stats->generated = out->count;
        stats->budget_scale = s.scale;
    }
}

}  // namespace

void refine_points(RefinementMesh* r, const MeshView& mesh, const float* positions,
                   const float* normals, const uint8_t* double_sided, const SizeParams& params,
                   bool stretch, RefinedPoints* out, RefinementStats* stats) {
    out->count = 0;
    classify_vertices(r, mesh, positions, normals, params, double_sided != nullptr);
    refine_passes(r, mesh, positions, normals, double_sided, params, stretch, out, stats, nullptr,
                  nullptr);
}

void refine_points_culled(RefinementMesh* r, const MeshView& mesh, const float* positions,
                          const float* normals, const SizeParams& params, bool stretch,
                          RefinedPoints* out, RefinementStats* stats, ThreadPool* pool) {
    out->count = 0;
    const InkTable ink(params);
    ClassifyTask task{r, positions, normals, &params, &ink, r->cull.list.get()};
    constexpr uint32_t kMinVerticesPerThread = 2048;
    if (pool)
        thread_pool_run(pool, r->cull.list_count, kMinVerticesPerThread, classify_range, &task);
    else
        classify_range(&task, 0, r->cull.list_count);
    refine_passes(r, mesh, positions, normals, nullptr, params, stretch, out, stats, &r->cull,
                  pool);
}

float refinement_near_w(const SizeParams& params) {
    return near_plane_w(params);
}

void fade_baked_points(const RefinementMesh& r, const PointsView& points, float* size) {
    if (!r.hand_over) return;  // the points domain continues the bake: no baked point fades
    for (uint32_t i = 0; i < points.point_count; ++i) size[i] *= r.fade[points.host_triangle[i]];
}

}  // namespace stipple
