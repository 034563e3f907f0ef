#include "runtime/particle_temporary.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "runtime/stipple_size.h"

namespace stipple {

namespace {

// The baked radii of the bake's second half over the A / i law (sqrt(A / i)).
float fitted_radius_scale(const PointsView& p, double area_total) {
    double sum = 0.0;
    uint32_t n = 0;
    for (uint32_t i = std::max(p.point_count / 2, 1u); i < p.point_count; ++i) {
        const double law = std::sqrt(area_total / double(i) / double(kRegionPerRadiusSquared));
        if (!(law > 0.0) || !std::isfinite(p.radius[i])) continue;
        sum += double(p.radius[i]) / law;
        ++n;
    }
    return n > 0 && sum > 0.0 ? float(sum / double(n)) : 1.0f;
}

Status out_of_memory(uint32_t total) {
    return make_status(StatusCode::out_of_memory, "out of memory for %u temporary particles",
                       total);
}

// The per-id arrays: the baked points copied, the slots' entries written when taken.
bool alloc_ids(TemporaryParticles* t, const PointsView& baked) {
    const uint32_t n = t->count, b = baked.point_count;
    if (!alloc(&t->host_triangle, n) || !alloc(&t->bary_u, n) || !alloc(&t->bary_v, n) ||
        !alloc(&t->radius, n))
        return false;
    std::memcpy(t->host_triangle.get(), baked.host_triangle, sizeof(uint32_t) * b);
    std::memcpy(t->bary_u.get(), baked.bary_u, sizeof(float) * b);
    std::memcpy(t->bary_v.get(), baked.bary_v, sizeof(float) * b);
    std::memcpy(t->radius.get(), baked.radius, sizeof(float) * b);
    std::fill(t->host_triangle.get() + b, t->host_triangle.get() + n, 0u);
    std::fill(t->bary_u.get() + b, t->bary_u.get() + n, 0.0f);
    std::fill(t->bary_v.get() + b, t->bary_v.get() + n, 0.0f);
    std::fill(t->radius.get() + b, t->radius.get() + n, 0.0f);
    return true;
}

bool alloc_slots(TemporaryParticles* t, uint32_t triangles, uint32_t vertices) {
    const uint32_t s = t->slots;
    if (!alloc(&t->triangle, s) || !alloc(&t->rank, s) || !alloc(&t->prev, s) ||
        !alloc(&t->free_slots, s) || !alloc(&t->linked, triangles) || !alloc(&t->tail, triangles) ||
        !alloc(&t->shown, triangles) || !alloc(&t->need, triangles) ||
        !alloc(&t->touched, triangles) || !alloc(&t->clip, vertices) ||
        !alloc(&t->outside, vertices) || !alloc(&t->facing, vertices))
        return false;
    std::fill(t->triangle.get(), t->triangle.get() + s, kFreeSlot);
    std::fill(t->rank.get(), t->rank.get() + s, 0u);
    std::fill(t->prev.get(), t->prev.get() + s, kFreeSlot);
    // LIFO: slot 0 is taken first.
    for (uint32_t k = 0; k < s; ++k) t->free_slots[k] = s - 1 - k;
    t->free_count = s;
    std::fill(t->linked.get(), t->linked.get() + triangles, 0u);
    std::fill(t->tail.get(), t->tail.get() + triangles, kFreeSlot);
    std::fill(t->shown.get(), t->shown.get() + triangles, 0u);
    std::fill(t->need.get(), t->need.get() + triangles, 0.0f);
    t->vertex_count = vertices;
    return true;
}

}  // namespace

void particle_bind_positions(const MeshView& mesh, const PointsView& p, float* out) {
    for (uint32_t i = 0; i < p.point_count; ++i) {
        const uint32_t* t = mesh.indices + size_t(p.host_triangle[i]) * 3;
        const float u = p.bary_u[i], v = p.bary_v[i], w = 1.0f - u - v;
        for (int k = 0; k < 3; ++k)
            out[size_t(i) * 3 + k] = u * mesh.positions[size_t(t[0]) * 3 + k] +
                                     v * mesh.positions[size_t(t[1]) * 3 + k] +
                                     w * mesh.positions[size_t(t[2]) * 3 + k];
    }
}

Status temporary_particles_build(TemporaryParticles* t, const Asset& asset, uint32_t total) {
    *t = TemporaryParticles();
    const PointsView& baked = asset.points;
    t->baked = t->count = baked.point_count;
    t->view = baked;
    if (total <= baked.point_count || baked.point_count == 0 || asset.mesh.triangle_count == 0)
        return {};
    // The refinement's tables on the render mesh (bind areas, root cells, baked density and
    // first-point phases per triangle): the same sequence the stipples continue with.
    Status st;
    {
        Buffer<float> bind = make_buffer<float>(size_t(baked.point_count) * 3);
        if (!bind) return out_of_memory(total);
        particle_bind_positions(asset.mesh, baked, bind.get());
        st = refinement_init(&t->mesh, asset.mesh, baked, bind.get(), RefinementDomain::mesh);
    }
    if (!st.ok()) return st;
    double area_total = 0.0;
    for (uint32_t k = 0; k < t->mesh.triangle_count; ++k) area_total += t->mesh.bind_area[k];
    if (!(area_total > 0.0)) return {};
    t->slots = total - baked.point_count;
    t->count = total;
    if (!alloc_ids(t, baked) || !alloc_slots(t, asset.mesh.triangle_count, asset.mesh.vertex_count))
        return out_of_memory(total);
    t->radius_scale = fitted_radius_scale(baked, area_total);
    t->view = PointsView();
    t->view.point_count = t->count;
    t->view.host_triangle = t->host_triangle.get();
    t->view.bary_u = t->bary_u.get();
    t->view.bary_v = t->bary_v.get();
    t->view.radius = t->radius.get();
    // The stored curvature directions cover the baked points only (curvature_count): the
    // temporary particles past them take the random field (runtime/particle_transform.h).
    t->view.curvature_angle = baked.curvature_angle;
    t->view.curvature_confidence = baked.curvature_confidence;
    t->view.curvature_count = baked.curvature_count;
    return {};
}

}  // namespace stipple
