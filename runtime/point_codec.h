// Compact point hierarchy coding (format version 1, section PNTQ): one bit stream holding,
// per point in hierarchy order,
//   u, v            barycentrics, 12 bits each (round to nearest, v clamped so u + v <= 1)
//   radius          12-bit log code: r = r_max * 2^(-q / 256), q = 4095 means 0
//   neighbour count 4 bits (lists are cut to 15 at bake)
//   neighbours      sorted descending; the first as a zigzag offset from the point's own
//                   index, the rest as gaps - 1; Exp-Golomb codes whose order grows with
//                   log2(index), because relevant neighbours sit at levels of similar size
//   host triangle   zigzag delta from the host of the first neighbour below the point's
//                   index (Exp-Golomb order 4: neighbours are close on the surface), or,
//                   without one, from the previous point's host (order log2(T) - 2)
// Errors: barycentric +-1/8190 of the host triangle's extent (the point stays exactly on the
// triangle), radius +-0.14% (half of 2^(1/256) - 1). Decoding is bounds-checked and returns
// false on a malformed stream.
#pragma once
#include <cstddef>
#include <cstdint>

namespace stipple::codec {

constexpr int kBaryBits = 12;
constexpr int kRadiusBits = 12;
constexpr int kCountBits = 4;
constexpr uint32_t kMaxNeighbours = (1u << kCountBits) - 1;
constexpr float kRadiusStepsPerOctave = 256.0f;
constexpr uint32_t kRadiusZero = (1u << kRadiusBits) - 1;
inline int floor_log2(uint32_t x) {
    int log2 = 0;
    while ((x >> log2) > 1) ++log2;
    return log2;
}

// Exp-Golomb order of point i's neighbour offsets.
inline int neighbour_order(uint32_t i) {
    return floor_log2(i) > 2 ? floor_log2(i) - 2 : 0;
}

// The neighbour whose host triangle predicts point i's host: the first (largest) neighbour
// index below i, decoded earlier; -1 if none (then the previous point's host is used).
inline int32_t host_reference(uint32_t i, const uint32_t* sorted_descending, uint32_t count) {
    for (uint32_t j = 0; j < count; ++j)
        if (sorted_descending[j] < i) return int32_t(sorted_descending[j]);
    return -1;
}
constexpr int kPredictedHostOrder = 4;

// Exp-Golomb order of host triangle deltas without a prediction.
inline int host_order(uint32_t triangle_count) {
    return floor_log2(triangle_count) > 2 ? floor_log2(triangle_count) - 2 : 0;
}

struct BitReader {
    const uint8_t* data;
    size_t bit_count;
    size_t at = 0;
    bool ok = true;

    uint32_t bits(int n) {
        if (n == 0) return 0;
        if (!ok || at + size_t(n) > bit_count) {
            ok = false;
            return 0;
        }
        uint32_t v = 0;
        for (int k = 0; k < n; ++k, ++at) v |= uint32_t((data[at >> 3] >> (at & 7)) & 1u) << k;
        return v;
    }
    // Exp-Golomb code of order k: n ones and a zero, then n + k bits of v + 2^k - 2^(n+k).
    // Lengths are capped so a corrupted stream fails instead of overflowing.
    uint32_t golomb(int k) {
        int n = 0;
        while (ok && bits(1) == 1)
            if (++n + k > 31) ok = false;
        if (!ok) return 0;
        uint64_t base = (uint64_t(1) << (n + k)) - (uint64_t(1) << k);
        uint64_t v = base + bits(n + k);
        if (v > 0xFFFFFFFFull) ok = false;
        return uint32_t(v);
    }
    int32_t zigzag(int k) {
        uint32_t z = golomb(k);
        return int32_t(z >> 1) ^ -int32_t(z & 1);
    }
};

}  // namespace stipple::codec
