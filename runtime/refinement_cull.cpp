#include "runtime/refinement_cull.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/frustum.h"
#include "runtime/normal_bounds.h"
#include "runtime/refinement_sigma.h"

namespace stipple {

namespace {

// The largest eigenvalue of a symmetric 3x3 matrix (closed form), a little above.
double max_eigenvalue(const glm::dmat3& a) {
    const double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) +
                      (a[2][2] - q) * (a[2][2] - q) + 2.0 * p1;
    const double p = std::sqrt(p2 / 6.0);
    if (!(p > 1e-300)) return q * (1.0 + 1e-9);
    const glm::dmat3 b = (a - q * glm::dmat3(1.0)) / p;
    const double r = std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0);
    return (q + 2.0 * p * std::cos(std::acos(r) / 3.0)) * (1.0 + 1e-9) + 1e-12 * p;
}

// An upper bound on max_t stretch_t / lower_t over cluster k, from any affine map M x + t:
// each posed corner is M x_i + t + delta_i, |delta_i| <= D (its host vertices' largest distance
// from the map), so twice the posed area is at most s12 |e1 x e2| + 2 D s1 (|e1| + |e2|) + 4 D^2
// (s1 = |M|, s12 = |cof M|: largest singular values). M: the least-squares fit of the cluster's
// host vertices, bind to posed (any M gives a bound; the fit makes D small). +inf if not finite.
float affine_ratio(const RefinementCull& c, const MeshView& host, const float* posed, uint32_t k) {
    const uint32_t begin = c.host_begin[k], end = c.host_begin[k + 1];
    if (end == begin) return INFINITY;
    glm::dvec3 mean(0.0), mean_posed(0.0);
    for (uint32_t j = begin; j < end; ++j) {
        mean += glm::dvec3(glm::make_vec3(host.positions + size_t(c.host_vertex[j]) * 3));
        mean_posed += glm::dvec3(glm::make_vec3(posed + size_t(c.host_vertex[j]) * 3));
    }
    mean /= double(end - begin);
    mean_posed /= double(end - begin);
    glm::dmat3 spread(0.0), cross(0.0);
    for (uint32_t j = begin; j < end; ++j) {
        const glm::dvec3 x =
            glm::dvec3(glm::make_vec3(host.positions + size_t(c.host_vertex[j]) * 3)) - mean;
        const glm::dvec3 y =
            glm::dvec3(glm::make_vec3(posed + size_t(c.host_vertex[j]) * 3)) - mean_posed;
        spread += glm::outerProduct(x, x);
        cross += glm::outerProduct(y, x);
    }
    const double ridge = 1e-3 * (spread[0][0] + spread[1][1] + spread[2][2]) / 3.0 + 1e-30;
    const glm::dmat3 m = cross * glm::inverse(spread + ridge * glm::dmat3(1.0));
    double d2 = 0.0;
    for (uint32_t j = begin; j < end; ++j) {
        const glm::dvec3 x =
            glm::dvec3(glm::make_vec3(host.positions + size_t(c.host_vertex[j]) * 3)) - mean;
        const glm::dvec3 y =
            glm::dvec3(glm::make_vec3(posed + size_t(c.host_vertex[j]) * 3)) - mean_posed;
        const glm::dvec3 off = y - m * x;
        d2 = std::max(d2, glm::dot(off, off));
    }
    const glm::dmat3 cof(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
    const double s1 = std::sqrt(max_eigenvalue(glm::transpose(m) * m));
    const double s12 = std::sqrt(max_eigenvalue(glm::transpose(cof) * cof));
    const double d = std::sqrt(d2) * (1.0 + 1e-6) + 1e-7 * std::sqrt(glm::dot(mean, mean));
    const float* a = c.affine.get() + size_t(k) * 3;
    const double r = s12 * a[0] + 2.0 * d * s1 * a[1] + 4.0 * d * d * a[2];
    return r == r ? float(r * (1.0 + 1e-6)) : INFINITY;
}

// The box [lo, hi] of cluster k's host vertices, posed; false where a coordinate is not finite
// (|x| < 1e30 fails: then the box is not used). Without branches: every vertex is visited, the
// flags and bounds in registers.
bool host_box(const RefinementCull& c, const float* posed, uint32_t k, glm::vec3* lo,
              glm::vec3* hi) {
    float lx = INFINITY, ly = INFINITY, lz = INFINITY, hx = -INFINITY, hy = -INFINITY,
          hz = -INFINITY;
    bool finite = true;
    for (uint32_t j = c.host_begin[k]; j < c.host_begin[k + 1]; ++j) {
        const float* p = posed + size_t(c.host_vertex[j]) * 3;
        const float x = p[0], y = p[1], z = p[2];
        finite &= (std::fabs(x) < 1e30f) & (std::fabs(y) < 1e30f) & (std::fabs(z) < 1e30f);
        lx = std::min(lx, x), ly = std::min(ly, y), lz = std::min(lz, z);
        hx = std::max(hx, x), hy = std::max(hy, y), hz = std::max(hz, z);
    }
    *lo = glm::vec3(lx, ly, lz), *hi = glm::vec3(hx, hy, hz);
    return finite;
}

// The largest sigma^2 (runtime/refinement_sigma.h) over cluster k's path triangles, each
// triangle's computed once per frame (clusters' spans overlap): those not yet computed are
// listed and done together (4 a step with AVX2).
float span_sigma2(RefinementCull* c, const MeshView& host, const float* posed, uint32_t k) {
    const uint32_t begin = c->span_begin[k], end = c->span_begin[k + 1];
    uint32_t todo = 0;
    for (uint32_t j = begin; j < end; ++j) {
        const uint32_t t = c->span[j];
        if (c->sigma_frame[t] != c->frame) c->sigma_frame[t] = c->frame, c->sigma_todo[todo++] = t;
    }
    refinement_sigma2_listed(c->sigma_todo.get(), todo, host.indices, posed, c->bind_gram.get(),
                             c->sigma.get());
    float l2 = 0.0f;
    for (uint32_t j = begin; j < end; ++j) l2 = std::max(l2, c->sigma[c->span[j]]);
    return l2;
}

// Whether every point of the box [lo, hi] lies beyond one of the frustum's planes (margin 0),
// and the box's least clip w (minus a little slack): runtime/frustum.h, with each test's slack
// relative to the plane's size at the box.
bool box_outside(const Frustum& f, const glm::vec3& lo, const glm::vec3& hi, float* w_min) {
    const glm::vec3 big = glm::max(glm::abs(lo), glm::abs(hi));
    auto slack = [&](const glm::vec4& a) {
        return 1e-5f * (glm::dot(glm::abs(glm::vec3(a)), big) + std::fabs(a.w));
    };
    *w_min = least_over(f.w, lo, hi) - slack(f.w);
    for (const glm::vec4& plane : f.plane)
        if (least_over(plane, lo, hi) > slack(plane)) return true;
    return false;
}

// Paths cross seams: each crossing can add the largest gap between welded vertices' posed
// positions (a path crosses at most kCullSpanPerEdge edges). +inf if a position is not finite.
float seam_gap(const RefinementCull& c, const float* posed) {
    float gap = 0.0f;
    for (uint32_t j = 0; j < c.seam_count; ++j) {
        const glm::vec3 d = glm::make_vec3(posed + size_t(c.seam[j * 2]) * 3) -
                            glm::make_vec3(posed + size_t(c.seam[j * 2 + 1]) * 3);
        const float len = glm::length(d);
        gap = len == len && gap < len ? len : (len == len ? gap : INFINITY);
    }
    return gap * float(kCullSpanPerEdge) * (1.0f + kCullSlack);
}

// The active clusters' corners into c->list, each once, cluster by cluster.
void list_corners(RefinementCull* c) {
    c->list_count = 0;
    for (uint32_t a = 0; a < c->active_count; ++a) {
        const uint32_t k = c->active_list[a];
        for (uint32_t j = c->corner_begin[k]; j < c->corner_begin[k + 1]; ++j) {
            const uint32_t i = c->corner[j];
            uint64_t& word = c->stamp[i / 64];
            const uint64_t bit = uint64_t(1) << (i % 64);
            if (!(word & bit)) word |= bit, c->list[c->list_count++] = i;  // each corner once
        }
    }
    for (uint32_t j = 0; j < c->list_count; ++j) c->stamp[c->list[j] / 64] = 0;
}

// Whether a triangle of active cluster k can pass the full stage's density test, with its
// exact posed area (the full stage's expression, from the same placed corners) and the cull's
// bound on the rest: density_t <= density_bound (corners in the hosts' box, normals in their
// cone), so stretched_t = |e1 x e2| / (2 area_t) density_t, against lower_t.
bool posed_area_can_refine(const RefinementCull& c, const MeshView& domain, const float* positions,
                           uint32_t k) {
    const float density = c.density_bound[k] * (1.0f + kCullSlack);
    if (!(density < INFINITY)) return true;
    for (uint32_t j = c.tri_begin[k]; j < c.tri_begin[k + 1]; ++j) {
        const float limit = c.cross_limit[j];
        if (!(limit < INFINITY)) continue;  // no bind area: never refined
        const uint32_t* tri = domain.indices + size_t(c.triangles[j]) * 3;
        const glm::vec3 pa = glm::make_vec3(positions + size_t(tri[0]) * 3);
        const glm::vec3 e1 = glm::make_vec3(positions + size_t(tri[1]) * 3) - pa;
        const glm::vec3 e2 = glm::make_vec3(positions + size_t(tri[2]) * 3) - pa;
        const glm::vec3 n = glm::cross(e1, e2);
        if (!(density * std::sqrt(glm::dot(n, n)) < limit)) return true;  // NaN: kept
    }
    return false;
}

}  // namespace

