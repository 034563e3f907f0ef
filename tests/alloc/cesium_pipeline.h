// The allocation tests' common set-up: CesiumMan baked at some point count, loaded, a headless
// context and a pipeline initialised on it, so each test starts counting from a ready frame.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"

namespace stipple::test {

struct CesiumPipeline {
    Asset asset;
    HeadlessGl gl;
    std::unique_ptr<Pipeline> pipeline = std::make_unique<Pipeline>();
};

// Loads CesiumMan baked with `bake_options` ("--points N") into out->asset and opens the
// context. A failure says which step failed.
inline ::testing::AssertionResult open_cesium(const std::string& bake_options,
                                              CesiumPipeline* out) {
    std::string error;
    if (!load_baked(baked_asset("assets/CesiumMan/CesiumMan.glb", bake_options), &out->asset,
                    &error))
        return ::testing::AssertionFailure() << "load: " << error;
    if (!out->gl.open(&error)) return ::testing::AssertionFailure() << "context: " << error;
    return ::testing::AssertionSuccess();
}

// The same, then out->pipeline initialised with `config`.
inline ::testing::AssertionResult open_cesium(const std::string& bake_options,
                                              const FrameConfig& config, CesiumPipeline* out) {
    const ::testing::AssertionResult opened = open_cesium(bake_options, out);
    if (!opened) return opened;
    const Status init = pipeline_init(out->pipeline.get(), out->asset, out->gl.gl(), config);
    if (!init.ok()) return ::testing::AssertionFailure() << "pipeline_init: " << init.message;
    return ::testing::AssertionSuccess();
}

}  // namespace stipple::test
