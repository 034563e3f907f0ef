#include "bake/surface_projection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "bake/closest_on_triangle.h"

namespace stipple::bake {

namespace {

Vec3d closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    return bake::closest_on_triangle(p, a, b, c,
                                     [](const Vec3d& x, const Vec3d& y) { return x | y; });
}

}  // namespace

void NearestTree::build(std::vector<double> xyz, std::vector<uint32_t> ids) {
    xyz_ = std::move(xyz);
    ids_ = std::move(ids);
    order_.resize(xyz_.size() / 3);
    std::iota(order_.begin(), order_.end(), 0u);
    axis_.assign(order_.size(), 0);
    build_range(0, uint32_t(order_.size()));
}

// Splits [lo, hi) at its median along its widest axis (ties by index: deterministic).
void NearestTree::build_range(uint32_t lo, uint32_t hi) {
    while (hi - lo > 1) {
        double mn[3] = {1e300, 1e300, 1e300}, mx[3] = {-1e300, -1e300, -1e300};
        for (uint32_t i = lo; i < hi; ++i)
            for (int k = 0; k < 3; ++k) {
                mn[k] = std::min(mn[k], xyz_[size_t(order_[i]) * 3 + size_t(k)]);
                mx[k] = std::max(mx[k], xyz_[size_t(order_[i]) * 3 + size_t(k)]);
            }
        int a = 0;
        for (int k = 1; k < 3; ++k)
            if (mx[k] - mn[k] > mx[a] - mn[a]) a = k;
        const uint32_t mid = lo + (hi - lo) / 2;
        std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                         [&](uint32_t x, uint32_t y) {
                             const double cx = xyz_[size_t(x) * 3 + size_t(a)];
                             const double cy = xyz_[size_t(y) * 3 + size_t(a)];
                             return cx != cy ? cx < cy : x < y;
                         });
        axis_[mid] = uint8_t(a);
        build_range(lo, mid);
        lo = mid + 1;
    }
}

void NearestTree::nearest(const Vec3d& p, int k, std::vector<uint32_t>* out) const {
    using Entry = std::pair<double, uint32_t>;  // (squared distance, point): a max-heap
    std::vector<Entry> heap;
    const size_t want = size_t(std::max(k, 1));
    struct Range {
        uint32_t lo, hi;
        double bound;  // a lower bound of the squared distance to its centroids
    };
    std::vector<Range> stack{{0u, uint32_t(order_.size()), 0.0}};
    while (!stack.empty()) {
        const Range r = stack.back();
        stack.pop_back();
        if (r.lo >= r.hi || (heap.size() == want && r.bound > heap.front().first)) continue;
        const uint32_t mid = r.lo + (r.hi - r.lo) / 2, t = order_[mid];
        const double* c = &xyz_[size_t(t) * 3];
        const Entry e{(p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
                          (p[2] - c[2]) * (p[2] - c[2]),
                      t};
        if (heap.size() < want || e < heap.front()) {
            if (heap.size() == want) {
                std::pop_heap(heap.begin(), heap.end());
                heap.pop_back();
            }
            heap.push_back(e);
            std::push_heap(heap.begin(), heap.end());
        }
        // The far side is at least |diff| away (exactly, in floating point too); it is
        // searched after the near side, when the heap has its tightest bound.
        const double diff = p[axis_[mid]] - c[axis_[mid]];
        const Range low{r.lo, mid, r.bound}, high{mid + 1, r.hi, r.bound};
        const double far_bound = std::max(r.bound, diff * diff);
        if (diff < 0) {
            stack.push_back({high.lo, high.hi, far_bound});
            stack.push_back(low);
        } else {
            stack.push_back({low.lo, low.hi, far_bound});
            stack.push_back(high);
        }
    }
    for (const Entry& e : heap) out->push_back(ids_[e.second]);
}

InputSurface::InputSurface(const RawScene& scene, const std::vector<uint32_t>& welded)
    : scene_(scene) {
    const size_t tris = scene.triangle_count();
    normals_.resize(tris);
    uint32_t classes = 0;
    for (uint32_t w : welded) classes = std::max(classes, w + 1);
    // Triangles around each welded vertex (CSR): 3T entries whatever the connectivity. The
    // triangles near a triangle are gathered from them per projection, not stored per
    // triangle (that was quadratic in the valence: a fan of T triangles stored T^2).
    corner_class_.resize(tris * 3);
    for (size_t i = 0; i < tris * 3; ++i) corner_class_[i] = welded[scene.indices[i]];
    around_offsets_.assign(classes + 1, 0);
    for (uint32_t c : corner_class_) ++around_offsets_[c + 1];
    for (uint32_t c = 0; c < classes; ++c) around_offsets_[c + 1] += around_offsets_[c];
    around_.resize(around_offsets_[classes]);
    std::vector<uint32_t> fill(around_offsets_.begin(), around_offsets_.end() - 1);
    for (uint32_t t = 0; t < tris; ++t) {
        for (int k = 0; k < 3; ++k) around_[fill[corner_class_[size_t(t) * 3 + size_t(k)]]++] = t;
        const Vec3d n = (corner(t, 1) - corner(t, 0)) % (corner(t, 2) - corner(t, 0));
        const double len = n.norm();
        normals_[t] = len > 0 ? n / len : Vec3d(0, 0, 0);
        area_ += 0.5 * len;
    }
    build_hubs(classes);
}

// The class most of a hub's triangles share besides the hub: the other end of a
// non-manifold edge they all hang from (a star), or UINT32_MAX if no class is in more than
// half of them.
uint32_t InputSurface::edge_partner(uint32_t c) const {
    std::vector<uint32_t> others;
    const uint32_t b = around_offsets_[c], e = around_offsets_[c + 1];
    for (uint32_t i = b; i < e; ++i)
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = corner_class_[size_t(around_[i]) * 3 + size_t(k)];
            if (o != c) others.push_back(o);
        }
    std::sort(others.begin(), others.end());
    for (size_t i = 0, j = 0; i < others.size(); i = j) {
        while (j < others.size() && others[j] == others[i]) ++j;
        if (2 * (j - i) > e - b) return others[i];
    }
    return UINT32_MAX;
}

