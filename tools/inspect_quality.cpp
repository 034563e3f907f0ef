#include "tools/inspect_quality.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "runtime/spatial_grid.h"

namespace stipple::tools {

namespace {

// The grid's cell range is computed in float: ask for a little more than the distance that
// must be covered, so no point within it is missed to rounding.
constexpr double kReachMargin = 1.001;

double distance2(const std::vector<float>& xyz, uint32_t i, uint32_t j) {
    double s = 0;
    for (size_t k = 0; k < 3; ++k) {
        const double e = double(xyz[size_t(j) * 3 + k]) - double(xyz[size_t(i) * 3 + k]);
        s += e * e;
    }
    return s;
}

// Mean, coefficient of variation and min / mean of `d`.
void summarize(const std::vector<double>& d, Spacing* s) {
    double sum = 0, sum2 = 0, lowest = 1e300;
    for (double x : d) {
        sum += x;
        sum2 += x * x;
        lowest = std::min(lowest, x);
    }
    const double n = double(d.size());
    s->mean = sum / n;
    s->cv = std::sqrt(std::max(sum2 / n - s->mean * s->mean, 0.0)) / s->mean;
    s->min_over_mean = lowest / s->mean;
}

}  // namespace

double surface_area(const MeshView& m) {
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

// Nearest-neighbour distances among the first n points (cells twice the even spacing; the
// search widens until the nearest point found is nearer than the reach searched).
Spacing nearest_neighbour_spacing(const std::vector<float>& xyz, uint32_t n, double area) {
    const double spacing = std::sqrt(area / n);
    const double cell = 2 * spacing;
    SpatialGrid grid;
    if (!grid.build(xyz.data(), n, float(cell), nullptr)) throw std::bad_alloc();
    std::vector<double> d(n);
    for (uint32_t i = 0; i < n; ++i) {
        double best = 1e300;
        for (int ring = 1; ring <= 64; ring *= 2) {
            const double reach = ring * cell;
            grid.near(grid.point(i), float(reach * kReachMargin), [&](uint32_t j) {
                if (j != i) best = std::min(best, distance2(xyz, i, j));
            });
            if (std::sqrt(best) <= reach) break;
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
        grid.near(grid.point(i), float(3 * spacing * kReachMargin),
                  [&](uint32_t j) { count += distance2(xyz, i, j) <= reach2; });
        csum += count;
        csum2 += count * count;
    }
    const double cmean = csum / n;
    Spacing s;
    summarize(d, &s);
    s.density_cv = std::sqrt(std::max(csum2 / n - cmean * cmean, 0.0)) / cmean;
    return s;
}

double region_per_radius2(const PointsView& p, uint32_t n, double area) {
    double sum = 0;
    uint32_t count = 0;
    for (uint32_t i = uint32_t(0.9 * n); i < n; ++i, ++count)
        sum += area / double(i + 1) / (double(p.radius[i]) * p.radius[i]);
    return count ? sum / count : 0;
}

}  // namespace stipple::tools
