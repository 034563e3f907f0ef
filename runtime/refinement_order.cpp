#include "runtime/refinement_order.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <memory>
#include <new>

#include "runtime/memory.h"
#include "runtime/spatial_grid.h"

namespace stipple {

namespace {

glm::vec3 point3(const float* p, uint32_t i) {
    return glm::vec3(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]);
}

// Max-heap of triangles keyed by dist, with decrease-key.
struct Heap {
    uint32_t size = 0;
    Buffer<uint32_t> item, slot;  // slot[t] = position of t, or ~0u
    const float* key = nullptr;

    void swap(uint32_t a, uint32_t b) {
        std::swap(item[a], item[b]);
        slot[item[a]] = a;
        slot[item[b]] = b;
    }
    void up(uint32_t i) {
        while (i > 0 && key[item[(i - 1) / 2]] < key[item[i]])
            swap(i, (i - 1) / 2), i = (i - 1) / 2;
    }
    void down(uint32_t i) {
        for (;;) {
            uint32_t l = 2 * i + 1, r = l + 1, m = i;
            if (l < size && key[item[l]] > key[item[m]]) m = l;
            if (r < size && key[item[r]] > key[item[m]]) m = r;
            if (m == i) return;
            swap(i, m);
            i = m;
        }
    }
    void push(uint32_t t) {
        item[size] = t;
        slot[t] = size;
        up(size++);
    }
    uint32_t pop() {
        const uint32_t t = item[0];
        swap(0, --size);
        slot[t] = ~0u;
        down(0);
        return t;
    }
};

}  // namespace

bool first_point_phases(uint32_t triangle_count, const float* first_points, const float* area,
                        uint32_t baked_count, const float* baked, float* phase) {
    const uint32_t n = triangle_count;
    if (n == 0) return true;
    double total_area = 0.0;
    for (uint32_t t = 0; t < n; ++t) total_area += std::max(area[t], 0.0f);
    uint32_t rank = 0;
    if (total_area > 0.0) {
        // Cell size ~ the spacing of baked points and triangles together; distances beyond a
        // few cells are clamped (such holes come first whatever their exact size).
        const float spacing = float(std::sqrt(total_area / double(baked_count + n)));
        const float reach = 3.0f * spacing;
        SpatialGrid baked_grid, tri_grid;
        Buffer<float> dist = make_buffer<float>(n);
        Heap heap;
        heap.item = make_buffer<uint32_t>(n);
        heap.slot = make_buffer<uint32_t>(n);
        heap.key = dist.get();
        if (!dist || !heap.item || !heap.slot ||
            !baked_grid.build(baked, baked_count, reach, nullptr) ||
            !tri_grid.build(first_points, n, 1.5f * spacing, area))
            return false;
        for (uint32_t t = 0; t < n; ++t) {
            heap.slot[t] = ~0u;
            dist[t] = reach;
            if (!(area[t] > 0.0f)) continue;
            const glm::vec3 p = point3(first_points, t);
            float& d = dist[t];
            baked_grid.near(
                p, reach, [&](uint32_t i) { d = std::min(d, glm::length(point3(baked, i) - p)); });
            heap.push(t);
        }
        while (heap.size > 0) {
            const uint32_t t = heap.pop();
            phase[t] = (float(rank++) + 0.5f) / float(n);
            const glm::vec3 p = point3(first_points, t);
            tri_grid.near(p, dist[t], [&](uint32_t u) {
                if (heap.slot[u] == ~0u) return;  // ranked already
                const float d = glm::length(point3(first_points, u) - p);
                if (d < dist[u]) {
                    dist[u] = d;
                    heap.down(heap.slot[u]);
                }
            });
        }
    }
    // Degenerate triangles (never refined) rank last.
    for (uint32_t t = 0; t < n; ++t)
        if (!(area[t] > 0.0f) || total_area <= 0.0) phase[t] = (float(rank++) + 0.5f) / float(n);
    return true;
}

}  // namespace stipple