uint32_t refinement_cull(RefinementCull* c, const MeshView& host, const float* posed,
                         const float* posed_normals, const SizeParams& params, bool stretch,
                         float near_w) {
    c->active_count = c->list_count = 0;
    if (++c->frame == 0) {  // the stamps wrapped: none is current
        std::fill(c->sigma_frame.get(), c->sigma_frame.get() + host.triangle_count, 0u);
        c->frame = 1;
    }
    const InkBound ink(params);  // need <= N.V ink <= ink.at(0), the table's largest
    const float focal = focal_pixels(params);
    const float dot_area = 0.785398163f * params.max_point_size * params.max_point_size;
    const float scale = (1.0f + kCullSlack) * focal * focal / dot_area;
    const float gap = seam_gap(*c, posed);
    const Frustum frustum = frustum_planes(params.view_projection, glm::vec2(0.0f));
    for (uint32_t k = 0; k < c->cluster_count; ++k) {
        c->active[k] = 0;
        const float lower = stretch ? c->lower_stretch[k] : c->lower_rest[k];
        if (!(lower < INFINITY)) continue;  // no triangle with an area
        float ratio = INFINITY;             // the bound on stretch_t / lower_t, if any
        float density_bound = INFINITY;     // the bound on need_t focal^2 / (dot area w_t^2)
        if (c->lower_rest[k] >= 0.0f) {     // every corner lies in its host: the box holds
            glm::vec3 lo, hi;
            const bool finite = host_box(*c, posed, k, &lo, &hi);
            float w_min = 0.0f;
            if (finite && box_outside(frustum, lo, hi, &w_min)) continue;
            if (finite) {
                ratio = stretch ? INFINITY : 1.0f / lower;
                const float w = std::max(w_min, near_w);
                // The stretch bound first, with the largest need (most clusters end there:
                // the same decision as with the hosts' need bound, which is below it).
                const bool paths = stretch && lower > 0.0f && gap < INFINITY;  // 0: no path
                float l = 0.0f;
                if (paths) {
                    const float l2 = span_sigma2(c, host, posed, k);
                    // |posed edge| <= L g + gap <= (L + gap / g_min) g
                    l = std::sqrt(l2) + gap / c->min_path[k];
                    if (scale * ink.at(0.0f) / (w * w) * l * l < lower) continue;
                }
                const uint32_t h = c->host_begin[k], hn = c->host_begin[k + 1] - h;
                const float need = posed_normals
                                       ? need_bound(posed_normals, c->host_vertex.get() + h, hn, lo,
                                                    hi, params, ink)
                                       : ink.at(0.0f);
                const float density = scale * need / (w * w);
                density_bound = density;
                if (!stretch && density < lower) continue;
                if (paths) {
                    if (density * l * l < lower) continue;
                    ratio = l * l / lower;
                }
                // Second chance: the affine map nearest the hosts, and how far they are from it.
                if (stretch) {
                    const float affine = affine_ratio(*c, host, posed, k);
                    if (density * affine < 1.0f) continue;
                    ratio = std::min(ratio, affine);
                }
            }
        }
        c->active[k] = 1;
        c->ratio_bound[k] = ratio;
        c->density_bound[k] = density_bound;
        c->active_list[c->active_count++] = k;
    }
    list_corners(c);
    return c->active_count;
}

uint32_t refinement_cull_posed(RefinementCull* c, const MeshView& domain, const float* positions) {
    uint32_t kept = 0;
    for (uint32_t j = 0; j < c->active_count; ++j) {
        const uint32_t k = c->active_list[j];
        if (posed_area_can_refine(*c, domain, positions, k))
            c->active_list[kept++] = k;
        else
            c->active[k] = 0;
    }
    if (kept == c->active_count) return kept;
    c->active_count = kept;
    list_corners(c);
    return kept;
}

}  // namespace stipple
