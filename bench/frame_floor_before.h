// bench_frame_floor's "before" variant, for the draw against its floor (docs/measurements-
// after.md): the frame as pipeline_frame drew it before the mesh pass went ahead of the point
// stages and the clear was narrowed to what the last frame drew (runtime/frame_pipeline.cpp,
// runtime/renderer_dirty.cpp): every CPU stage (pipeline_update), then a full clear, the mesh
// pass, lines, dots and glFinish. Same GL commands, same picture; measured in the same run,
// interleaved with the others.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "runtime/frame_pipeline.h"

namespace frame_floor {

struct Before {
    std::vector<double> frame_ms, frame_cpu, draw_ms;  // per round
};

// One frame drawn the previous way; returns the ms of its draw (after pipeline_update).
inline double frame_before(stipple::Pipeline* p, int clip, float time) {
    stipple::AnimationState state;
    state.clip = clip;
    state.time = time;
    stipple::pipeline_update(p, state, nullptr);
    const auto start = std::chrono::steady_clock::now();
    stipple::renderer_mark_dirty(&p->renderer);  // the full clear
    stipple::renderer_draw_fill(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                p->vertex_normals.get(), p->asset->mesh.vertex_count);
    stipple::renderer_draw_line_sets(&p->renderer, p->view_projection, p->lines.get(),
                                     p->lines_drawn, p->style.crease_lines.get(),
                                     p->style.creases_drawn);
    stipple::renderer_draw_dots(&p->renderer, p->view_projection, p->draw_positions.get(),
                                p->draw_sizes.get(), nullptr, p->points_drawn);
    p->renderer.gl.Finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

inline double min_of(std::vector<double> v) {
    return *std::min_element(v.begin(), v.end());
}
inline double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// One row: the frame before and now, the floor, the ratios, the draw stage before and now
// (ms per frame, min / median over rounds; the draw stage's median), process CPU (min).
inline void report_before(const char* name, const Before& b, const std::vector<double>& frame_ms,
                          const std::vector<double>& frame_cpu, const std::vector<double>& floor_ms,
                          double draw_now_median) {
    std::printf(
        "| %s | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f | "
        "%.2f | %.2f | %.2f |\n",
        name, min_of(b.frame_ms), median_of(b.frame_ms), min_of(frame_ms), median_of(frame_ms),
        min_of(floor_ms), median_of(floor_ms), min_of(b.frame_ms) / min_of(floor_ms),
        median_of(b.frame_ms) / median_of(floor_ms), min_of(frame_ms) / min_of(floor_ms),
        median_of(frame_ms) / median_of(floor_ms), median_of(b.draw_ms), draw_now_median,
        min_of(b.frame_cpu), min_of(frame_cpu));
}

inline void report_before_header() {
    std::printf(
        "\nBefore and after (this run): the frame drawn the previous way (all CPU stages, then a "
        "full\nclear and the passes) and now (the mesh pass ahead of the point stages, the "
        "clear narrowed);\nms per frame, min / median over rounds; draw stage median; process "
        "CPU min:\n\n| asset | frame before | frame now | floor | before / floor (min, median) "
        "| now / floor (min, median) | draw before | draw now | CPU before | CPU now |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
}

}  // namespace frame_floor
