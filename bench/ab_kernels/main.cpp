// bench/ab_kernels: the two trees' kernels on one frame's lists (build.sh says how).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "ab.h"
#include "bench/ab_common.h"
#include "runtime/frame_pipeline.h"
using Clock = std::chrono::steady_clock;
namespace {

// Each tree's output arrays, so the two never read each other's results.
struct Outputs {
    std::vector<float> positions, normals, radius, size;
    explicit Outputs(uint32_t n) : positions(n * 3 + 4), normals(n * 3 + 4), radius(n), size(n) {}
    AbState on(AbState s) {
        s.positions = positions.data();
        s.normals = normals.data();
        s.radius = radius.data();
        s.size = size.data();
        return s;
    }
};

// The state of one frame (t = 0.4 s of clip 0, 1280x720) the kernels read.
AbState frame_state(const stipple::Asset& asset, const stipple::Pipeline& p) {
    AbState s{};
    s.points = &asset.points;
    s.params = &p.size_params;
    s.indices = asset.mesh.indices;
    s.hosts = p.point_hosts.get();
    s.pairs = p.vertex_pairs.get();
    s.quads = p.neighbour_quads.get();
    s.scale = p.radius_scale.get();
    s.fallback = p.rest_radius.get();
    s.run = p.clusters.run.get();
    s.run_count = p.clusters.run_count;
    s.placed = p.clusters.placed.get();
    s.placed_count = p.clusters.placed_count;
    return s;
}

std::pair<double, double> min_median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return std::make_pair(v[0], v[v.size() / 2]);
}

// Old and new alternately, `reps` each, touching `flush_mb` MB before every run.
void time_both(const AbState& so, const AbState& sn, int reps, int part, size_t flush_mb,
               std::vector<double>* to, std::vector<double>* tn) {
    std::vector<char> junk((flush_mb << 20) + 1);
    char sink = 0;
    for (int r = 0; r < reps; ++r) {
        for (int k = 0; k < 2; ++k) {
            const bool old = (k + r) % 2 == 0;
            for (size_t q = 0; q < junk.size(); q += 64) junk[q] += 1;
            sink += junk[(junk.size() / 2 + r) % junk.size()];
            const Clock::time_point t0 = Clock::now();
            if (old)
                old_stages(so, part);
            else
                new_stages(sn, part);
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            (old ? to : tn)->push_back(ms);
        }
    }
    if (sink == 123) std::puts("");  // keeps the touches
}

void report(const AbState& s, const Outputs& o, const Outputs& n, const std::vector<double>& to,
            const std::vector<double>& tn) {
    const auto a = min_median(to), b = min_median(tn);
    size_t placed_diff = 0, radius_diff = 0, size_diff = 0;
    double max_rel = 0;
    for (uint32_t j = 0; j < s.placed_count; ++j) {
        const uint32_t i = s.placed[j];
        placed_diff += std::memcmp(&o.positions[i * 3], &n.positions[i * 3], 12) != 0 ||
                       std::memcmp(&o.normals[i * 3], &n.normals[i * 3], 12) != 0;
    }
    for (uint32_t j = 0; j < s.run_count; ++j) {
        const uint32_t i = s.run[j];
        radius_diff += o.radius[i] != n.radius[i];
        size_diff += o.size[i] != n.size[i];
        if (o.size[i] > 0)
            max_rel = std::max(max_rel, std::abs(double(o.size[i]) - n.size[i]) / o.size[i]);
    }
    std::printf(
        "run %u placed %u | old %.4f / %.4f ms | new %.4f / %.4f ms | new/old min %.3f median %.3f "
        "| differ: placed %zu radius %zu size %zu (max rel %.2g)\n",
        s.run_count, s.placed_count, a.first, a.second, b.first, b.second, b.first / a.first,
        b.second / a.second, placed_diff, radius_diff, size_diff, max_rel);
}

}  // namespace

int main(int argc, char** argv) {
    stipple::Asset asset;
    if (!stipple::bench::ab_load(argc, argv, "ab FILE.stip [REPS] [PARTS 1|2|3] [FLUSH_MB]",
                                 &asset))
        return 1;
    const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 200;
    const int part = argc > 3 ? std::atoi(argv[3]) : 3;
    const size_t flush_mb = argc > 4 ? size_t(std::max(0, std::atoi(argv[4]))) : 0;
    stipple::bench::HeadlessGl context;
    if (!stipple::bench::ab_context(&context)) return 1;
    const stipple::FrameConfig config = stipple::bench::ab_config();
    auto p = std::make_unique<stipple::Pipeline>();
    if (!stipple::pipeline_init(p.get(), asset, context.gl, config).ok()) return 1;
    stipple::AnimationState state;
    state.clip = 0;
    state.time = 0.4f;
    stipple::pipeline_update(p.get(), state, nullptr);
    const AbState s = frame_state(asset, *p);
    Outputs o(asset.points.point_count), n(asset.points.point_count);
    const AbState so = o.on(s), sn = n.on(s);
    old_stages(so, 1);  // relevance + size alone (PARTS 2) read placed points
    new_stages(sn, 1);
    std::vector<double> to, tn;
    time_both(so, sn, reps, part, flush_mb, &to, &tn);
    report(s, o, n, to, tn);
}
