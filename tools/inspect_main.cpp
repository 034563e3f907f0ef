// stipple-inspect: what is in a .stip asset, and how evenly its point hierarchy is spread.
// Prints one JSON object. With --quality, for prefixes of 1k, 4k, 16k and 64k points (the
// hierarchy's coarser levels, thesis §3.1.1), the nearest-neighbour distance of every point
// of the prefix to the rest of it, in bind pose, normalised by sqrt(area / n) — the spacing
// of an even distribution: mean, coefficient of variation and min / mean. Two bakes (methods,
// seeds) compare by these numbers instead of by eye.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "runtime/asset.h"
#include "runtime/point_placement.h"

namespace {

const char* kUsage =
    "usage: stipple-inspect ASSET.stip [--quality]\n"
    "  --quality   nearest-neighbour spacing statistics of the 1k/4k/16k/64k-point levels\n";

struct Spacing {
    double mean = 0, cv = 0, min_over_mean = 0;
};

double surface_area(const stipple::MeshView& m) {
    double area = 0;
    for (uint32_t t = 0; t < m.triangle_count; ++t) {
        const float* a = m.positions + size_t(m.indices[t * 3]) * 3;
        const float* b = m.positions + size_t(m.indices[t * 3 + 1]) * 3;
        const float* c = m.positions + size_t(m.indices[t * 3 + 2]) * 3;
        double u[3], v[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = double(b[k]) - a[k];
            v[k] = double(c[k]) - a[k];
        }
        double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
               z = u[0] * v[1] - u[1] * v[0];
        area += 0.5 * std::sqrt(x * x + y * y + z * z);
    }
    return area;
}

// Nearest-neighbour distances among the first n points, with a uniform grid of cells about
// twice the even spacing (sorted cell keys, 27-cell search, widened when a cell is empty).
Spacing nearest_neighbour_spacing(const float* p, uint32_t n, double area) {
    const double spacing = std::sqrt(area / n), cell = 2 * spacing;
    float lo[3] = {1e30f, 1e30f, 1e30f};
    for (uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[i * 3 + k]);
    auto coord = [&](uint32_t i, int k) { return int64_t((p[i * 3 + k] - lo[k]) / cell); };
    auto key = [](int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x) << 42) | (uint64_t(y) << 21) | uint64_t(z);
    };
    std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
    for (uint32_t i = 0; i < n; ++i) keyed[i] = {key(coord(i, 0), coord(i, 1), coord(i, 2)), i};
    std::sort(keyed.begin(), keyed.end());
    std::vector<double> d(n);
    for (uint32_t i = 0; i < n; ++i) {
        double best = 1e300;
        for (int64_t ring = 1; best == 1e300 && ring < 64; ring *= 2) {
            for (int64_t dx = -ring; dx <= ring; ++dx)
                for (int64_t dy = -ring; dy <= ring; ++dy)
                    for (int64_t dz = -ring; dz <= ring; ++dz) {
                        int64_t x = coord(i, 0) + dx, y = coord(i, 1) + dy, z = coord(i, 2) + dz;
                        if (x < 0 || y < 0 || z < 0) continue;
                        uint64_t k = key(x, y, z);
                        auto it = std::lower_bound(keyed.begin(), keyed.end(),
                                                   std::make_pair(k, uint32_t(0)));
                        for (; it != keyed.end() && it->first == k; ++it) {
                            if (it->second == i) continue;
                            double s = 0;
                            for (int c = 0; c < 3; ++c) {
                                double e = double(p[it->second * 3 + c]) - p[i * 3 + c];
                                s += e * e;
                            }
                            best = std::min(best, s);
                        }
                    }
        }
        d[i] = std::sqrt(best) / spacing;
    }
    Spacing s;
    double sum = 0, sum2 = 0, lowest = 1e300;
    for (double x : d) {
        sum += x;
        sum2 += x * x;
        lowest = std::min(lowest, x);
    }
    s.mean = sum / n;
    s.cv = std::sqrt(std::max(sum2 / n - s.mean * s.mean, 0.0)) / s.mean;
    s.min_over_mean = lowest / s.mean;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const char* path = nullptr;
    bool quality = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (!std::strcmp(argv[i], "--quality")) {
            quality = true;
        } else if (argv[i][0] == '-') {
            std::fprintf(stderr, "stipple-inspect: unknown option '%s' (see --help)\n", argv[i]);
            return 1;
        } else if (!path) {
            path = argv[i];
        } else {
            std::fprintf(stderr, "stipple-inspect: more than one asset given\n");
            return 1;
        }
    }
    if (!path) {
        std::fprintf(stderr, "stipple-inspect: no asset given (see --help)\n");
        return 1;
    }
    stipple::Asset a;
    stipple::LoadStatus st = stipple::load_asset_file(path, &a);
    if (!st.ok()) {
        std::fprintf(stderr, "stipple-inspect: %s: %s\n", path, st.message);
        return 1;
    }
    const stipple::PointsView& p = a.points;
    const char* names[stipple::kSectionCount] = {"MESH", "SKIN", "CLIP", "PNTQ", "EDGE", "MRPH"};
    size_t mesh_side = 0;
    for (int s : {stipple::kSectionMesh, stipple::kSectionSkin, stipple::kSectionClips,
                  stipple::kSectionEdges, stipple::kSectionMorph})
        mesh_side += a.section_size[s];
    std::printf("{\"asset\": \"%s\", \"version\": %u, \"bytes\": %zu, \"sections\": {", path,
                a.version, a.file_size);
    for (int s = 0; s < stipple::kSectionCount; ++s)
        std::printf("%s\"%s\": %zu", s ? ", " : "", names[s], a.section_size[s]);
    std::printf(
        "}, \"vertices\": %u, \"triangles\": %u, \"joints\": %u, \"clips\": %u, "
        "\"morph_targets\": %u, \"points\": %u, \"neighbours_per_point\": %.2f, "
        "\"bytes_per_point\": %.2f, \"radius_first\": %g, \"radius_last\": %g",
        a.mesh.vertex_count, a.mesh.triangle_count, a.skinned ? a.skin.skeleton.joint_count : 0,
        a.clip_count, a.morph.target_count, p.point_count,
        p.point_count ? double(p.neighbour_count) / p.point_count : 0.0,
        p.point_count ? double(a.file_size - mesh_side) / p.point_count : 0.0,
        p.point_count ? double(p.radius[0]) : 0.0,
        p.point_count ? double(p.radius[p.point_count - 1]) : 0.0);
    if (quality && p.point_count > 1) {
        std::vector<float> pos(size_t(p.point_count) * 3), nrm(size_t(p.point_count) * 3);
        stipple::place_points(p, a.mesh.indices, a.mesh.positions, a.mesh.normals, pos.data(),
                              nrm.data());
        const double area = surface_area(a.mesh);
        std::printf(", \"surface_area\": %g, \"quality\": [", area);
        bool first = true;
        for (uint32_t n : {1000u, 4000u, 16000u, 64000u}) {
            if (n > p.point_count) break;
            Spacing s = nearest_neighbour_spacing(pos.data(), n, area);
            std::printf(
                "%s{\"points\": %u, \"nn_mean\": %.4f, \"nn_cv\": %.4f, "
                "\"nn_min_over_mean\": %.4f}",
                first ? "" : ", ", n, s.mean, s.cv, s.min_over_mean);
            first = false;
        }
        std::printf("]");
    }
    std::printf("}\n");
    return 0;
}
