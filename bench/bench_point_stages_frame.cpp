// The CPU point stages as a frame runs them (issue 9, "What it must show"): pipeline_update
// (pose, level-of-detail selection, place, relevance, refinement, size, silhouettes; no draw)
// at 1280x720 on assets given on the command line, each on 1 and on 2 threads, in interleaved
// rounds (min and median over rounds of the ms per frame, each round kFrames frames of the
// clip at 30 fps). Beside each, the memory-bandwidth bound of the bytes the point stages touch
// (place: the placed points, relevance and size: the run points; runtime/point_clusters.h),
// from a memcpy measured in the same rounds, and the ns per run point. Last, the same stages
// over every point in stored order (level of detail off): what they reach with no scatter.
//   stipple_bench_point_stages_frame [--rounds N] [--yaw DEG] NAME=FILE.stip[:CLIP] ...
// Without assets it bakes CesiumMan at 100k points in memory. The thread counts of one asset
// share one asset and run the same frames; their stages are byte-identical (point_stages.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_asset.h"
#include "platform/headless_context.h"
#include "runtime/double_sided.h"
#include "runtime/frame_pipeline.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kFrames = 30;

struct Series {
    std::vector<double> v;
    double min() const { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
    double max() const { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
    double median() const {
        if (v.empty()) return 0.0;
        std::vector<double> s = v;
        std::sort(s.begin(), s.end());
        return s.size() % 2 ? s[s.size() / 2] : 0.5 * (s[s.size() / 2 - 1] + s[s.size() / 2]);
    }
};

enum Column {
    kPose,
    kSelect,
    kPlace,
    kRelevance,
    kRefine,
    kSize,
    kLines,
    kStages,
    kStagesSelect,
    kPoints,
    kUpdate,
    kColumns
};
// "place+rel+size": the CPU stages (place, relevance, size), without the level of
// detail's selection and the run-time refinement; "+select" with the selection.
const char* kColumnNames[kColumns] = {
    "pose",         "select",     "place",          "relevance", "refine",
    "size+compact", "silhouette", "place+rel+size", "+select",   "points (place..size)",
    "update"};

struct Run {
    std::unique_ptr<stipple::Pipeline> pipeline;
    int threads = 1;
    Series ms[kColumns];
    Series ns_per_run_point;                               // kPoints per run point
    Series warm, warm_place, warm_relevance_size;          // warm_frames: ms per frame
    double run = 0, placed = 0, neighbours = 0, dots = 0;  // per frame, last round
    double worker_ranges =
        0;  // per frame, over every round: ranges the worker (not the caller) ran
};

struct Case {
    std::string name, file, clip_name;
    stipple::Asset asset;
    int clip = 0;
    Run runs[2];         // 1 and 2 threads
    Run full;            // level of detail off (1 thread): the check, and the stored order's time
    int differing = -1;  // frames whose drawn dots differ from `full`
    double line_bytes = 0;  // per frame (check_frames): the 64-byte lines the stages touch
};

bool parse_case(const char* arg, Case* c) {
    const char* eq = std::strchr(arg, '=');
    if (!eq) return false;
    c->name.assign(arg, eq);
    c->file = eq + 1;
    const size_t colon = c->file.rfind(':');
    if (colon != std::string::npos && c->file.find(".stip", colon) == std::string::npos) {
        c->clip_name = c->file.substr(colon + 1);
        c->file.resize(colon);
    }
    return stipple::load_asset_file(c->file.c_str(), &c->asset).ok();
}

bool init_runs(Case* c, const stipple::GlApi& gl, float yaw) {
    c->clip = std::max(0, stipple::find_clip(c->asset, c->clip_name.c_str()));
    for (int k = 0; k < 2; ++k) {
        stipple::FrameConfig config;
        config.width = 1280;
        config.height = 720;
        config.relevance_update = true;
        config.yaw_degrees = yaw;
        config.threads = k == 1 ? 2 : 1;
        Run& r = c->runs[k];
        r.threads = config.threads;
        r.pipeline = std::make_unique<stipple::Pipeline>();
        if (!stipple::pipeline_init(r.pipeline.get(), c->asset, gl, config).ok()) return false;
        if (k > 0) continue;
        config.lod = false;
        c->full.pipeline = std::make_unique<stipple::Pipeline>();
        if (!stipple::pipeline_init(c->full.pipeline.get(), c->asset, gl, config).ok())
            return false;
    }
    return true;
}

bool same_dots(const stipple::Pipeline& a, const stipple::Pipeline& b) {
    const size_t n = a.points_drawn;
    return n == b.points_drawn &&
           std::memcmp(a.draw_positions.get(), b.draw_positions.get(), n * 12) == 0 &&
           std::memcmp(a.draw_sizes.get(), b.draw_sizes.get(), n * 4) == 0;
}

// The 64-byte lines elements ids[0 .. n) (ascending) of `size` bytes each occupy in an array
// taken to start on a line (runtime/memory.h aligns buffers to 16 bytes: a line's worth of
// error per run of elements at most).
double lines_of(const uint32_t* ids, uint32_t n, uint32_t size) {
    double lines = 0;
    uint64_t last = ~uint64_t(0);
    for (uint32_t j = 0; j < n; ++j) {
        const uint64_t first = uint64_t(ids[j]) * size / 64;
        const uint64_t end = (uint64_t(ids[j]) * size + size - 1) / 64 + 1;  // past the last
        lines += double(end - (first == last ? first + 1 : first));
        last = end - 1;
    }
    return lines;
}

// What the stages of stage_bytes move at the granularity of the memory system: each array's
// distinct 64-byte lines that hold an element they read or write, a written line counted
// twice (its read for ownership and its write-back), as if nothing stayed cached from the last
// frame. Scattered records share lines with points not run, so this is more than the bytes.
double frame_line_bytes(const stipple::Pipeline& p) {
    const stipple::PointClusters& c = p.clusters;
    const bool lod = p.config.lod && c.cluster_count > 0;
    if (!lod || !p.point_hosts || !p.neighbour_quads) return 0;
    const uint32_t *placed = c.placed.get(), *run = c.run.get();
    const uint32_t np = c.placed_count, nr = c.run_count;
    double lines = lines_of(placed, np, 16)            // host records, read
                   + 2 * lines_of(placed, np, 12) * 2  // positions and normals, written
                   + lines_of(run, nr, 16)             // neighbour records
                   + lines_of(run, nr, 4)              // scale
                   + 2 * lines_of(run, nr, 4) * 2;     // radius and size, written
    if (p.vertex_pairs) {
        const double v = p.asset->mesh.vertex_count;
        lines += std::ceil(v * 24 / 64) + 2 * std::ceil(v * 32 / 64);  // posed in, pairs out
    }
    return lines * 64;
}

// The frames of a round with level of detail on (1 thread) against the full stages: the
// drawn dots (positions, sizes, order) must be the same bytes (docs/lod.md).
void check_frames(Case* c) {
    c->differing = 0;
    c->line_bytes = 0;
    for (int k = 0; k < kFrames; ++k) {
        stipple::AnimationState state;
        state.clip = c->clip;
        state.time = float(k) / 30.0f;
        stipple::pipeline_update(c->runs[0].pipeline.get(), state, nullptr);
        stipple::pipeline_update(c->full.pipeline.get(), state, nullptr);
        c->differing += !same_dots(*c->runs[0].pipeline, *c->full.pipeline);
        c->line_bytes += frame_line_bytes(*c->runs[0].pipeline) / kFrames;
    }
}

// Relevant neighbours of the points relevance runs on (it reads each one's position).
double run_neighbours(const stipple::Pipeline& p) {
    const stipple::PointsView& pts = p.asset->points;
    const stipple::PointClusters& c = p.clusters;
    if (!p.config.lod || c.cluster_count == 0) return double(pts.neighbour_count);
    double n = 0;
    for (uint32_t j = 0; j < c.run_count; ++j)
        n += pts.neighbour_offsets[c.run[j] + 1] - pts.neighbour_offsets[c.run[j]];
    return n;
}

// The frame's place, relevance and size again, twice, on the lists and pose the frame just
// used; the second time: what the kernels cost when their bytes are already in the caches
// (the vertex pass, place and the facing of double-sided points, relevance + size; not the
// compaction). Against the bound, the part of the gap no layout can close. The sizes it
// leaves lack the refinement's fade; the next frame rewrites every size it reads.
struct WarmMs {
    double place = 0, relevance_size = 0;  // place: with the vertex pass and the facing
};
WarmMs warm_stages(stipple::Pipeline* p) {
    const stipple::PointClusters& c = p->clusters;
    const stipple::PointStageFrame f = stipple::point_stage_frame(p);
    WarmMs ms;
    for (int rep = 0; rep < 2; ++rep) {
        const Clock::time_point t0 = Clock::now();
        stipple::point_stage_pair_vertices(p);
        stipple::point_stage_place(&p->pool, f, c.placed.get(), c.placed_count);
        stipple::face_listed_double_sided_points(c.run.get(), c.run_count,
                                                 p->point_double_sided.get(), f.positions,
                                                 f.normals, p->size_params.eye);
        const Clock::time_point t1 = Clock::now();
        if (!stipple::point_stage_relevance_size(&p->pool, f, c.run.get(), c.run_count)) {
            stipple::point_stage_relevance(&p->pool, f, c.run.get(), c.run_count);
            stipple::point_stage_size(&p->pool, f, c.run.get(), c.run_count);
        }
        ms.place = std::chrono::duration<double, std::milli>(t1 - t0).count();
        ms.relevance_size = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    }
    return ms;
}

// The frames of run_frames on 1 thread with level of detail, each followed by warm_stages:
// their own pass of a round, so the warm caches they leave bias no frame timed above.
void warm_frames(Case* c) {
    Run* r = &c->runs[0];
    stipple::Pipeline* p = r->pipeline.get();
    if (!p->config.lod || p->clusters.cluster_count == 0 || !p->config.relevance_update) return;
    WarmMs sum;
    for (int k = 0; k < kFrames; ++k) {
        stipple::AnimationState state;
        state.clip = c->clip;
        state.time = float(k) / 30.0f;
        stipple::pipeline_update(p, state, nullptr);
        const WarmMs ms = warm_stages(p);
        sum.place += ms.place;
        sum.relevance_size += ms.relevance_size;
    }
    r->warm_place.v.push_back(sum.place / kFrames);
    r->warm_relevance_size.v.push_back(sum.relevance_size / kFrames);
    r->warm.v.push_back((sum.place + sum.relevance_size) / kFrames);
}

void run_frames(Case* c, Run* r) {
    stipple::Pipeline* p = r->pipeline.get();
    stipple::StageTimes t;
    double run = 0, placed = 0, neighbours = 0, dots = 0;
    const uint64_t ranges = stipple::thread_pool_worker_ranges(&p->pool);
    const Clock::time_point start = Clock::now();
    for (int k = 0; k < kFrames; ++k) {
        stipple::AnimationState state;
        state.clip = c->clip;
        state.time = float(k) / 30.0f;
        stipple::pipeline_update(p, state, &t);
        const bool lod = p->config.lod && p->clusters.cluster_count > 0;
        run += lod ? p->clusters.run_count : p->asset->points.point_count;
        placed += lod ? p->clusters.placed_count : p->asset->points.point_count;
        neighbours += run_neighbours(*p);
        dots += p->points_drawn;
    }
    const double update = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const double f = 1.0 / kFrames;
    r->worker_ranges += double(stipple::thread_pool_worker_ranges(&p->pool) - ranges) * f;
    const double cols[kColumns] = {(t.sample + t.skin) * f,
                                   t.select * f,
                                   t.place * f,
                                   t.relevance * f,
                                   t.refine * f,
                                   t.size * f,
                                   t.silhouette * f,
                                   (t.place + t.relevance + t.size) * f,
                                   (t.select + t.place + t.relevance + t.size) * f,
                                   (t.select + t.place + t.relevance + t.refine + t.size) * f,
                                   update * f};
    for (int k = 0; k < kColumns; ++k) r->ms[k].v.push_back(cols[k]);
    r->run = run * f, r->placed = placed * f, r->neighbours = neighbours * f, r->dots = dots * f;
    r->ns_per_run_point.v.push_back(cols[kStages] * 1e6 / std::max(r->run, 1.0));
}

// Bytes the point stages stream per frame, in the layout the pipeline reads: place reads each
// placed point's host (its 16-byte record, runtime/point_simd.h's point_hosts, else host, u,
// v) and writes its position and normal; relevance reads each run point's neighbour record (16
// bytes with quad_neighbours, else an offset, the indices counted per neighbour), scale and
// position, each neighbour's position, and writes the radius; size reads position, normal and
// radius, writes the size. Fused (runtime/point_stages.h's point_stage_relevance_size, the
// AVX2 path) size reads only the normal: the position and radius are already in registers.
// With `pairs`, also what place's time holds before its points: pair_vertices reads each
// posed vertex (position, normal) and writes its 32-byte pair (the horse's 48k vertices: 2.7
// MB); the pairs place then gathers are not counted again.
double stage_bytes(const Run& r, bool pairs) {
    const stipple::Pipeline& p = *r.pipeline;
    const double host = p.point_hosts ? 16 : 12;
    const double record = p.neighbour_quads ? 16 : 4, index = p.neighbour_quads ? 0 : 4;
    const bool fused = stipple::has_avx2(stipple::point_simd());
    const double vertices = p.vertex_pairs && pairs ? p.asset->mesh.vertex_count : 0;
    return r.placed * (host + 24) + r.run * (record + 4 + 12 + 4) + r.neighbours * (index + 12) +
           r.run * (fused ? 12 + 4 : 12 + 12 + 4 + 4) + vertices * (24 + 32);
}

// memcpy bandwidth (read + write bytes per ns) over `bytes`, best of 5 copies.
double bandwidth(std::vector<char>* src, std::vector<char>* dst) {
    double best = 0;
    for (int k = 0; k < 5; ++k) {
        const Clock::time_point t0 = Clock::now();
        std::memcpy(dst->data(), src->data(), src->size());
        const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
        best = std::max(best, 2.0 * double(src->size()) / ns);
        std::swap(*src, *dst);
    }
    return best;
}

// The ms `bytes` take at `bandwidth` bytes per ns.
double ms_at(double bytes, double bandwidth) {
    return bytes / bandwidth * 1e-6;
}

// Per round: the stages' ms over the bound from that round's memcpy (the machine's bandwidth
// moves between rounds; a ratio of two bests taken at different times can mix a quiet memcpy
// with a busy frame).
Series round_ratios(const Series& ms, const Series& bw, double bytes) {
    Series r;
    for (size_t k = 0; k < ms.v.size() && k < bw.v.size(); ++k)
        r.v.push_back(ms.v[k] / ms_at(bytes, bw.v[k]));
    return r;
}

std::string mm(const Series& s) {
    char text[48];
    std::snprintf(text, sizeof(text), "%.3f / %.3f", s.min(), s.median());
    return text;
}

void print_stages(const std::vector<Case>& cases) {
    std::printf("| asset | threads |");
    for (const char* name : kColumnNames) std::printf(" %s |", name);
    std::printf(" points run (placed) | dots |\n| --- | ---: |");
    for (int k = 0; k < kColumns; ++k) std::printf(" ---: |");
    std::printf(" ---: | ---: |\n");
    for (const Case& c : cases)
        for (const Run& r : c.runs) {
            std::printf("| %s | %d |", c.name.c_str(), r.threads);
            for (const Series& s : r.ms) std::printf(" %s |", mm(s).c_str());
            std::printf(" %.0f (%.0f) | %.0f |\n", r.run, r.placed, r.dots);
        }
}

void print_bounds(const std::vector<Case>& cases, const Series& bw) {
    std::printf(
        "\nmemcpy: best %.2f, median %.2f GB/s (read + write). CPU stages (place, relevance, "
        "size; not the selection, not the refinement) against the bound of the bytes they "
        "stream (the vertex pass place's time holds included; \"points only\" leaves its bytes "
        "out, as this bench did before), per run point; and with the selection (its cluster and "
        "triangle passes, whose bytes the bound does not count); last, the bound of the 64-byte "
        "lines those bytes lie on (each array's distinct lines, written ones twice: read for "
        "ownership and write-back), what the memory system moves if nothing stays cached:\n\n",
        bw.max(), bw.median());
    std::printf(
        "| asset | bytes per frame | bound ms | 1 thread ms (min / median) | 1T / bound | "
        "1T / bound, points only | ns per run point 1T | bound ns per run point | 2 threads ms | "
        "1T / 2T (min, median) | "
        "with select 1T ms | with select / bound | lines touched | 1T / bound of the lines | "
        "per round: 1T / bound, of the lines (min / median) |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
        "| ---: | ---: |\n");
    for (const Case& c : cases) {
        const Run& one = c.runs[0];
        const Run& two = c.runs[1];
        const double bytes = stage_bytes(one, true), bound_ms = ms_at(bytes, bw.max());
        const double points_ms = ms_at(stage_bytes(one, false), bw.max());
        const Series per_round = round_ratios(one.ms[kStages], bw, bytes);
        const Series per_round_lines = round_ratios(one.ms[kStages], bw, c.line_bytes);
        std::printf(
            "| %s | %.2f MB | %.3f | %s | %.1f | %.1f | %.1f / %.1f | %.1f | %s | %.2f, %.2f | %s "
            "| %.1f | %.2f MB | %.1f | %.1f / %.1f, %.1f / %.1f |\n",
            c.name.c_str(), bytes * 1e-6, bound_ms, mm(one.ms[kStages]).c_str(),
            one.ms[kStages].min() / bound_ms, one.ms[kStages].min() / points_ms,
            one.ns_per_run_point.min(), one.ns_per_run_point.median(),
            bytes / bw.max() / std::max(one.run, 1.0), mm(two.ms[kStages]).c_str(),
            one.ms[kStages].min() / two.ms[kStages].min(),
            one.ms[kStages].median() / two.ms[kStages].median(), mm(one.ms[kStagesSelect]).c_str(),
            one.ms[kStagesSelect].min() / bound_ms, c.line_bytes * 1e-6,
            one.ms[kStages].min() / ms_at(c.line_bytes, bw.max()), per_round.min(),
            per_round.median(), per_round_lines.min(), per_round_lines.median());
    }
}

// The same stages over every point in the stored order (level of detail off, 1 thread): each
// array a stream from first point to last, only the neighbours' positions gathered, no point
// sharing a line with one not run. What the kernels reach when the layout wastes nothing: the
// lower limit of what a cluster-major order (the level of detail's run points contiguous)
// could give the frame's stages above.
void print_stored_order(const std::vector<Case>& cases, const Series& bw) {
    std::printf(
        "\nEvery point in stored order (level of detail off, 1 thread; the arrays streamed, the "
        "neighbours' positions gathered):\n\n"
        "| asset | points | bytes per frame | bound ms | ms (min / median) | / bound | "
        "ns per point | per round: / bound (min / median) |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) {
        const Run& r = c.full;
        const double bytes = stage_bytes(r, true), bound_ms = ms_at(bytes, bw.max());
        const Series per_round = round_ratios(r.ms[kStages], bw, bytes);
        std::printf("| %s | %.0f | %.2f MB | %.3f | %s | %.1f | %.1f | %.1f / %.1f |\n",
                    c.name.c_str(), r.run, bytes * 1e-6, bound_ms, mm(r.ms[kStages]).c_str(),
                    r.ms[kStages].min() / bound_ms, r.ns_per_run_point.min(), per_round.min(),
                    per_round.median());
    }
}

// warm_frames against the same bound: the kernels' own cost with no byte waiting on memory.
// Above 2x, no layout or prefetch takes the frame's stages to 2x: that needs fewer operations.
void print_warm(const std::vector<Case>& cases, const Series& bw) {
    std::printf(
        "\nThe same stages again on the frame's lists, caches warm (the second of two repeats; "
        "1 thread; without the compaction):\n\n"
        "| asset | frame's stages ms (min / median) | warm ms (min / median) | warm place | "
        "warm relevance + size | frame / warm (min) | warm / bound | per round: warm / bound "
        "(min / median) |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Case& c : cases) {
        const Run& one = c.runs[0];
        if (one.warm.v.empty()) continue;
        const double bytes = stage_bytes(one, true), bound_ms = ms_at(bytes, bw.max());
        const Series per_round = round_ratios(one.warm, bw, bytes);
        std::printf("| %s | %s | %s | %s | %s | %.2f | %.1f | %.1f / %.1f |\n", c.name.c_str(),
                    mm(one.ms[kStages]).c_str(), mm(one.warm).c_str(), mm(one.warm_place).c_str(),
                    mm(one.warm_relevance_size).c_str(), one.ms[kStages].min() / one.warm.min(),
                    one.warm.min() / bound_ms, per_round.min(), per_round.median());
    }
}

void print_ratios(const std::vector<Case>& cases) {
    if (cases.size() < 2) return;
    std::printf("\nAgainst %s (1 thread, min / median):\n\n", cases[0].name.c_str());
    std::printf("| asset | points (place..size) | update |\n| --- | ---: | ---: |\n");
    const Run& base = cases[0].runs[0];
    for (size_t k = 1; k < cases.size(); ++k) {
        const Run& r = cases[k].runs[0];
        std::printf("| %s | %.2f / %.2f | %.2f / %.2f |\n", cases[k].name.c_str(),
                    r.ms[kPoints].min() / base.ms[kPoints].min(),
                    r.ms[kPoints].median() / base.ms[kPoints].median(),
                    r.ms[kUpdate].min() / base.ms[kUpdate].min(),
                    r.ms[kUpdate].median() / base.ms[kUpdate].median());
    }
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 7;
    float yaw = 0.0f;
    std::vector<Case> cases;
    cases.reserve(size_t(argc));
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
            rounds = std::max(1, std::atoi(argv[++i]));
        } else if (std::strcmp(argv[i], "--yaw") == 0 && i + 1 < argc) {
            yaw = float(std::atof(argv[++i]));
        } else {
            cases.emplace_back();
            if (!parse_case(argv[i], &cases.back())) {
                std::fprintf(stderr, "cannot load %s (NAME=FILE.stip[:CLIP])\n", argv[i]);
                return 1;
            }
        }
    }
    if (cases.empty()) {
        cases.emplace_back();
        cases[0].name = "CesiumMan 100k";
        if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", 100000, &cases[0].asset))
            return 1;
    }
    stipple::platform::HeadlessConfig hc;
    hc.width = 1280;
    hc.height = 720;
    stipple::platform::HeadlessContext context;
    stipple::GlApi gl;
    if (!stipple::platform::create_headless_context(hc, &context).ok() ||
        !stipple::load_gl_api(stipple::platform::proc_loader(context), &gl).ok())
        return 1;
    for (Case& c : cases) {
        if (!init_runs(&c, gl, yaw)) return 1;
        check_frames(&c);
    }
    std::vector<char> src(size_t(64) << 20, 1), dst(size_t(64) << 20, 2);
    Series bw;
    for (int round = 0; round < rounds; ++round) {
        bw.v.push_back(bandwidth(&src, &dst));
        for (size_t i = 0; i < cases.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                Case& c = cases[(i + size_t(round)) % cases.size()];
                const int at = (k + round) % 3;
                run_frames(&c, at < 2 ? &c.runs[at] : &c.full);
            }
        for (Case& c : cases) warm_frames(&c);
    }
    std::printf("1280x720, %d interleaved rounds of %d frames, ms per frame (min / median)\n\n",
                rounds, kFrames);
    print_stages(cases);
    print_bounds(cases, bw);
    print_stored_order(cases, bw);
    print_warm(cases, bw);
    print_ratios(cases);
    std::printf(
        "\nRanges the 2nd thread ran per frame (the caller runs those of a worker not "
        "scheduled in time; ~3-4 when it always is):");
    for (const Case& c : cases)
        std::printf(" %s %.2f;", c.name.c_str(),
                    c.runs[1].worker_ranges / double(c.runs[1].ms[0].v.size()));
    std::printf("\nDrawn dots with level of detail against the full stages (%d frames):", kFrames);
    for (const Case& c : cases)
        std::printf(
            " %s %s;", c.name.c_str(),
            c.differing == 0 ? "identical" : (std::to_string(c.differing) + " differ").c_str());
    std::printf("\n");
    for (Case& c : cases) {
        for (Run& r : c.runs) stipple::pipeline_destroy(r.pipeline.get());
        stipple::pipeline_destroy(c.full.pipeline.get());
    }
    return 0;
}
