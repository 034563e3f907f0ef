// The PNTQ section: the coded point hierarchy (runtime/point_codec.h), decoded at load into
// PointsView's arrays. Split from asset.cpp.
#include <cmath>
#include <cstring>
#include <new>

#include "runtime/asset_limits.h"
#include "runtime/asset_parse.h"
#include "runtime/point_codec.h"

namespace stipple::detail {

namespace {

// The fewest bits a point can take: u, v, radius, neighbour count, and a host delta of at
// least one bit (an Exp-Golomb code's terminating zero).
constexpr uint64_t kMinPointBits =
    codec::kBaryBits * 2 + codec::kRadiusBits + codec::kCountBits + 1;
static_assert(codec::kMaxNeighbours == limits::kMaxNeighboursPerPoint, "one neighbour limit");

// One pass over the point stream (thesis §4.5 fields, coded as in point_codec.h). With
// out == nullptr it only counts neighbours so the caller can size the arrays.
Status decode_point_stream(codec::BitReader r, uint32_t point_count, float radius_max,
                           uint32_t triangle_count, uint32_t* host, PointsView* out,
                           uint32_t* neighbour_total) {
    uint32_t total = 0, list[codec::kMaxNeighbours];
    const float bary_scale = 1.0f / float((1u << codec::kBaryBits) - 1);
    for (uint32_t i = 0; i < point_count; ++i) {
        uint32_t u = r.bits(codec::kBaryBits), v = r.bits(codec::kBaryBits);
        uint32_t q = r.bits(codec::kRadiusBits), n = r.bits(codec::kCountBits);
        const int k = codec::neighbour_order(i);
        for (uint32_t j = 0; j < n && r.ok; ++j) {
            int64_t index =
                j == 0 ? int64_t(i) - r.zigzag(k) : int64_t(list[j - 1]) - 1 - r.golomb(k);
            if (index < 0 || index >= int64_t(point_count))
                return load_failure(LoadError::out_of_range,
                                    "PNTQ: point %u neighbour %lld out of range", i,
                                    static_cast<long long>(index));
            list[j] = uint32_t(index);
        }
        const int32_t reference = codec::host_reference(i, list, n);
        const uint32_t base = reference >= 0 ? host[reference] : i > 0 ? host[i - 1] : 0;
        host[i] = base + uint32_t(r.zigzag(reference >= 0 ? codec::kPredictedHostOrder
                                                          : codec::host_order(triangle_count)));
        if (!r.ok) break;
        if (host[i] >= triangle_count || u + v > (1u << codec::kBaryBits) - 1)
            return load_failure(LoadError::out_of_range,
                                "PNTQ: point %u host triangle %u (of %u) or barycentrics invalid",
                                i, host[i], triangle_count);
        if (out) {
            for (uint32_t j = 0; j < n; ++j)
                const_cast<uint32_t*>(out->neighbours)[total + j] = list[j];
            const_cast<float*>(out->bary_u)[i] = float(u) * bary_scale;
            const_cast<float*>(out->bary_v)[i] = float(v) * bary_scale;
            const_cast<float*>(out->radius)[i] =
                q == codec::kRadiusZero
                    ? 0.0f
                    : radius_max * std::exp2(-float(q) / codec::kRadiusStepsPerOctave);
            const_cast<uint32_t*>(out->neighbour_offsets)[i + 1] = total + n;
        }
        total += n;
    }
    if (!r.ok) return load_failure(LoadError::out_of_range, "PNTQ: stream ends early");
    *neighbour_total = total;
    return {};
}

}  // namespace

Status parse_point_stream(Reader r, uint32_t triangle_count, DecodeBudget* budget, Asset* a) {
    uint32_t point_count = r.u32();
    const float* radius_max = r.take<float>(1);
    const uint64_t* bit_count = r.take<uint64_t>(1);
    if (!r.ok || *bit_count > uint64_t(r.size - r.at) * 8)
        return load_failure(LoadError::malformed_section, "PNTQ: header does not fit the section");
    const size_t bytes = size_t((*bit_count + 7) / 8);
    codec::BitReader bits{r.data + r.at, size_t(*bit_count)};
    if (r.at + bytes != r.size)
        return load_failure(LoadError::malformed_section, "PNTQ: %llu bits but %zu bytes follow",
                            static_cast<unsigned long long>(*bit_count), r.size - r.at);
    if (!std::isfinite(*radius_max) || *radius_max < 0.0f)
        return load_failure(LoadError::bad_radius, "PNTQ: radius scale %g not finite and >= 0",
                            double(*radius_max));
    if (point_count == 0) return load_failure(LoadError::zero_count, "PNTQ: no points");
    Status st = check_limit("PNTQ", "point count", point_count, limits::kMaxPoints);
    if (!st.ok()) return st;
    // Every point takes at least kMinPointBits of the stream: check before allocating.
    if (uint64_t(point_count) * kMinPointBits > *bit_count)
        return load_failure(LoadError::count_exceeds_data,
                            "PNTQ: %u points need at least %llu bits, the stream has %llu",
                            point_count,
                            static_cast<unsigned long long>(uint64_t(point_count) * kMinPointBits),
                            static_cast<unsigned long long>(*bit_count));
    st = charge(budget, (uint64_t(point_count) + 1) * 4, "PNTQ");
    if (!st.ok()) return st;
    uint32_t total = 0;
    // Hosts are decoded in the first pass (later hosts are predicted from earlier ones);
    // the second pass fills the other arrays once the neighbour count is known.
    a->point_storage.reset(new (std::nothrow) uint32_t[size_t(point_count) + 1]);
    if (!a->point_storage) return load_failure(LoadError::out_of_memory, "PNTQ: out of memory");
    st = decode_point_stream(bits, point_count, *radius_max, triangle_count, a->point_storage.get(),
                             nullptr, &total);
    if (!st.ok()) return st;
    // host (kept from the first pass), u, v, radius (one word each per point), offsets
    // (P + 1), neighbours.
    const size_t words = size_t(point_count) * 5 + 1 + total;
    st = charge(budget, uint64_t(words) * 4, "PNTQ");
    if (!st.ok()) return st;
    std::unique_ptr<uint32_t[]> storage(new (std::nothrow) uint32_t[words]);
    if (!storage) return load_failure(LoadError::out_of_memory, "PNTQ: out of memory");
    std::memcpy(storage.get(), a->point_storage.get(), size_t(point_count) * 4);
    a->point_storage = std::move(storage);
    uint32_t* w = a->point_storage.get();
    PointsView& p = a->points;
    p.point_count = point_count;
    p.host_triangle = w;
    p.bary_u = reinterpret_cast<const float*>(w + point_count);
    p.bary_v = reinterpret_cast<const float*>(w + size_t(point_count) * 2);
    p.radius = reinterpret_cast<const float*>(w + size_t(point_count) * 3);
    p.neighbour_offsets = w + size_t(point_count) * 4;
    p.neighbours = w + size_t(point_count) * 5 + 1;
    p.neighbour_count = total;
    w[size_t(point_count) * 4] = 0;
    // The same bytes passed the first pass, so this one cannot fail; its status is returned
    // all the same rather than assumed.
    return decode_point_stream(bits, point_count, *radius_max, triangle_count, w, &p, &total);
}

}  // namespace stipple::detail
