// Shared by the benchmarks: bake a repo asset in memory and load it with the runtime loader.
#pragma once
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"

namespace stipple::bench {

// The bytes of assets/<relative> baked to `points` points; false if anything fails.
inline bool bake_bytes(const char* relative, uint32_t points, std::vector<uint8_t>* bytes) {
    bake::RawScene scene;
    if (!bake::import_scene(std::string(STIPPLE_SOURCE_DIR) + "/assets/" + relative, &scene).ok())
        return false;
    bake::HierarchyConfig config;
    config.point_count = points;
    bake::PointHierarchy hierarchy;
    if (!bake::build_point_hierarchy(scene, config, &hierarchy, nullptr).ok()) return false;
    *bytes = bake::encode_asset(scene, hierarchy);
    return true;
}

// assets/<relative> baked to `points` points and loaded; false if anything fails.
inline bool bake_asset(const char* relative, uint32_t points, Asset* out) {
    std::vector<uint8_t> bytes;
    return bake_bytes(relative, points, &bytes) &&
           load_asset_memory(bytes.data(), bytes.size(), out).ok();
}

}  // namespace stipple::bench
