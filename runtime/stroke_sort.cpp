// Back-to-front order of paintstroke segments (runtime/stroke_sort.h): a stable LSD radix
// sort, 4 passes of 8 bits over the depths' float bits, into caller-owned buffers.
#include "runtime/stroke_sort.h"

#include <cstring>

namespace stipple {

namespace {

// Unsigned key whose ascending order is the float's *descending* order (largest depth first):
// the usual order-preserving map (flip all bits of negatives, the sign bit of the rest), then
// complemented.
uint32_t descending_key(float depth) {
    uint32_t u;
    std::memcpy(&u, &depth, sizeof u);
    const uint32_t ascending = (u & 0x80000000u) ? ~u : (u | 0x80000000u);
    return ~ascending;
}

}  // namespace

void sort_segments_back_to_front(const StrokeMesh& mesh, uint32_t* order, uint32_t* scratch) {
    const uint32_t n = mesh.segment_count;
    if (n == 0) return;
    uint32_t* keys = scratch + n;  // keys by segment index; scratch[0, n) is the ping-pong buffer
    uint32_t counts[4][256];
    std::memset(counts, 0, sizeof counts);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t k = descending_key(mesh.segments[i].depth);
        keys[i] = k;
        order[i] = i;
        for (int p = 0; p < 4; ++p) ++counts[p][(k >> (8 * p)) & 0xffu];
    }
    uint32_t* src = order;
    uint32_t* dst = scratch;
    for (int p = 0; p < 4; ++p) {
        // Each pass is a stable counting sort on one byte; an even number of passes leaves
        // the result in `order`.
        uint32_t offset[256];
        uint32_t sum = 0;
        for (int b = 0; b < 256; ++b) {
            offset[b] = sum;
            sum += counts[p][b];
        }
        const int shift = 8 * p;
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t s = src[i];
            dst[offset[(keys[s] >> shift) & 0xffu]++] = s;
        }
        uint32_t* tmp = src;
        src = dst;
        dst = tmp;
    }
}

void gather_sorted_indices(const StrokeMesh& mesh, const uint32_t* order, uint32_t* out_indices) {
    uint32_t k = 0;
    for (uint32_t i = 0; i < mesh.segment_count; ++i) {
        const StrokeSegment& s = mesh.segments[order[i]];
        for (uint32_t j = 0; j < s.index_count; ++j)
            out_indices[k++] = mesh.indices[s.first_index + j];
    }
}

}  // namespace stipple
