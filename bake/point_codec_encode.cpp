#include "bake/point_codec_encode.h"

#include <algorithm>
#include <cmath>

#include "runtime/point_codec.h"

namespace stipple::bake {

namespace {

struct BitWriter {
    std::vector<uint8_t> bytes;
    uint64_t at = 0;
    void bits(uint32_t v, int n) {
        for (int k = 0; k < n; ++k, ++at) {
            if ((at >> 3) >= bytes.size()) bytes.push_back(0);
            bytes[at >> 3] |= uint8_t(((v >> k) & 1u) << (at & 7));
        }
    }
    // Exp-Golomb of order k (see runtime/point_codec.h).
    void golomb(uint32_t v, int k) {
        uint64_t w = uint64_t(v) + (uint64_t(1) << k);
        int n = 0;
        while ((w >> (n + k + 1)) != 0) ++n;
        for (int i = 0; i < n; ++i) bits(1, 1);
        bits(0, 1);
        uint64_t rest = w - (uint64_t(1) << (n + k));
        bits(uint32_t(rest), n + k);
    }
    void zigzag(int32_t v, int k) { golomb((uint32_t(v) << 1) ^ uint32_t(v >> 31), k); }
};

uint32_t quantize_unit(float x) {
    const float scale = float((1u << codec::kBaryBits) - 1);
    return uint32_t(std::lround(std::min(std::max(x, 0.0f), 1.0f) * scale));
}

uint32_t quantize_radius(float r, float r_max) {
    if (!(r > 0.0f)) return codec::kRadiusZero;
    double q = std::round(-std::log2(double(r) / double(r_max)) * codec::kRadiusStepsPerOctave);
    return uint32_t(std::min(std::max(q, 0.0), double(codec::kRadiusZero - 1)));
}

}  // namespace

EncodedPoints encode_points(const PointHierarchy& p, uint32_t triangle_count) {
    EncodedPoints out;
    for (float r : p.radius) out.radius_max = std::max(out.radius_max, r);
    if (out.radius_max <= 0.0f) out.radius_max = 1.0f;
    BitWriter w;
    const uint32_t bary_max = (1u << codec::kBaryBits) - 1;
    for (uint32_t i = 0; i < p.size(); ++i) {
        uint32_t u = quantize_unit(p.bary_u[i]);
        uint32_t v = std::min(quantize_unit(p.bary_v[i]), bary_max - u);
        w.bits(u, codec::kBaryBits);
        w.bits(v, codec::kBaryBits);
        w.bits(quantize_radius(p.radius[i], out.radius_max), codec::kRadiusBits);

        std::vector<uint32_t> n(p.neighbours.begin() + p.neighbour_offsets[i],
                                p.neighbours.begin() + p.neighbour_offsets[i + 1]);
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
        std::reverse(n.begin(), n.end());
        if (n.size() > codec::kMaxNeighbours) n.resize(codec::kMaxNeighbours);
        w.bits(uint32_t(n.size()), codec::kCountBits);
        const int k = codec::neighbour_order(i);
        for (size_t j = 0; j < n.size(); ++j) {
            if (j == 0)
                w.zigzag(int32_t(i) - int32_t(n[0]), k);
            else
                w.golomb(n[j - 1] - n[j] - 1, k);
        }
        // The host triangle, predicted from an already coded neighbour's host: neighbours
        // are close on the surface, so with a spatially coherent triangle order the delta is
        // small.
        const int32_t reference = codec::host_reference(i, n.data(), uint32_t(n.size()));
        const bool predicted = reference >= 0;
        const uint32_t base = predicted ? p.host_triangle[uint32_t(reference)]
                              : i > 0   ? p.host_triangle[i - 1]
                                        : 0;
        w.zigzag(int32_t(p.host_triangle[i] - base),
                 predicted ? codec::kPredictedHostOrder : codec::host_order(triangle_count));
    }
    out.bit_count = w.at;
    out.bytes = std::move(w.bytes);
    return out;
}

}  // namespace stipple::bake
