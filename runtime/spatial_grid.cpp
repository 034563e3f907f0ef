#include "runtime/spatial_grid.h"

#include <algorithm>
#include <new>

#include "runtime/memory.h"

namespace stipple {

bool SpatialGrid::build(const float* p, uint32_t n, float cell_size, const float* use) {
    points = p;
    cell = cell_size;
    uint32_t buckets = 1;
    while (buckets < 2 * n && buckets < (1u << 30)) buckets <<= 1;
    mask = buckets - 1;
    start = make_buffer<uint32_t>(size_t(buckets) + 1);
    items = make_buffer<uint32_t>(n);
    slot_points = make_buffer<float>(size_t(n) * 3);
    slot_cells = make_buffer<int32_t>(size_t(n) * 3);
    Buffer<uint32_t> of = make_buffer<uint32_t>(n), fill = make_buffer<uint32_t>(buckets);
    if (!start || !items || !slot_points || !slot_cells || !of || !fill) return false;
    std::fill(start.get(), start.get() + buckets + 1, 0u);
    for (uint32_t i = 0; i < n; ++i) {
        of[i] = bucket(at(point(i)));
        if (!use || use[i] > 0.0f) ++start[of[i] + 1];
    }
    for (uint32_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
    std::copy(start.get(), start.get() + buckets, fill.get());
    for (uint32_t i = 0; i < n; ++i) {
        if (use && !(use[i] > 0.0f)) continue;
        const uint32_t k = fill[of[i]]++;
        items[k] = i;
        const glm::ivec3 c = at(point(i));
        for (int d = 0; d < 3; ++d) {
            slot_points[size_t(k) * 3 + d] = p[size_t(i) * 3 + d];
            slot_cells[size_t(k) * 3 + d] = c[d];
        }
    }
    return true;
}

}  // namespace stipple
