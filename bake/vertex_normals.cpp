#include "bake/vertex_normals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace stipple::bake {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 position(const RawScene& s, uint32_t v) {
    return {s.positions[size_t(v) * 3], s.positions[size_t(v) * 3 + 1],
            s.positions[size_t(v) * 3 + 2]};
}

// Area-weighted face normal (cross product, twice the area long).
Vec3 face_normal(const RawScene& s, uint32_t t) {
    const uint32_t* i = &s.indices[size_t(t) * 3];
    Vec3 a = position(s, i[0]), b = position(s, i[1]), c = position(s, i[2]);
    Vec3 u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
}

double length(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

uint32_t find(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

}  // namespace

bool parse_normal_mode(const std::string& text, NormalMode* out) {
    if (text == "input")
        *out = NormalMode::input;
    else if (text == "flat")
        *out = NormalMode::flat;
    else if (text == "smooth")
        *out = NormalMode::smooth;
    else if (text == "auto")
        *out = NormalMode::automatic;
    else
        return false;
    return true;
}

bool orient_outward(RawScene* scene) {
    RawScene& s = *scene;
    if (s.triangle_count() == 0) return false;
    double volume = 0;
    Vec3 lo = position(s, 0), hi = lo;
    for (uint32_t v = 0; v < s.vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) {
            lo[size_t(k)] = std::min(lo[size_t(k)], position(s, v)[size_t(k)]);
            hi[size_t(k)] = std::max(hi[size_t(k)], position(s, v)[size_t(k)]);
        }
    for (uint32_t t = 0; t < s.triangle_count(); ++t) {
        const uint32_t* i = &s.indices[size_t(t) * 3];
        const Vec3 a = position(s, i[0]), n = face_normal(s, t);
        volume += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6.0;
    }
    const double box = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    if (!(volume < -0.01 * box)) return false;
    for (size_t t = 0; t < s.triangle_count(); ++t)
        std::swap(s.indices[t * 3 + 1], s.indices[t * 3 + 2]);
    for (float& n : s.normals) n = -n;
    s.warnings.push_back("faces pointed inwards (negative volume); triangles flipped");
    return true;
}

size_t assign_normals(const NormalConfig& config, RawScene* scene) {
    RawScene& s = *scene;
    if (config.mode == NormalMode::input || s.triangle_count() == 0) return 0;
    if (!s.morph_targets.empty()) {
        // Targets cover contiguous vertex ranges; split copies would fall outside them.
        s.warnings.push_back(
            "morph targets present: --normals ignored, the input normals are kept");
        return 0;
    }
    const double cos_crease = config.mode == NormalMode::flat ? 2.0  // nothing is smooth
                              : config.mode == NormalMode::smooth
                                  ? -2.0  // everything is smooth
                                  : std::cos(double(config.crease_degrees) * M_PI / 180.0);
    const size_t tris = s.triangle_count();

    // Weld by position: seams split for UVs must not split the shading.
    std::map<std::array<float, 3>, uint32_t> ids;
    std::vector<uint32_t> welded(s.vertex_count());
    for (size_t v = 0; v < s.vertex_count(); ++v)
        welded[v] = ids.emplace(std::array<float, 3>{s.positions[v * 3], s.positions[v * 3 + 1],
                                                     s.positions[v * 3 + 2]},
                                uint32_t(ids.size()))
                        .first->second;
    std::vector<Vec3> normal(tris), unit(tris);
    for (uint32_t t = 0; t < tris; ++t) {
        normal[t] = face_normal(s, t);
        double len = length(normal[t]);
        unit[t] = len > 0 ? Vec3{normal[t][0] / len, normal[t][1] / len, normal[t][2] / len}
                          : Vec3{0, 0, 0};
    }

    // Corners grouped into smoothing groups: two corners at the same welded vertex join
    // when their faces share an edge there and meet at less than the crease angle.
    std::vector<uint32_t> parent(tris * 3);
    std::iota(parent.begin(), parent.end(), 0u);
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> edge_corner;  // (from, to) -> corner
    for (uint32_t t = 0; t < tris; ++t)
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t a = welded[s.indices[t * 3 + k]], b = welded[s.indices[t * 3 + (k + 1) % 3]];
            edge_corner[{a, b}] = t * 3 + k;
        }
    for (uint32_t t = 0; t < tris; ++t)
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t a = welded[s.indices[t * 3 + k]], b = welded[s.indices[t * 3 + (k + 1) % 3]];
            auto it = edge_corner.find({b, a});  // the neighbour across this edge
            if (it == edge_corner.end()) continue;
            uint32_t g = it->second / 3;
            const Vec3 &n0 = unit[t], &n1 = unit[g];
            if (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] < cos_crease) continue;
            // Corner of t at a joins the corner of g at a, and likewise at b.
            uint32_t ga = it->second % 3, g_a = g * 3 + (ga + 1) % 3, g_b = g * 3 + ga;
            parent[find(parent, t * 3 + k)] = find(parent, g_a);
            parent[find(parent, t * 3 + (k + 1) % 3)] = find(parent, g_b);
        }

    // One normal per group: sum of the area-weighted normals of its faces.
    std::vector<Vec3> group_normal(tris * 3, Vec3{0, 0, 0});
    for (uint32_t c = 0; c < tris * 3; ++c) {
        Vec3& g = group_normal[find(parent, c)];
        for (int i = 0; i < 3; ++i) g[size_t(i)] += normal[c / 3][size_t(i)];
    }

    // Each input vertex keeps its index for the first smoothing group that uses it (so the
    // importer's vertex order, sorted by influence count, survives); further groups get
    // copies appended after the input vertices.
    const size_t before = s.vertex_count();
    std::vector<int64_t> first_group(before, -1);
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> copy_of;
    auto set_normal = [&](uint32_t vertex, uint32_t group) {
        const Vec3& n = group_normal[group];
        double len = length(n);
        if (len > 0)
            for (int i = 0; i < 3; ++i)
                s.normals[size_t(vertex) * 3 + size_t(i)] = float(n[size_t(i)] / len);
    };
    for (uint32_t c = 0; c < tris * 3; ++c) {
        uint32_t v = s.indices[c], group = find(parent, c);
        if (first_group[v] < 0 || first_group[v] == int64_t(group)) {
            first_group[v] = group;
            set_normal(v, group);
            continue;
        }
        auto [it, added] = copy_of.emplace(std::make_pair(v, group), uint32_t(s.vertex_count()));
        s.indices[c] = it->second;
        if (!added) continue;
        for (int i = 0; i < 3; ++i) {
            s.positions.push_back(s.positions[size_t(v) * 3 + size_t(i)]);
            s.normals.push_back(0.0f);
        }
        set_normal(it->second, group);
        if (!s.joints.empty())
            for (int i = 0; i < 4; ++i) {
                s.joints.push_back(s.joints[size_t(v) * 4 + size_t(i)]);
                s.weights.push_back(s.weights[size_t(v) * 4 + size_t(i)]);
            }
    }
    return s.vertex_count() - before;
}

}  // namespace stipple::bake
