#include "runtime/region_density.h"

#include <algorithm>
#include <cmath>

#include "runtime/memory.h"

namespace stipple {

namespace {

float distance_squared(const float* a, const float* b) {
    const float dx = a[0] - b[0];
    const float dy = a[1] - b[1];
    const float dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

// Squared distance from point i to its k-th nearest point of [0, i) (k <= i, k <= 32).
float kth_nearest_squared(const float* positions, uint32_t i, uint32_t k) {
    float best[32];
    uint32_t n = 0;
    for (uint32_t j = 0; j < i; ++j) {
        const float d = distance_squared(positions + size_t(i) * 3, positions + size_t(j) * 3);
        if (n == k && d >= best[k - 1]) continue;
        uint32_t at = n < k ? n++ : k - 1;
        while (at > 0 && best[at - 1] > d) {
            best[at] = best[at - 1];
            --at;
        }
        best[at] = d;
    }
    return best[k - 1];
}

// A uniform grid over all points (counting sort by cell; positions copied in cell order), so
// the share of the set inside a ball visits only the cells the ball overlaps. The count of
// points inside is a sum of 1 and 1/2, exact in any order: the result equals the brute force.
struct Grid {
    float lo[3] = {0, 0, 0};
    float cell = 1;
    uint32_t dim[3] = {1, 1, 1};
    Buffer<uint32_t> start;  // per cell, into sorted; one past the end last
    Buffer<float> sorted;    // positions, 3 per point, in cell order
};

uint32_t cell_of(const Grid& g, float x, int axis) {
    const float c = std::floor((x - g.lo[axis]) / g.cell);
    if (!(c > 0.0f)) return 0;
    return c >= float(g.dim[axis] - 1) ? g.dim[axis] - 1 : uint32_t(c);
}

size_t cell_index(const Grid& g, const float* p) {
    return (size_t(cell_of(g, p[2], 2)) * g.dim[1] + cell_of(g, p[1], 1)) * g.dim[0] +
           cell_of(g, p[0], 0);
}

enum class GridResult { built, left_alone, out_of_memory };

// left_alone when a coordinate is not finite or the set has no extent.
GridResult build_grid(const float* positions, uint32_t count, Grid* g) {
    float hi[3] = {positions[0], positions[1], positions[2]};
    for (int a = 0; a < 3; ++a) g->lo[a] = positions[a];
    for (size_t k = 0; k < size_t(count) * 3; ++k) {
        const float x = positions[k];
        if (!std::isfinite(x)) return GridResult::left_alone;
        g->lo[k % 3] = std::fmin(g->lo[k % 3], x);
        hi[k % 3] = std::fmax(hi[k % 3], x);
    }
    double ext[3], vol = 1, longest = 0;
    for (int a = 0; a < 3; ++a) {
        ext[a] = double(hi[a]) - double(g->lo[a]);
        longest = std::fmax(longest, ext[a]);
    }
    if (!(longest > 0) || !std::isfinite(longest)) return GridResult::left_alone;
    for (int a = 0; a < 3; ++a) vol *= std::fmax(ext[a], longest / 1024);
    double cell = std::cbrt(vol / count);
    size_t cells = 0;
    for (;;) {
        cells = 1;
        for (int a = 0; a < 3; ++a) {
            const double d = std::floor(ext[a] / cell) + 1;
            g->dim[a] = uint32_t(d);
            cells *= g->dim[a];
        }
        if (cells <= size_t(count) * 2 + 64) break;
        cell *= 1.25;
    }
    g->cell = float(cell);
    Buffer<uint32_t> index, fill;
    if (!alloc(&g->start, cells + 1) || !alloc(&index, count) || !alloc(&fill, cells) ||
        !alloc(&g->sorted, size_t(count) * 3))
        return GridResult::out_of_memory;
    std::fill(g->start.get(), g->start.get() + cells + 1, 0u);
    for (uint32_t j = 0; j < count; ++j) {
        index[j] = uint32_t(cell_index(*g, positions + size_t(j) * 3));
        ++g->start[index[j] + 1];
    }
    for (size_t c = 0; c < cells; ++c) g->start[c + 1] += g->start[c];
    std::copy(g->start.get(), g->start.get() + cells, fill.get());
    for (uint32_t j = 0; j < count; ++j) {
        const size_t at = size_t(fill[index[j]]++) * 3;
        for (int a = 0; a < 3; ++a) g->sorted[at + a] = positions[size_t(j) * 3 + a];
    }
    return GridResult::built;
}

// Share of the whole set within squared distance r2 of p (the rim counts half).
double share_within(const Grid& g, uint32_t count, const float* p, float r2) {
    // The cells the ball's box overlaps, widened a little against rounding: a point outside
    // them is farther than r in exact and in float arithmetic.
    const float r = std::sqrt(r2) * 1.001f + g.cell * 1e-3f;
    uint32_t from[3], to[3];
    for (int a = 0; a < 3; ++a) {
        from[a] = cell_of(g, p[a] - r, a);
        to[a] = cell_of(g, p[a] + r, a);
    }
    double inside = 0;
    for (uint32_t z = from[2]; z <= to[2]; ++z) {
        for (uint32_t y = from[1]; y <= to[1]; ++y) {
            const size_t row = (size_t(z) * g.dim[1] + y) * g.dim[0];
            const uint32_t end = g.start[row + to[0] + 1];
            for (uint32_t j = g.start[row + from[0]]; j < end; ++j) {
                const float d = distance_squared(p, g.sorted.get() + size_t(j) * 3);
                inside += d < r2 ? 1.0 : (d == r2 ? 0.5 : 0.0);
            }
        }
    }
    return inside / double(count);
}

}  // namespace

bool density_corrected_radii(const float* positions, uint32_t count,
                             const RegionDensityParams& params, float* radius) {
    const uint32_t m = params.neighbours;
    const uint32_t limit = params.limit < count ? params.limit : count;
    if (m == 0 || m > 32 || limit < 8 || count < 4 * limit) return true;
    Grid grid;
    const GridResult built = build_grid(positions, count, &grid);
    if (built != GridResult::built) return built == GridResult::left_alone;
    // Each factor c_i = (i + 1) share_i / (k + 1/2), about 1 where the prefix is even (the
    // k-th neighbour on the ball's rim counts half), is applied as it is found; the
    // estimator's bias then comes off: its mean over ranks [limit / 2, limit), even on every
    // corpus asset (the horse's from rank 256 on) and coarse enough against the whole set,
    // which measures the area, for many samples per ball. (The newest points of a coarse
    // prefix are not a sample of it, as they go where it is sparse: the coarse ranks' own
    // mean is no reference.)
    double bias = 0;
    for (uint32_t i = 1; i < limit; ++i) {
        const uint32_t k = i < m ? i : m;
        const float r2 = kth_nearest_squared(positions, i, k);
        const float* p = positions + size_t(i) * 3;
        double c = double(i + 1) * share_within(grid, count, p, r2) / (k + 0.5);
        c = c > 1e-6 ? c : 1e-6;
        if (i >= limit / 2) bias += c;
        radius[i] *= float(std::sqrt(c));
    }
    const float unbias = float(std::sqrt(double(limit - limit / 2) / bias));
    for (uint32_t i = 1; i < limit; ++i) radius[i] *= unbias;
    return true;
}

}  // namespace stipple
