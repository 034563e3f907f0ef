#include "bake/surface_projection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stipple::bake {

namespace {

// Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3d closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab | ap, d2 = ac | ap;
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3d bp = p - b;
    const double d3 = ab | bp, d4 = ac | bp;
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3d cp = p - c;
    const double d5 = ab | cp, d6 = ac | cp;
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

InputSurface::InputSurface(const RawScene& scene, const std::vector<uint32_t>& welded)
    : scene_(scene) {
    const size_t tris = scene.triangle_count();
    normals_.resize(tris);
    uint32_t classes = 0;
    for (uint32_t w : welded) classes = std::max(classes, w + 1);
    // Triangles around each welded vertex, then around each triangle (CSR).
    std::vector<uint32_t> offsets(classes + 1, 0), around;
    for (size_t t = 0; t < tris; ++t)
        for (int k = 0; k < 3; ++k) ++offsets[welded[scene.indices[t * 3 + size_t(k)]] + 1];
    for (uint32_t c = 0; c < classes; ++c) offsets[c + 1] += offsets[c];
    around.resize(offsets[classes]);
    std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
    for (uint32_t t = 0; t < tris; ++t) {
        for (int k = 0; k < 3; ++k)
            around[fill[welded[scene.indices[size_t(t) * 3 + size_t(k)]]]++] = t;
        const Vec3d n = (corner(t, 1) - corner(t, 0)) % (corner(t, 2) - corner(t, 0));
        const double len = n.norm();
        normals_[t] = len > 0 ? n / len : Vec3d(0, 0, 0);
        area_ += 0.5 * len;
    }
    near_offsets_.assign(tris + 1, 0);
    std::vector<uint32_t> list;
    for (uint32_t t = 0; t < tris; ++t) {
        list.clear();
        for (int k = 0; k < 3; ++k) {
            uint32_t c = welded[scene.indices[size_t(t) * 3 + size_t(k)]];
            list.insert(list.end(), around.begin() + offsets[c], around.begin() + offsets[c + 1]);
        }
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        near_.insert(near_.end(), list.begin(), list.end());
        near_offsets_[t + 1] = uint32_t(near_.size());
    }
}

Vec3d InputSurface::corner(uint32_t t, int k) const {
    const float* p = &scene_.positions[size_t(scene_.indices[size_t(t) * 3 + size_t(k)]) * 3];
    return Vec3d(p[0], p[1], p[2]);
}

SurfacePoint InputSurface::locate(uint32_t t, const Vec3d& p) const {
    const Vec3d a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    const Vec3d e0 = a - c, e1 = b - c, d = p - c;
    const double d00 = e0 | e0, d01 = e0 | e1, d11 = e1 | e1, d20 = d | e0, d21 = d | e1;
    const double den = d00 * d11 - d01 * d01;
    double u = den > 0 ? (d11 * d20 - d01 * d21) / den : 1.0 / 3;
    double v = den > 0 ? (d00 * d21 - d01 * d20) / den : 1.0 / 3;
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1) {
        const double s = u + v;
        u /= s;
        v /= s;
    }
    SurfacePoint out;
    out.host = t;
    out.u = u;
    out.v = v;
    out.position = a * u + b * v + c * (1 - u - v);
    return out;
}

SurfacePoint InputSurface::project(const Vec3d& p, const Vec3d& direction, const uint32_t* seeds,
                                   int seed_count) const {
    candidates_.clear();
    for (int i = 0; i < seed_count; ++i)
        candidates_.insert(candidates_.end(), near_.begin() + near_offsets_[seeds[i]],
                           near_.begin() + near_offsets_[seeds[i] + 1]);
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());

    // Line/triangle intersection (Moller-Trumbore, both directions along the line).
    const double dir_len = direction.norm();
    double best = std::numeric_limits<double>::infinity();
    uint32_t best_t = seeds[0];
    Vec3d best_p = p;
    if (dir_len > 0) {
        const Vec3d d = direction / dir_len;
        for (uint32_t t : candidates_) {
            const Vec3d a = corner(t, 0), e1 = corner(t, 1) - a, e2 = corner(t, 2) - a;
            const Vec3d q = d % e2;
            const double det = e1 | q;
            if (std::fabs(det) < 1e-18) continue;
            const Vec3d s = p - a;
            const double bu = (s | q) / det;
            const Vec3d r = s % e1;
            const double bv = (d | r) / det;
            const double eps = 1e-9;
            if (bu < -eps || bv < -eps || bu + bv > 1 + eps) continue;
            const double along = (e2 | r) / det;
            if (std::fabs(along) < best) {
                best = std::fabs(along);
                best_t = t;
                best_p = p + d * along;
            }
        }
    }
    // The closest point on the candidates bounds how far a sensible projection travels: a
    // line that grazes a sharp edge can hit a far face first; then the closest point wins.
    double closest = std::numeric_limits<double>::infinity();
    uint32_t closest_t = seeds[0];
    Vec3d closest_p = p;
    for (uint32_t t : candidates_) {
        const Vec3d c = closest_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
        const double dist = (c - p).norm();
        if (dist < closest) {
            closest = dist;
            closest_t = t;
            closest_p = c;
        }
    }
    if (best > 2.0 * closest + 1e-12) return locate(closest_t, closest_p);
    return locate(best_t, best_p);
}

}  // namespace stipple::bake
