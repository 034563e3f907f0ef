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

#include "bake/point_grid.h"
#include "runtime/asset.h"
#include "runtime/asset_format.h"
#include "runtime/point_placement.h"

namespace {

const char* kUsage =
    "usage: stipple-inspect ASSET.stip [--quality] [--prefixes N,N,...]\n"
    "  --quality       nearest-neighbour spacing of the 1k/4k/16k/64k-point prefixes (levels)\n"
    "                  and the tone calibration (area per point / radius^2) there\n"
    "  --prefixes L    other prefix sizes for --quality (comma-separated)\n";

struct Spacing {
    double mean = 0, cv = 0, min_over_mean = 0;
    double density_cv = 0;  // of the point count within 3 even spacings of each point
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

// Nearest-neighbour distances among the first n points (a grid of cells twice the even
// spacing; the search widens until the nearest point found is nearer than the ring).
Spacing nearest_neighbour_spacing(const std::vector<double>& xyz, uint32_t n, double area) {
    const double spacing = std::sqrt(area / n);
    stipple::bake::PointGrid grid;
    grid.build(xyz.data(), n, 2 * spacing);
    std::vector<double> d(n);
    for (uint32_t i = 0; i < n; ++i) {
        double best = 1e300;
        for (int ring = 1; ring <= 64; ring *= 2) {
            grid.visit(&xyz[size_t(i) * 3], ring, [&](uint32_t j) {
                if (j == i) return;
                double s = 0;
                for (int k = 0; k < 3; ++k) {
                    const double e = xyz[size_t(j) * 3 + size_t(k)] - xyz[size_t(i) * 3 + size_t(k)];
                    s += e * e;
                }
                best = std::min(best, s);
            });
            if (std::sqrt(best) <= ring * grid.cell()) break;
        }
        d[i] = std::sqrt(best) / spacing;
    }
    // Large-scale evenness, which nearest-neighbour distances do not see (a region twice as
    // dense can be locally regular): the points within 3 even spacings of each point, about
    // 28 on a flat even surface; Poisson points give a CV near 0.2.
    const double reach2 = 9 * spacing * spacing;
    double csum = 0, csum2 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        double count = 0;
        grid.visit(&xyz[size_t(i) * 3], 2, [&](uint32_t j) {
            double s2 = 0;
            for (int k = 0; k < 3; ++k) {
                const double e = xyz[size_t(j) * 3 + size_t(k)] - xyz[size_t(i) * 3 + size_t(k)];
                s2 += e * e;
            }
            count += s2 <= reach2;
        });
        csum += count;
        csum2 += count * count;
    }
    const double cmean = csum / n;
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
    s.density_cv = std::sqrt(std::max(csum2 / n - cmean * cmean, 0.0)) / cmean;
    return s;
}

// Tone calibration (runtime/stipple_size.h): the area per point of an n-point prefix over
// the squared radius of its last points, mean over ranks [0.9 n, n); 1.0 is what the
// runtime's kRegionPerRadiusSquared assumes.
double region_per_radius2(const stipple::PointsView& p, uint32_t n, double area) {
    double sum = 0;
    uint32_t count = 0;
    for (uint32_t i = uint32_t(0.9 * n); i < n; ++i, ++count)
        sum += area / double(i + 1) / (double(p.radius[i]) * p.radius[i]);
    return count ? sum / count : 0;
}

std::vector<uint32_t> parse_prefixes(const char* text) {
    std::vector<uint32_t> out;
    for (const char* at = text; *at;) {
        char* end = nullptr;
        const long v = std::strtol(at, &end, 10);
        if (end == at || v <= 1 || v > 100000000) return {};
        out.push_back(uint32_t(v));
        at = *end == ',' ? end + 1 : end;
        if (*end && *end != ',') return {};
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const char* path = nullptr;
    bool quality = false;
    std::vector<uint32_t> prefixes = {1000, 4000, 16000, 64000};
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (!std::strcmp(argv[i], "--quality")) {
            quality = true;
        } else if (!std::strcmp(argv[i], "--prefixes")) {
            prefixes = i + 1 < argc ? parse_prefixes(argv[++i]) : std::vector<uint32_t>();
            if (prefixes.empty()) {
                std::fprintf(stderr, "stipple-inspect: --prefixes needs sizes > 1, e.g. 1000,4000\n");
                return 1;
            }
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
    size_t mesh_side = 0;
    for (int s : {stipple::kSectionMesh, stipple::kSectionSkin, stipple::kSectionClips,
                  stipple::kSectionEdges, stipple::kSectionMorph, stipple::kSectionBounds,
                  stipple::kSectionSides})
        mesh_side += a.section_size[s];
    std::printf("{\"asset\": \"%s\", \"version\": %u, \"bytes\": %zu, \"sections\": {", path,
                a.version, a.file_size);
    for (int s = 0; s < stipple::kSectionCount; ++s)
        std::printf("%s\"%s\": %zu", s ? ", " : "", stipple::section_name(s), a.section_size[s]);
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
    // Orientation and framing (BNDS) and double-sided triangles (SIDE), format version 3.
    const stipple::BoundsView& b = a.bounds;
    std::printf(", \"up\": \"%s\", \"double_sided_triangles\": %u",
                !b.present ? "unknown" : b.up_axis == stipple::format::kUpZ ? "z" : "y",
                a.sides.triangle_count);
    auto box = [](const float* x) {
        std::printf("{\"min\": [%g, %g, %g], \"max\": [%g, %g, %g]}", double(x[0]), double(x[1]),
                    double(x[2]), double(x[3]), double(x[4]), double(x[5]));
    };
    if (b.present) {
        std::printf(", \"bounds\": {\"rest\": ");
        box(b.rest);
        std::printf(", \"clips\": [");
        for (uint32_t c = 0; c < a.clip_count; ++c) {
            std::printf("%s{\"name\": \"%s\", \"duration\": %g, \"box\": ", c ? ", " : "",
                        a.clips[c].name, double(a.clips[c].duration));
            box(b.clips + size_t(c) * 6);
            std::printf("}");
        }
        std::printf("]}");
    }
    if (quality && p.point_count > 1) {
        std::vector<float> pos(size_t(p.point_count) * 3), nrm(size_t(p.point_count) * 3);
        stipple::place_points(p, a.mesh.indices, a.mesh.positions, a.mesh.normals, pos.data(),
                              nrm.data());
        const std::vector<double> xyz(pos.begin(), pos.end());
        const double area = surface_area(a.mesh);
        std::printf(", \"surface_area\": %g, \"quality\": [", area);
        bool first = true;
        for (uint32_t n : prefixes) {
            if (n > p.point_count) continue;
            Spacing s = nearest_neighbour_spacing(xyz, n, area);
            std::printf(
                "%s{\"points\": %u, \"nn_mean\": %.4f, \"nn_cv\": %.4f, "
                "\"nn_min_over_mean\": %.4f, \"density_cv\": %.4f, \"region_per_r2\": %.3f}",
                first ? "" : ", ", n, s.mean, s.cv, s.min_over_mean, s.density_cv,
                region_per_radius2(p, n, area));
            first = false;
        }
        std::printf("]");
    }
    std::printf("}\n");
    return 0;
}
