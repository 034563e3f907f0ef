#include "runtime/spatial_grid.h"

#include <algorithm>
#include <new>

#include "runtime/memory.h"

namespace stipple {

namespace {}  // namespace

bool SpatialGrid::build(const float* p, uint32_t n, float cell_size, const float* use) {
    points = p;
    cell = cell_size;
    uint32_t buckets = 1;
    while (buckets < 2 * n && buckets < (1u << 30)) buckets <<= 1;
    mask = buckets - 1;
    start = make_buffer<uint32_t>(size_t(buckets) + 1);
    items = make_buffer<uint32_t>(n);
    Buffer<uint32_t> of = make_buffer<uint32_t>(n), fill = make_buffer<uint32_t>(buckets);
    if (!start || !items || !of || !fill) return false;
    std::fill(start.get(), start.get() + buckets + 1, 0u);
    for (uint32_t i = 0; i < n; ++i) {
        of[i] = bucket(at(point(i)));
        if (!use || use[i] > 0.0f) ++start[of[i] + 1];
    }
    for (uint32_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
    std::copy(start.get(), start.get() + buckets, fill.get());
    for (uint32_t i = 0; i < n; ++i)
        if (!use || use[i] > 0.0f) items[fill[of[i]]++] = i;
    return true;
}

}  // namespace stipple
