// A baked asset loaded into a pipeline on this process's headless context and drawn at a
// zoom, tone and yaw into a measured picture (tools/frame_measure.h): the frame checks of tone
// and evenness (tests/frames/test_corpus_frames.cpp, tests/frames/test_tone_small.cpp). 640x480,
// silhouettes off, GL errors checked on every frame.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "runtime/asset.h"
#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"
#include "tools/frame_measure.h"

namespace stipple::test {

// One picture as measured: RGBA top row first, the mesh pass's coverage, the dots it shows
// and the dots it sized but the mesh in front hides (pipeline_hidden_dots).
struct Shot {
    measure::Image image;
    measure::Mask mask;
    std::vector<measure::Dot> dots, hidden;
};

// A baked asset loaded into a pipeline on this process's headless context.
class Stage {
  public:
    // Loads assets/<path> as baked with default options (plus `bake_args`) by the fixture step.
    bool open(const std::string& path, const std::string& bake_args, const char* clip_name,
              std::string* error) {
        if (!headless_.open(error)) return false;
        const std::string baked = test::baked_asset("assets/" + path, bake_args);
        if (baked.empty() || !test::load_baked(baked, &asset_, error)) return false;
        clip_ = asset_.clip_count > 0 ? 0 : -1;
        if (clip_name) clip_ = find_clip(asset_, clip_name);
        FrameConfig config;
        config.width = kWidth;
        config.height = kHeight;
        config.silhouettes = false;
        config.depth_readback = true;
        config.check_gl_errors = true;  // every frame drawn here is also checked for GL errors
        config.frame_clip = clip_;
        pipeline_.reset(new Pipeline());
        const Status init = pipeline_init(pipeline_.get(), asset_, headless_.gl(), config);
        if (!init.ok()) {
            *error = init.message;
            return false;
        }
        rgba_.resize(size_t(kWidth) * kHeight * 4);
        scratch_.resize(size_t(kWidth) * kHeight * 4);
        depth_.resize(size_t(kWidth) * kHeight);
        dots_.resize(pipeline_->point_capacity);
        return true;
    }

    Shot shoot(float zoom, float tone, float time = 0.0f, float yaw = 0.0f) {
        FrameConfig view = pipeline_->config;
        view.zoom = zoom;
        view.constant_tone = tone;
        view.yaw_degrees = yaw;
        const Status set = pipeline_set_view(pipeline_.get(), view);
        EXPECT_TRUE(set.ok()) << set.message;
        pipeline_frame(pipeline_.get(), clip_, time, nullptr);
        renderer_read_color(&pipeline_->renderer, rgba_.data());
        renderer_read_depth(&pipeline_->renderer, scratch_.data(), depth_.data());
        const GlErrorLog& gl_errors = pipeline_gl_errors(*pipeline_);
        EXPECT_EQ(gl_errors.count, 0u)
            << gl_error_name(gl_errors.first_error) << " after the "
            << (gl_errors.first_pass ? gl_errors.first_pass : "?") << " pass";
        Shot s;
        s.image.width = s.mask.width = kWidth;
        s.image.height = s.mask.height = kHeight;
        s.image.rgba.resize(rgba_.size());
        s.mask.inside.resize(depth_.size());
        for (int y = 0; y < kHeight; ++y) {  // GL rows are bottom first
            const size_t from = size_t(kHeight - 1 - y) * kWidth, to = size_t(y) * kWidth;
            std::copy(rgba_.begin() + from * 4, rgba_.begin() + (from + kWidth) * 4,
                      s.image.rgba.begin() + to * 4);
            for (int x = 0; x < kWidth; ++x) s.mask.inside[to + x] = depth_[from + x] < 1.0f;
        }
        const uint32_t n =
            pipeline_visible_dots(*pipeline_, depth_.data(), dots_.data(), uint32_t(dots_.size()));
        s.dots.resize(n);
        for (uint32_t i = 0; i < n; ++i)
            s.dots[i] = {dots_[i].id, dots_[i].x, dots_[i].y, dots_[i].size};
        const uint32_t h =
            pipeline_hidden_dots(*pipeline_, depth_.data(), dots_.data(), uint32_t(dots_.size()));
        s.hidden.resize(h);
        for (uint32_t i = 0; i < h; ++i)
            s.hidden[i] = {dots_[i].id, dots_[i].x, dots_[i].y, dots_[i].size};
        return s;
    }

    const Pipeline& pipeline() const { return *pipeline_; }
    // The last shot's window depth of the mesh pass, bottom row first (renderer_read_depth).
    const std::vector<float>& depth() const { return depth_; }

    ~Stage() {
        if (pipeline_) pipeline_destroy(pipeline_.get());
    }

    static constexpr int kWidth = 640, kHeight = 480;

  private:
    test::HeadlessGl headless_;  // destroyed last: the pipeline's GL objects go first
    Asset asset_;
    int clip_ = -1;
    std::unique_ptr<Pipeline> pipeline_;
    std::vector<uint8_t> rgba_;
    std::vector<float> scratch_, depth_;
    std::vector<VisibleDot> dots_;
};

}  // namespace stipple::test
