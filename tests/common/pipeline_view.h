// A headless stipple pipeline on one baked asset, for the in-process frame checks that draw a
// frame from several camera views and read its colour and depth copies back
// (tests/frames/test_front_faces.cpp, test_occluder_frames.cpp): open, set_view, draw with
// pipeline_frame, read. The pipeline is destroyed before its context.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"

namespace stipple::test {

// A camera: zoom, yaw and pitch in degrees (FrameConfig's fields).
struct CameraView {
    float zoom, yaw_degrees, pitch_degrees;
};

class PipelineView {
  public:
    PipelineView() = default;
    PipelineView(const PipelineView&) = delete;
    PipelineView& operator=(const PipelineView&) = delete;
    ~PipelineView() { pipeline_destroy(pipeline_.get()); }

    // Loads the asset at `asset_path`, opens a context and initialises the pipeline with
    // `config`; false with the reason in *error.
    bool open(const std::string& asset_path, const FrameConfig& config, std::string* error) {
        if (!load_baked(asset_path, &asset_, error) || !gl_.open(error)) return false;
        const Status status = pipeline_init(pipeline_.get(), asset_, gl_.gl(), config);
        if (!status.ok()) *error = status.message;
        return status.ok();
    }

    // A `width` x `height` frame with the depth copy kept (FrameConfig::depth_readback), the
    // rest of the config at its defaults.
    bool open(const std::string& asset_path, int width, int height, std::string* error) {
        FrameConfig config;
        config.width = width;
        config.height = height;
        config.depth_readback = true;
        return open(asset_path, config, error);
    }

    // The pipeline's config with `view`'s camera.
    bool set_view(const CameraView& view) {
        FrameConfig c = pipeline_->config;
        c.zoom = view.zoom;
        c.yaw_degrees = view.yaw_degrees;
        c.pitch_degrees = view.pitch_degrees;
        return pipeline_set_view(pipeline_.get(), c).ok();
    }

    // The last frame's colour (RGBA8) and depth copy (FrameConfig::depth_readback).
    std::vector<uint8_t> read_colour() {
        std::vector<uint8_t> colour(pixels() * 4);
        renderer_read_color(&pipeline_->renderer, colour.data());
        return colour;
    }
    std::vector<float> read_depth() {
        std::vector<float> depth(pixels()), scratch(pixels() * 4);
        renderer_read_depth(&pipeline_->renderer, scratch.data(), depth.data());
        return depth;
    }

    Pipeline* pipeline() { return pipeline_.get(); }
    const Asset& asset() const { return asset_; }

  private:
    size_t pixels() const {
        return size_t(pipeline_->config.width) * size_t(pipeline_->config.height);
    }

    Asset asset_;
    HeadlessGl gl_;
    std::unique_ptr<Pipeline> pipeline_ = std::make_unique<Pipeline>();
};

}  // namespace stipple::test
