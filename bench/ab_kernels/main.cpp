// bench/ab_kernels: the two trees' kernels on one frame's lists (build.sh says how).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "ab.h"
#include "bench/bench_setup.h"
#include "runtime/frame_pipeline.h"
using Clock = std::chrono::steady_clock;
int main(int argc, char** argv) {
    stipple::Asset asset;
    if (!stipple::load_asset_file(argv[1], &asset).ok()) return 1;
    int reps = argc > 2 ? atoi(argv[2]) : 200;
    int part = argc > 3 ? atoi(argv[3]) : 3;
    size_t flush_mb = argc > 4 ? atoi(argv[4]) : 0;
    std::vector<char> junk((flush_mb << 20) + 1);
    char sink = 0;
    stipple::platform::HeadlessConfig hc;
    hc.width = 1280;
    hc.height = 720;
    stipple::bench::HeadlessGl context;
    if (!stipple::bench::headless_gl(&context, hc)) return 1;
    const stipple::GlApi& gl = context.gl;
    stipple::FrameConfig config;
    config.width = 1280;
    config.height = 720;
    config.relevance_update = true;
    auto p = std::make_unique<stipple::Pipeline>();
    if (!stipple::pipeline_init(p.get(), asset, gl, config).ok()) return 1;
    stipple::AnimationState st;
    st.clip = 0;
    st.time = 0.4f;
    stipple::pipeline_update(p.get(), st, nullptr);
    const uint32_t n = asset.points.point_count;
    std::vector<float> pos_o(n * 3 + 4), nrm_o(n * 3 + 4), rad_o(n), size_o(n), pos_n(n * 3 + 4),
        nrm_n(n * 3 + 4), rad_n(n), size_n(n);
    AbState s{};
    s.points = &asset.points;
    s.params = &p->size_params;
    s.indices = asset.mesh.indices;
    s.hosts = p->point_hosts.get();
    s.pairs = p->vertex_pairs.get();
    s.quads = p->neighbour_quads.get();
    s.scale = p->radius_scale.get();
    s.fallback = p->rest_radius.get();
    s.run = p->clusters.run.get();
    s.run_count = p->clusters.run_count;
    s.placed = p->clusters.placed.get();
    s.placed_count = p->clusters.placed_count;
    AbState so = s, sn = s;
    so.positions = pos_o.data();
    so.normals = nrm_o.data();
    so.radius = rad_o.data();
    so.size = size_o.data();
    sn.positions = pos_n.data();
    sn.normals = nrm_n.data();
    sn.radius = rad_n.data();
    sn.size = size_n.data();
    old_stages(so, 1);
    new_stages(sn, 1);
    std::vector<double> to, tn;
    for (int r = 0; r < reps; ++r) {
        for (int k = 0; k < 2; ++k) {
            const bool old = (k + r) % 2 == 0;
            for (size_t q = 0; q < junk.size(); q += 64) junk[q] += 1;
            sink += junk[(junk.size() / 2 + r) % (junk.size() + 1)];
            auto t0 = Clock::now();
            if (old)
                old_stages(so, part);
            else
                new_stages(sn, part);
            double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            (old ? to : tn).push_back(ms);
        }
    }
    auto mm = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return std::make_pair(v[0], v[v.size() / 2]);
    };
    auto a = mm(to), b = mm(tn);
    size_t pos_diff = 0, rad_diff = 0, size_diff = 0;
    double max_rel = 0;
    for (uint32_t j = 0; j < s.placed_count; ++j) {
        uint32_t i = s.placed[j];
        pos_diff += memcmp(&pos_o[i * 3], &pos_n[i * 3], 12) != 0 ||
                    memcmp(&nrm_o[i * 3], &nrm_n[i * 3], 12) != 0;
    }
    for (uint32_t j = 0; j < s.run_count; ++j) {
        uint32_t i = s.run[j];
        rad_diff += rad_o[i] != rad_n[i];
        size_diff += size_o[i] != size_n[i];
        if (size_o[i] > 0)
            max_rel = std::max(max_rel, std::abs(double(size_o[i]) - size_n[i]) / size_o[i]);
    }
    if (sink == 123) puts("");
    printf(
        "run %u placed %u | old %.4f / %.4f ms | new %.4f / %.4f ms | new/old min %.3f median %.3f "
        "| differ: placed %zu radius %zu size %zu (max rel %.2g)\n",
        s.run_count, s.placed_count, a.first, a.second, b.first, b.second, b.first / a.first,
        b.second / a.second, pos_diff, rad_diff, size_diff, max_rel);
}
