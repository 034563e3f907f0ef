// Shared by the benchmarks: bake a repo asset in memory and load it with the runtime loader.
#pragma once
#include <string>
#include <vector>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"

namespace stipple::bench {

// assets/<relative> baked to `points` points; false if anything fails.
inline bool bake_asset(const char* relative, uint32_t points, Asset* out) {
    bake::RawScene scene;
    if (!bake::import_scene(std::string(STIPPLE_SOURCE_DIR) + "/assets/" + relative, &scene).ok())
        return false;
    bake::HierarchyConfig config;
    config.point_count = points;
    bake::PointHierarchy hierarchy;
    if (!bake::build_point_hierarchy(scene, config, &hierarchy, nullptr).ok()) return false;
    std::vector<uint8_t> bytes = bake::encode_asset(scene, hierarchy);
    return load_asset_memory(bytes.data(), bytes.size(), out).ok();
}

}  // namespace stipple::bench
