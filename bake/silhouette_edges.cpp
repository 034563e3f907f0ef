#include "bake/silhouette_edges.h"

#include <algorithm>

#include "bake/position_weld.h"

namespace stipple::bake {

std::vector<uint32_t> silhouette_edges(const RawScene& scene) {
    // Same position = same vertex for connectivity.
    const std::vector<uint32_t> welded = weld_by_position(scene);
    struct Half {
        uint32_t lo, hi, face, a, b;
    };
    std::vector<Half> halves;
    halves.reserve(scene.indices.size());
    for (uint32_t t = 0; t < scene.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            uint32_t a = scene.indices[size_t(t) * 3 + size_t(k)];
            uint32_t b = scene.indices[size_t(t) * 3 + size_t((k + 1) % 3)];
            uint32_t wa = welded[a], wb = welded[b];
            if (wa == wb) continue;  // degenerate edge
            halves.push_back({std::min(wa, wb), std::max(wa, wb), t, a, b});
        }
    }
    std::stable_sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
        return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
    });
    std::vector<uint32_t> edges;
    for (size_t i = 0; i < halves.size();) {
        size_t j = i + 1;
        while (j < halves.size() && halves[j].lo == halves[i].lo && halves[j].hi == halves[i].hi)
            ++j;
        const Half& h = halves[i];
        uint32_t second = j - i >= 2 ? halves[i + 1].face : format::kNoFace;
        if (second != h.face) edges.insert(edges.end(), {h.a, h.b, h.face, second});
        i = j;
    }
    return edges;
}

}  // namespace stipple::bake