// A direction from the hub: unit, and for the hub of a star perpendicular to its edge (the
// pages of a star differ only by their angle around the edge; from the hub they all point
// nearly along it, and a point near the edge would be equally near all of them).
Vec3d InputSurface::Hub::key(Vec3d d) const {
    d -= axis * (d | axis);  // axis is 0 for the hub of a fan
    const double len = d.norm();
    return len > 0 ? d / len : d;
}

// Each hub's triangles by their direction from the hub (the unit vector to the centroid): in
// a fan or a star the triangles near a point around the hub are those in its direction.
void InputSurface::build_hubs(uint32_t classes) {
    for (uint32_t c = 0; c < classes; ++c) {
        const uint32_t b = around_offsets_[c], e = around_offsets_[c + 1];
        if (e - b <= kHubValence) continue;
        if (hub_of_class_.empty()) hub_of_class_.assign(classes, UINT32_MAX);
        hub_of_class_[c] = uint32_t(hubs_.size());
        hubs_.emplace_back();
        Hub& hub = hubs_.back();
        const uint32_t partner = edge_partner(c);
        const uint32_t t0 = around_[b];
        for (int k = 0; k < 3; ++k)
            if (corner_class_[size_t(t0) * 3 + size_t(k)] == c) hub.centre = corner(t0, k);
        bool found = false;
        for (uint32_t i = b; i < e && partner != UINT32_MAX && !found; ++i)
            for (int k = 0; k < 3 && !found; ++k)
                if (corner_class_[size_t(around_[i]) * 3 + size_t(k)] == partner) {
                    hub.axis = corner(around_[i], k);
                    found = true;
                }
        if (found) {
            hub.axis -= hub.centre;
            const double len = hub.axis.norm();
            hub.axis = len > 0 ? hub.axis / len : Vec3d(0, 0, 0);
        }
        std::vector<double> xyz;
        xyz.reserve(size_t(e - b) * 3);
        for (uint32_t i = b; i < e; ++i) {
            const uint32_t t = around_[i];
            const Vec3d d =
                hub.key((corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0 - hub.centre);
            xyz.insert(xyz.end(), {d[0], d[1], d[2]});
        }
        hub.directions.build(std::move(xyz),
                             std::vector<uint32_t>(around_.begin() + b, around_.begin() + e));
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

// The triangles sharing a welded vertex with a seed, sorted. A hub's triangles are replaced
// by the kHubNearest in p's direction, so a projection costs about O(k log T) there instead
// of O(valence); without hubs the candidates are exactly the vertex-sharing ones.
void InputSurface::gather(const Vec3d& p, const uint32_t* seeds, int seed_count) const {
    candidates_.clear();
    uint32_t queried[64];  // hubs whose nearest are in candidates_
    int n_queried = 0;
    for (int i = 0; i < seed_count; ++i) {
        candidates_.push_back(seeds[i]);
        for (int k = 0; k < 3; ++k) {
            const uint32_t c = corner_class_[size_t(seeds[i]) * 3 + size_t(k)];
            const uint32_t b = around_offsets_[c], e = around_offsets_[c + 1];
            if (e - b <= kHubValence) {
                candidates_.insert(candidates_.end(), around_.begin() + b, around_.begin() + e);
                continue;
            }
            // Each hub once: its nearest depend on p only (the seeds of a star all share both
            // ends of its edge).
            const uint32_t h = hub_of_class_[c];
            if (std::find(queried, queried + n_queried, h) != queried + n_queried) continue;
            if (n_queried < 64) queried[n_queried++] = h;
            const Hub& hub = hubs_[h];
            const Vec3d key = hub.key(p - hub.centre);
            // On a star's edge itself every page holds p (so do the seeds): and a query from
            // the centre of the keys' circle would examine them all.
            if (hub.axis.sqrnorm() > 0 && key.sqrnorm() == 0) continue;
            hub.directions.nearest(key, kHubNearest, &candidates_);
        }
    }
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
    examined_ += candidates_.size();
}

SurfacePoint InputSurface::project(const Vec3d& p, const Vec3d& direction, const uint32_t* seeds,
                                   int seed_count) const {
    gather(p, seeds, seed_count);

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
