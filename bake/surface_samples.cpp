#include "bake/surface_samples.h"

#include <cmath>

namespace stipple::bake::elimination {

Triangles triangles_of(const RawScene& s) {
    Triangles t;
    const uint32_t n = s.triangle_count();
    t.corner.resize(size_t(n) * 3);
    t.normal.resize(n);
    t.area.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        for (int k = 0; k < 3; ++k) {
            const float* p = &s.positions[size_t(s.indices[size_t(f) * 3 + size_t(k)]) * 3];
            t.corner[size_t(f) * 3 + size_t(k)] = Vec3(p[0], p[1], p[2]);
        }
        const Vec3* c = &t.corner[size_t(f) * 3];
        const Vec3 cross = (c[1] - c[0]) % (c[2] - c[0]);
        const double len = cross.norm();
        t.normal[f] = len > 0 ? cross / len : Vec3(0, 0, 0);
        t.area[f] = 0.5 * len;
        t.total += t.area[f];
    }
    return t;
}

// `count` samples uniform in area: triangle t gets floor or ceil of count * area_t / A
// (systematic sampling along the running sum of areas, one random offset), each uniform
// inside its triangle. Stratifying by triangle keeps the samples' density even at the
// scale of the triangles, which elimination would otherwise have to repair.
Samples sample_surface(const Triangles& t, uint64_t count, Rng* rng) {
    Samples c;
    c.reserve(count);
    const double scale = double(count) / t.total, offset = rng->uniform();
    double running = 0;
    uint64_t made = 0;
    for (uint32_t f = 0; f < uint32_t(t.area.size()); ++f) {
        running += t.area[f] * scale;
        const uint64_t upto = std::min<uint64_t>(count, uint64_t(std::floor(running + offset)));
        const Vec3* corner = &t.corner[size_t(f) * 3];
        for (; made < upto; ++made) {
            const double r1 = std::sqrt(rng->uniform()), r2 = rng->uniform();
            const double a = 1 - r1, b = r1 * (1 - r2);
            const Vec3 p = corner[0] * a + corner[1] * b + corner[2] * (1 - a - b);
            c.xyz.insert(c.xyz.end(), {p[0], p[1], p[2]});
            c.host.push_back(f);
            c.u.push_back(float(a));
            c.v.push_back(float(b));
            c.ghost.push_back(0);
        }
    }
    return c;
}

}  // namespace stipple::bake::elimination
