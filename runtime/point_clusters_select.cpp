// Level of detail, per frame (thesis §9.1.1; runtime/point_clusters.h, docs/lod.md): the
// clusters' frustum, back-face and prefix tests and the run / placed sets they give.
#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/frustum.h"
#include "runtime/normal_bounds.h"
#include "runtime/point_clusters.h"
#include "runtime/point_simd.h"

namespace stipple {

namespace {

const float* vertex(const float* positions, uint32_t v) {
    return positions + size_t(v) * 3;
}

}  // namespace

namespace {

struct Box {
    glm::vec3 lo, hi;
};

// Outside when the whole box lies beyond one plane (runtime/frustum.h; the planes with one
// pixel of margin in x and y: the renderer drops a dot whose centre falls outside the image or
// the depth range, runtime/renderer.cpp); also the smallest clip w over the box.
bool outside_frustum(const Box& b, const Frustum& f, float* w_min) {
    *w_min = least_over(f.w, b.lo, b.hi);
    bool outside = false;
    for (const glm::vec4& plane : f.plane) outside |= least_over(plane, b.lo, b.hi) > 0.0f;
    return outside;
}

// Points of cluster k whose radius bound times `stretch` passes `threshold`: the bounds are
// non-increasing along the cluster, so the kept points are a prefix (searched from last
// frame's keep).
uint32_t cut_length(const PointClusters& c, uint32_t k, const float* bound, float stretch,
                    float threshold) {
    const uint32_t first = c.point_begin[k], n = c.point_begin[k + 1] - first;
    return partition_from(bound + first, n, c.keep[k],
                          [&](float r) { return r * stretch > threshold; });
}

// The largest stretch over the triangles cluster k's points and neighbours lie on, at least 1
// (compressed radii still draw no dot past the cut), with a margin: kAreaMargin for the area
// measure (bending between neighbours' triangles, which no triangle's area shows), 2% for
// rounding on the edge ratios. The roots are taken of the largest squares: a correctly rounded
// square root is monotonic, so this is the largest root, bit for bit.
constexpr float kAreaMargin = 1.1f;
struct Stretch {
    float area, edges;
};
// The largest of 1 and value[i] over the list; four running maxima (a NaN never enters one:
// std::max keeps the first argument), so the same value as one in any order.
float largest(const uint32_t* first, const uint32_t* last, const float* value) {
    float s0 = 1.0f, s1 = 1.0f, s2 = 1.0f, s3 = 1.0f;
    for (; last - first >= 4; first += 4) {
        s0 = std::max(s0, value[first[0]]);
        s1 = std::max(s1, value[first[1]]);
        s2 = std::max(s2, value[first[2]]);
        s3 = std::max(s3, value[first[3]]);
    }
    for (; first != last; ++first) s0 = std::max(s0, value[*first]);
    return std::max(std::max(s0, s1), std::max(s2, s3));
}
Stretch cluster_stretches(const PointClusters& c, uint32_t k) {
    const uint32_t* reach = c.reach.get();
    const uint32_t *begin = reach + c.reach_begin[k], *split = reach + c.reach_split[k],
                   *end = reach + c.reach_begin[k + 1];
    const float* edge_ratio = c.edge_ratio.get();
    const float edges = std::sqrt(largest(begin, end, edge_ratio));
    const float area = std::max(std::sqrt(std::sqrt(largest(begin, split, c.area_ratio.get()))),
                                std::sqrt(largest(split, end, edge_ratio)));
    return {area * kAreaMargin, edges * 1.02f};
}

// Radius (object units) per unit of clip w below which the size rule gives size 0 for ink at
// most `ink`: region r^2 (focal / w)^2 N.V <= dot area / ink, with N.V <= 1 (the caller
// divides by the root of a tighter slope bound).
float cut_per_w(const SizeParams& params, float focal, float ink) {
    if (!(ink > 0.0f)) return 1e30f;
    const float dot_area = 0.785398163f * params.max_point_size * params.max_point_size;
    return 0.99f * std::sqrt(dot_area / (kRegionPerRadiusSquared * ink)) / focal;
}

// The points of a bit set, ascending.
uint32_t list_bits(const uint64_t* bits, uint32_t words, uint32_t* out) {
    uint32_t n = 0;
    for (uint32_t w = 0; w < words; ++w)
        for (uint64_t b = bits[w]; b; b &= b - 1) out[n++] = w * 64 + uint32_t(__builtin_ctzll(b));
    return n;
}

void set_bit(uint64_t* bits, uint32_t i) {
    bits[i >> 6] |= uint64_t(1) << (i & 63);
}

// The relevant neighbours of the run points join the placed set, so Alg. 6.4 reads this
// frame's positions: the prefixes' closure lists (the neighbours each does not hold itself,
// set by the caller), the forced points' whole lists, and the run points.
void place_closure(PointClusters* c, const PointsView& p) {
    uint64_t* placed = c->placed_bits.get();
    for (uint32_t j = 0; j < c->forced_count; ++j) {
        const uint32_t i = c->forced[j];
        for (uint32_t e = p.neighbour_offsets[i]; e < p.neighbour_offsets[i + 1]; ++e)
            set_bit(placed, p.neighbours[e]);
    }
    const uint64_t* run = c->run_bits.get();
    for (uint32_t w = 0; w < c->word_count; ++w) placed[w] |= run[w];
    c->placed_count = list_bits(placed, c->word_count, c->placed.get());
}

// The selection lists the clusters' prefixes one after another: their `order` and
// `closure_begin` entries, then their `closure` entries, each a few lines apart (the cut
// suffixes between them), which the hardware prefetcher does not follow. Fetched ahead.
constexpr uint32_t kAheadClusters = 4;
void prefetch_prefix(const PointClusters& c, uint32_t k) {
    const uint32_t begin = c.point_begin[k];
    prefetch_read(c.order.get() + begin);
    prefetch_read(c.closure_begin.get() + begin);
    prefetch_read(c.closure_begin.get() + begin + c.keep[k]);
}
void prefetch_closure(const PointClusters& c, uint32_t k) {
    prefetch_read(c.closure.get() + c.closure_begin[c.point_begin[k]]);
}

// Whether the first `keep` points of cluster k (ascending) reach point index `from`.
bool cut_reaches(const PointClusters& c, uint32_t k, uint32_t keep, uint32_t from) {
    return keep > 0 && c.order[c.point_begin[k] + keep - 1] >= from;
}

// What cluster_keep decided (LodStats), bits: cut to a prefix, culled by the frustum or as
// back-facing.
constexpr uint8_t kKindCut = 1, kKindFrustum = 2, kKindBack = 4;

// What every cluster's test reads: the frame, its frustum, focal length and ink bound.
struct KeepTask {
    PointClusters* c;
    const LodFrame* f;
    bool stretches;
    float focal;
    const InkBound* ink;
    Frustum frustum;
};

// How many of cluster k's points can draw this frame (0: culled), what decided it in *kind.
uint32_t cluster_keep(const KeepTask& t, uint32_t k, uint8_t* kind) {
    PointClusters* c = t.c;
    const LodFrame& f = *t.f;
    const SizeParams& params = *f.params;
    // The cluster's vertices in two passes (runtime/normal_bounds.h): box, cone axis and least
    // lighting, then the back-face test and the cone's slope bound (single-sided clusters).
    const uint32_t* vertices = c->vertices.get() + c->vertex_begin[k];
    const uint32_t vertex_count = c->vertex_begin[k + 1] - c->vertex_begin[k];
    PartBounds part;
    part_bounds(f.vertex_pairs, vertices, vertex_count, params, &part);
    const Box b{part.lo, part.hi};
    float w_min;
    const bool outside = outside_frustum(b, t.frustum, &w_min);
    *kind = 0;
    const bool single = c->single_sided[k] != 0;
    PartFacing facing;
    if (single) {
        facing = part_facing(f.vertex_pairs, vertices, vertex_count, part, params.eye, true);
        if (facing.away) {
            *kind = kKindBack;
            return 0;
        }
    }
    const uint32_t total = c->point_begin[k + 1] - c->point_begin[k];
    if (outside && !cut_reaches(*c, k, total, f.size_from)) {
        *kind = kKindFrustum;
        return 0;
    }
    if (!(w_min > 0.0f)) return total;
    const Stretch st = t.stretches ? cluster_stretches(*c, k) : Stretch{1.0f, 1.0f};
    // Double-sided clusters: normals that turn toward the eye, no bound (normal_bounds.h).
    const float lit = single ? part_least_lighting(part, params) : 0.0f;
    const float slope = single ? facing.slope : 1.0f;
    const float threshold = cut_per_w(params, t.focal, t.ink->at(lit)) * w_min / std::sqrt(slope);
    uint32_t keep;
    if (!f.relevance_update)  // the rest-pose radii as they are
        keep = cut_length(*c, k, c->rest_bound.get(), 1.0f, threshold);
    else  // a static mesh: the bind radii (stretches 1)
        keep = std::max(cut_length(*c, k, c->bound.get(), st.area, threshold),
                        cut_length(*c, k, c->line_bound.get(), st.edges, threshold));
    *kind = keep < total ? kKindCut : 0;
    if (outside && !cut_reaches(*c, k, keep, f.size_from)) {  // the cut ends before size_from
        *kind |= kKindFrustum;
        return 0;
    }
    return keep;
}

// cluster_keep over a range of clusters (a thread's; each writes only its own clusters').
void keep_range(void* context, uint32_t begin, uint32_t end) {
    const KeepTask& t = *static_cast<const KeepTask*>(context);
    for (uint32_t k = begin; k < end; ++k) t.c->keep[k] = cluster_keep(t, k, &t.c->keep_kind[k]);
}

// Below this many clusters (triangles) per thread the selection's loops run on the caller.
constexpr uint32_t kMinClustersPerThread = 64, kMinTrianglesPerThread = 4096;

}  // namespace

// Stretch of each triangle (bind -> posed). Alg. 6.4's area measure follows the local area
// (exactly, under a linear deformation: I2 scales by det^2), so its radius grows with the
// square root of the area ratio; the mean-distance measure with the edge lengths, bounded by
// the largest edge ratio. A degenerate bind triangle takes its edge ratio for both. Kept as
// squares here (no root per triangle): cluster_stretches takes the roots of the largest.
namespace {

void stretch_triangles(PointClusters* c, const MeshView& m, const float* posed, uint32_t begin,
                       uint32_t end) {
    float* area_ratio = c->area_ratio.get();
    float* edge_ratio = c->edge_ratio.get();
    const float* gram = c->bind_gram.get();
    uint32_t t = begin;  // runtime/point_simd.h: the same bits 8 triangles at a time
    if (has_avx2(point_simd()))
        t += triangle_stretch_avx2(m.indices + size_t(begin) * 3, posed, gram + size_t(begin) * 3,
                                   end - begin, area_ratio + begin, edge_ratio + begin);
    for (; t < end; ++t) {
        const uint32_t* tri = m.indices + size_t(t) * 3;
        const glm::vec3 o = glm::make_vec3(vertex(posed, tri[0]));
        const glm::vec3 e1 = glm::make_vec3(vertex(posed, tri[1])) - o;
        const glm::vec3 e2 = glm::make_vec3(vertex(posed, tri[2])) - o;
        const float a = gram[size_t(t) * 3], b = gram[size_t(t) * 3 + 1],
                    cc = gram[size_t(t) * 3 + 2];
        const float a2 = glm::dot(e1, e1), b2 = glm::dot(e1, e2), c2 = glm::dot(e2, e2);
        const float e3 = a2 - 2.0f * b2 + c2, e3_bind = a - 2.0f * b + cc;  // |e2 - e1|^2
        edge_ratio[t] = std::max({a > 0.0f ? a2 / a : (a2 > 0.0f ? 1e30f : 1.0f),
                                  cc > 0.0f ? c2 / cc : (c2 > 0.0f ? 1e30f : 1.0f),
                                  e3_bind > 0.0f ? e3 / e3_bind : (e3 > 0.0f ? 1e30f : 1.0f)});
        const float det = a * cc - b * b, det2 = a2 * c2 - b2 * b2;  // area^2 (times 4)
        area_ratio[t] = std::max(det2, 0.0f) / det;  // read only where bind_area_defined
    }
}

struct StretchTask {
    PointClusters* c;
    const MeshView* m;
    const float* posed;
};
void stretch_range(void* context, uint32_t begin, uint32_t end) {
    const StretchTask& t = *static_cast<const StretchTask*>(context);
    stretch_triangles(t.c, *t.m, t.posed, begin, end);
}

}  // namespace

void point_clusters_stretch(PointClusters* c, const MeshView& m, const float* posed) {
    stretch_triangles(c, m, posed, 0, m.triangle_count);
}

void point_clusters_select(PointClusters* c, const Asset& asset, const LodFrame& f) {
    const SizeParams& params = *f.params;
    const bool stretches = c->deforming && f.relevance_update;
    ThreadPool one;  // no pool: the caller alone
    ThreadPool* pool = f.pool ? f.pool : &one;
    if (stretches) {
        StretchTask task{c, &asset.mesh, f.vertex_positions};
        thread_pool_run(pool, asset.mesh.triangle_count, kMinTrianglesPerThread, stretch_range,
                        &task);
    }
    const InkBound ink(params);
    const glm::vec2 margin(2.0f / float(std::max(f.viewport_width, 1)),
                           2.0f / std::max(params.viewport_height, 1.0f));
    KeepTask task{c,         &f,
                  stretches, focal_pixels(params),
                  &ink,      frustum_planes(params.view_projection, margin)};
    thread_pool_run(pool, c->cluster_count, kMinClustersPerThread, keep_range, &task);
    LodStats s;
    s.clusters = c->cluster_count;
    uint64_t* bits = c->run_bits.get();
    uint64_t* placed = c->placed_bits.get();
    std::fill(bits, bits + c->word_count, uint64_t(0));
    std::fill(placed, placed + c->word_count, uint64_t(0));
    const uint32_t* order = c->order.get();
    const uint32_t* closure = c->closure.get();
    for (uint32_t k = 0; k < c->cluster_count; ++k) {
        const uint8_t kind = c->keep_kind[k];
        s.culled_back += (kind & kKindBack) != 0;
        s.culled_frustum += (kind & kKindFrustum) != 0;
        s.cut += (kind & kKindCut) != 0;
        if (k + kAheadClusters < c->cluster_count) prefetch_prefix(*c, k + kAheadClusters);
        if (k + 1 < c->cluster_count) prefetch_closure(*c, k + 1);
        const uint32_t begin = c->point_begin[k], end = begin + c->keep[k];
        for (uint32_t j = begin; j < end; ++j) set_bit(bits, order[j]);
        for (uint32_t e = c->closure_begin[begin]; e < c->closure_begin[end]; ++e)
            set_bit(placed, closure[e]);  // the neighbours the prefix does not hold
    }
    for (uint32_t j = 0; j < c->forced_count; ++j) set_bit(bits, c->forced[j]);
    c->run_count = list_bits(bits, c->word_count, c->run.get());
    place_closure(c, asset.points);
    s.points_run = c->run_count;
    s.points_placed = c->placed_count;
    c->stats = s;
}

void point_clusters_clear_sizes(const PointClusters& c, float* size) {
    for (uint32_t j = 0; j < c.run_count; ++j) size[c.run[j]] = 0.0f;
}

uint32_t point_clusters_rest(PointClusters* c, bool placed) {
    const uint64_t* bits = (placed ? c->placed_bits : c->run_bits).get();
    uint32_t* out = c->rest.get();
    uint32_t n = 0;
    for (uint32_t w = 0; w < c->word_count; ++w) {
        uint64_t b = ~bits[w];
        if (w + 1 == c->word_count && c->point_count % 64)
            b &= (uint64_t(1) << (c->point_count % 64)) - 1;
        for (; b; b &= b - 1) out[n++] = w * 64 + uint32_t(__builtin_ctzll(b));
    }
    return n;
}

}  // namespace stipple
