#include "bake/vertex_normals.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

#include "bake/position_weld.h"

namespace stipple::bake {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 position(const RawScene& s, uint32_t v) {
    return {s.positions[size_t(v) * 3], s.positions[size_t(v) * 3 + 1],
            s.positions[size_t(v) * 3 + 2]};
}

double length(const Vec3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

uint32_t find(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

// Corners (3 per triangle) grouped into smoothing groups, as a union-find forest: two
// corners at the same welded vertex join when their faces share an edge there and their
// unit normals' dot product is at least `cos_crease`.
std::vector<uint32_t> smoothing_groups(const RawScene& s, const std::vector<uint32_t>& welded,
                                       const std::vector<Vec3>& unit, double cos_crease) {
    const size_t tris = s.triangle_count();
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
    return parent;
}

// Appends a copy of vertex `v` (position, texture coordinates, colour, skin data; normal set
// by the caller).
void duplicate_vertex(uint32_t v, RawScene* scene) {
    RawScene& s = *scene;
    for (int i = 0; i < 3; ++i) {
        s.positions.push_back(s.positions[size_t(v) * 3 + size_t(i)]);
        s.normals.push_back(0.0f);
    }
    if (!s.uvs.empty())
        for (int i = 0; i < 2; ++i) s.uvs.push_back(s.uvs[size_t(v) * 2 + size_t(i)]);
    if (!s.colours.empty())
        for (int i = 0; i < 4; ++i) s.colours.push_back(s.colours[size_t(v) * 4 + size_t(i)]);
    if (!s.joints.empty())
        for (int i = 0; i < 4; ++i) {
            s.joints.push_back(s.joints[size_t(v) * 4 + size_t(i)]);
            s.weights.push_back(s.weights[size_t(v) * 4 + size_t(i)]);
        }
}

// Writes each group's normal to its corners' vertices. Each input vertex keeps its index
// for the first smoothing group that uses it (so the importer's vertex order, sorted by
// influence count, survives); further groups get copies appended after the input vertices.
void write_group_normals(const std::vector<Vec3>& group_normal, std::vector<uint32_t>& parent,
                         RawScene* scene) {
    RawScene& s = *scene;
    const size_t tris = s.triangle_count();
    std::vector<int64_t> first_group(s.vertex_count(), -1);
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
        duplicate_vertex(v, &s);
        set_normal(it->second, group);
    }
}

}  // namespace

Vec3 face_normal(const std::vector<float>& positions, const std::vector<uint32_t>& indices,
                 size_t t) {
    const uint32_t* i = &indices[t * 3];
    Vec3 p[3];
    for (int k = 0; k < 3; ++k)
        p[k] = {positions[size_t(i[k]) * 3], positions[size_t(i[k]) * 3 + 1],
                positions[size_t(i[k]) * 3 + 2]};
    const Vec3 u = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const Vec3 w = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    return {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
}

void compute_vertex_normals(const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::vector<float>* normals) {
    const size_t vertex_count = positions.size() / 3;
    std::vector<double> sum(vertex_count * 3, 0.0);
    for (size_t t = 0; t * 3 + 2 < indices.size(); ++t) {
        const uint32_t* v = &indices[t * 3];
        assert(v[0] < vertex_count && v[1] < vertex_count && v[2] < vertex_count);
        const Vec3 n = face_normal(positions, indices, t);
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c) sum[size_t(v[k]) * 3 + size_t(c)] += n[size_t(c)];
        }
    }
    normals->assign(vertex_count * 3, 0.0f);
    for (size_t i = 0; i < vertex_count; ++i) {
        const double* s = &sum[i * 3];
        const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (std::isfinite(len) && len > 0.0) {
            for (int c = 0; c < 3; ++c) (*normals)[i * 3 + size_t(c)] = float(s[c] / len);
        } else {
            (*normals)[i * 3 + 2] = 1.0f;
        }
    }
}

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
        const Vec3 a = position(s, i[0]), n = face_normal(s.positions, s.indices, t);
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
    // Welded by position: seams split for UVs must not split the shading.
    const std::vector<uint32_t> welded = weld_by_position(s);
    std::vector<Vec3> normal(tris), unit(tris);
    for (uint32_t t = 0; t < tris; ++t) {
        normal[t] = face_normal(s.positions, s.indices, t);
        double len = length(normal[t]);
        unit[t] = len > 0 ? Vec3{normal[t][0] / len, normal[t][1] / len, normal[t][2] / len}
                          : Vec3{0, 0, 0};
    }
    std::vector<uint32_t> parent = smoothing_groups(s, welded, unit, cos_crease);

    // One normal per group: sum of the area-weighted normals of its faces.
    std::vector<Vec3> group_normal(tris * 3, Vec3{0, 0, 0});
    for (uint32_t c = 0; c < tris * 3; ++c) {
        Vec3& g = group_normal[find(parent, c)];
        for (int i = 0; i < 3; ++i) g[size_t(i)] += normal[c / 3][size_t(i)];
    }
    const size_t before = s.vertex_count();
    write_group_normals(group_normal, parent, &s);
    return s.vertex_count() - before;
}

}  // namespace stipple::bake
