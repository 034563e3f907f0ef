#include "runtime/particle_temporary.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "runtime/point_refinement.h"
#include "runtime/refinement_sequence.h"

namespace stipple {

namespace {

// An extra point of the refinement, ranked by the hierarchy index its region stands for.
struct Candidate {
    double index;  // A / region: where the point falls in the coarse-to-fine order
    uint32_t triangle, rank;
    float region;
};

bool before(const Candidate& a, const Candidate& b) {
    if (a.index != b.index) return a.index < b.index;
    if (a.triangle != b.triangle) return a.triangle < b.triangle;
    return a.rank < b.rank;
}

// Extra points of triangle t whose index A * (rho_t + (k + phase) / a) lies below `total`.
uint32_t extra_count(const RefinementMesh& r, uint32_t t, double area_total, uint32_t total) {
    const double a = r.bind_area[t];
    if (!(a > 0.0)) return 0;
    const double n = (double(total) / area_total - double(r.density[t])) * a - double(r.phase[t]);
    return n > 0.0 ? uint32_t(std::min(std::ceil(n), 1e6)) : 0u;
}

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

// Lists the candidates of every triangle, ranked coarse to fine (at most `total` - baked).
Status rank_candidates(const RefinementMesh& r, double area_total, uint32_t total,
                       Buffer<Candidate>* out, uint32_t* count) {
    // A little past the total (the local densities do not add up to the bake's exactly), so
    // that the first total - baked candidates fill the budget.
    total = uint32_t(std::min(double(total) * 1.05 + 64.0, 4e9));
    uint64_t n = 0;
    for (uint32_t t = 0; t < r.triangle_count; ++t) n += extra_count(r, t, area_total, total);
    if (n > (uint64_t(1) << 28)) n = uint64_t(1) << 28;
    if (!alloc(out, size_t(std::max<uint64_t>(n, 1)))) return out_of_memory(total);
    Candidate* c = out->get();
    uint64_t k = 0;
    for (uint32_t t = 0; t < r.triangle_count && k < n; ++t) {
        const uint32_t m = extra_count(r, t, area_total, total);
        const double a = r.bind_area[t];
        for (uint32_t j = 0; j < m && k < n; ++j) {
            const double density = double(r.density[t]) + (double(j) + double(r.phase[t])) / a;
            c[k++] = Candidate{area_total * density, t, j, float(1.0 / density)};
        }
    }
    std::sort(c, c + k, before);
    *count = uint32_t(k);
    return {};
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
    Buffer<float> bind = make_buffer<float>(size_t(baked.point_count) * 3);
    if (!bind) return out_of_memory(total);
    particle_bind_positions(asset.mesh, baked, bind.get());
    RefinementMesh r;
    Status st = refinement_init(&r, asset.mesh, baked, bind.get(), RefinementDomain::mesh);
    if (!st.ok()) return st;
    double area_total = 0.0;
    for (uint32_t k = 0; k < r.triangle_count; ++k) area_total += r.bind_area[k];
    if (!(area_total > 0.0)) return {};
    Buffer<Candidate> candidates;
    uint32_t found = 0;
    st = rank_candidates(r, area_total, total, &candidates, &found);
    if (!st.ok()) return st;
    const uint32_t extra = std::min(found, total - baked.point_count);
    const uint32_t n = baked.point_count + extra;
    if (!alloc(&t->host_triangle, n) || !alloc(&t->bary_u, n) || !alloc(&t->bary_v, n) ||
        !alloc(&t->radius, n) || !alloc(&t->triangle, std::max(extra, 1u)) ||
        !alloc(&t->rank, std::max(extra, 1u)))
        return out_of_memory(total);
    const uint32_t b = baked.point_count;
    std::memcpy(t->host_triangle.get(), baked.host_triangle, sizeof(uint32_t) * b);
    std::memcpy(t->bary_u.get(), baked.bary_u, sizeof(float) * b);
    std::memcpy(t->bary_v.get(), baked.bary_v, sizeof(float) * b);
    std::memcpy(t->radius.get(), baked.radius, sizeof(float) * b);
    t->radius_scale = fitted_radius_scale(baked, area_total);
    for (uint32_t j = 0; j < extra; ++j) {
        const Candidate& c = candidates[j];
        const glm::vec2 uv =
            refinement_barycentric(r.frame.get() + size_t(c.triangle) * 3, r.root_depth[c.triangle],
                                   triangle_variant(c.triangle), c.rank);
        t->host_triangle[b + j] = c.triangle;
        t->bary_u[b + j] = uv.x;
        t->bary_v[b + j] = uv.y;
        t->radius[b + j] = t->radius_scale * std::sqrt(c.region / kRegionPerRadiusSquared);
        t->triangle[j] = c.triangle;
        t->rank[j] = c.rank;
    }
    t->count = n;
    t->view = PointsView();
    t->view.point_count = n;
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
