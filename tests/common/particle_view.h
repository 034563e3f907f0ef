// A headless pipeline drawing one particle style (GI'01, runtime/particle_frame.h) of one
// baked asset, for the particle frame checks (tests/frames/test_particle_frames.cpp,
// test_curvature_frames.cpp): open, draw frames, read the visible strokes and the image.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "runtime/particle_frame.h"
#include "tests/common/fixtures.h"
#include "tools/image_write.h"

namespace stipple {
namespace test {

class ParticleView {
  public:
    static constexpr int kWidth = 320, kHeight = 240;

    // tree_points: the particle tree's size (particle_stage_init; the asset's point count
    // leaves out the temporary particles); list_points: the most listed at once (0: all).
    bool open(const std::string& asset_path, const ParticleStyle& style, float zoom,
              std::string* error, uint32_t tree_points = kDefaultParticleTreePoints,
              uint32_t list_points = 0, int width = kWidth, int height = kHeight) {
        if (!gl_.open(error) || !load_baked(asset_path, &asset_, error)) return false;
        width_ = width;
        height_ = height;
        FrameConfig c;
        c.width = width;
        c.height = height;
        c.zoom = zoom;
        c.depth_readback = true;
        c.check_gl_errors = true;
        particle_style_frame_config(style, &c);
        Status st = pipeline_init(pipeline_.get(), asset_, gl_.gl(), c);
        if (st.ok())
            st = particle_stage_init(stage_.get(), asset_, style, width, height, tree_points,
                                     list_points);
        if (st.ok()) st = particle_stage_init_gl(stage_.get(), gl_.gl());
        if (!st.ok()) *error = st.message;
        return st.ok();
    }
    bool open(const std::string& asset_path, const char* style_name, float zoom, std::string* error,
              uint32_t tree_points = kDefaultParticleTreePoints, uint32_t list_points = 0,
              int width = kWidth, int height = kHeight) {
        const ParticleStyle* style = find_particle_style(style_name);
        if (!style) {
            *error = std::string("no style ") + style_name;
            return false;
        }
        return open(asset_path, *style, zoom, error, tree_points, list_points, width, height);
    }
    ~ParticleView() {
        particle_stage_destroy(stage_.get());
        pipeline_destroy(pipeline_.get());
    }
    // Draws a frame; returns its visible strokes.
    std::vector<VisibleStroke> frame(int clip, float time) {
        AnimationState state;
        state.clip = clip;
        state.time = time;
        pipeline_particle_frame(pipeline_.get(), stage_.get(), state, nullptr);
        rgba_.resize(size_t(width_) * height_ * 4);
        depth_.resize(size_t(width_) * height_);
        scratch_.resize(size_t(width_) * height_ * 4);
        renderer_read_color(&pipeline_->renderer, rgba_.data());
        renderer_read_depth(&pipeline_->renderer, scratch_.data(), depth_.data());
        std::vector<VisibleStroke> v(stage_->stroke_count);
        v.resize(particle_visible_strokes(*pipeline_, *stage_, depth_.data(), v.data(),
                                          uint32_t(v.size())));
        return v;
    }
    size_t object_pixels() const {
        return size_t(
            std::count_if(depth_.begin(), depth_.end(), [](float d) { return d < 1.0f; }));
    }
    void set_view(float yaw, float zoom) {
        FrameConfig v = pipeline_->config;
        v.yaw_degrees = yaw;
        v.zoom = zoom;
        ASSERT_TRUE(pipeline_set_view(pipeline_.get(), v).ok());
    }
    void set_yaw(float yaw) { set_view(yaw, pipeline_->config.zoom); }
    Status enable_visibility_fades() {
        return particle_stage_enable_visibility_fades(stage_.get());
    }
    const std::vector<uint8_t>& rgba() const { return rgba_; }
    const Asset& asset() const { return asset_; }
    const Pipeline& pipeline() const { return *pipeline_; }
    const ParticleStage& stage() const { return *stage_; }
    void save(const char* name) const {  // STIPPLE_PARTICLE_PNG=DIR: to look at them
        if (const char* dir = std::getenv("STIPPLE_PARTICLE_PNG")) {
            std::string e;
            image::write_png((std::string(dir) + "/" + name + ".png").c_str(), width_, height_,
                             rgba_.data(), true, &e);
        }
    }

  private:
    HeadlessGl gl_;
    int width_ = kWidth, height_ = kHeight;
    Asset asset_;
    std::unique_ptr<Pipeline> pipeline_ = std::make_unique<Pipeline>();
    std::unique_ptr<ParticleStage> stage_ = std::make_unique<ParticleStage>();
    std::vector<uint8_t> rgba_;
    std::vector<float> depth_, scratch_;
};

// Pixels whose RGB differ by more than 24 in sum.
inline size_t changed_pixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
        n += std::abs(int(a[i]) - int(b[i])) + std::abs(int(a[i + 1]) - int(b[i + 1])) +
                 std::abs(int(a[i + 2]) - int(b[i + 2])) >
             24;
    return n;
}

}  // namespace test
}  // namespace stipple
