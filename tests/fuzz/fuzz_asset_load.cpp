// libFuzzer target: the .stip loader (runtime/asset.cpp, load_asset_memory) on arbitrary
// bytes. Checksums are rewritten to match (or skipped by STIPPLE_FUZZ_SKIP_CRC), so
// mutations reach the section decoders. docs/fuzzing.md.
#include <cstddef>
#include <cstdint>

#include "runtime/asset.h"
#include "tests/fuzz/fuzz_common.h"

namespace {
volatile uint64_t g_sink;  // keeps the walk below from being optimised away
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<uint8_t> bytes = stipple::fuzz::asset_bytes(data, size);
    stipple::Asset asset;
    // The default decoded-size limit (16 x file + 1 MiB) keeps a load under -rss_limit_mb.
    const stipple::Status st = stipple::load_asset_memory(bytes.data(), bytes.size(), &asset);
    if (!st.ok()) return 0;
    // A loaded asset is safe to read: walk what the views promise.
    uint64_t sum = 0;
    for (uint32_t i = 0; i < asset.points.point_count; ++i) {
        sum += asset.points.host_triangle[i];
        for (uint32_t k = asset.points.neighbour_offsets[i];
             k < asset.points.neighbour_offsets[i + 1]; ++k)
            sum += asset.points.neighbours[k];
    }
    for (uint32_t t = 0; t < asset.mesh.triangle_count * 3; ++t) sum += asset.mesh.indices[t];
    for (uint32_t e = 0; e < asset.edges.edge_count * 4; ++e) sum += asset.edges.edges[e];
    g_sink = sum + uint64_t(stipple::find_clip(asset, "0"));
    return 0;
}
