// The CPU point stages over threads and SIMD paths (runtime/point_stages.h,
// runtime/point_simd.h, runtime/thread_pool.h): any thread count and either SIMD path give
// byte-identical positions, normals, radii and sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/point_placement.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"
#include "runtime/stipple.h"
#include "runtime/thread_pool.h"
#include "tests/common/point_frame_fixture.h"

namespace {

using stipple::Pipeline;
using stipple::PointSimd;

// The CPU outputs of a pipeline's last update, point by point, and its compacted dots.
struct Outputs {
    std::vector<float> positions, normals, radius, size, draw_positions, draw_sizes;
    uint32_t points = 0, drawn = 0;
};

Outputs outputs(const Pipeline& p) {
    Outputs o;
    o.points = stipple::pipeline_point_count(p);
    o.drawn = p.points_drawn;
    o.positions.assign(p.point_positions.get(), p.point_positions.get() + size_t(o.points) * 3);
    o.normals.assign(p.point_normals.get(), p.point_normals.get() + size_t(o.points) * 3);
    o.radius.assign(p.radius.get(), p.radius.get() + o.points);
    if (p.config.lod && p.clusters.cluster_count > 0) {      // radii of the run points only: the
        const uint32_t baked = p.asset->points.point_count;  // others are never written
        std::vector<uint8_t> run(baked, 0);
        for (uint32_t j = 0; j < p.clusters.run_count; ++j) run[p.clusters.run[j]] = 1;
        for (uint32_t i = 0; i < baked; ++i)
            if (!run[i]) o.radius[i] = 0.0f;
    }
    o.size.assign(p.size.get(), p.size.get() + o.points);
    o.draw_positions.assign(p.draw_positions.get(), p.draw_positions.get() + size_t(o.drawn) * 3);
    o.draw_sizes.assign(p.draw_sizes.get(), p.draw_sizes.get() + o.drawn);
    return o;
}

using stipple::test::same_bytes;

void expect_identical(const Outputs& a, const Outputs& b, const std::string& what) {
    ASSERT_EQ(a.points, b.points) << what;
    ASSERT_EQ(a.drawn, b.drawn) << what;
    EXPECT_TRUE(same_bytes(a.positions, b.positions)) << what;
    EXPECT_TRUE(same_bytes(a.normals, b.normals)) << what;
    EXPECT_TRUE(same_bytes(a.radius, b.radius)) << what;
    EXPECT_TRUE(same_bytes(a.size, b.size)) << what;
    EXPECT_TRUE(same_bytes(a.draw_positions, b.draw_positions)) << what;
    EXPECT_TRUE(same_bytes(a.draw_sizes, b.draw_sizes)) << what;
}

class PointStagesTest : public stipple::test::Cesium60kFrame {
  protected:
    // Pipelines with 1, 2 and 3 threads over `config`, updated at the same frames.
    void compare_threads(stipple::FrameConfig config, const char* name, uint32_t* most_run) {
        std::unique_ptr<Pipeline> p[3];
        for (int k = 0; k < 3; ++k) {
            config.threads = k + 1;
            p[k] = std::make_unique<Pipeline>();
            const stipple::Status st = stipple::pipeline_init(p[k].get(), asset_, gl_.gl(), config);
            ASSERT_TRUE(st.ok()) << st.message;
            ASSERT_EQ(p[k]->pool.threads, k + 1);
        }
        for (int f = 0; f < 8; ++f) {
            stipple::AnimationState state;
            state.clip = 0;
            state.time = float(f) / 10.0f;
            for (auto& q : p) stipple::pipeline_update(q.get(), state, nullptr);
            const Outputs one = outputs(*p[0]);
            EXPECT_GT(one.drawn, 100u);
            *most_run = std::max(*most_run, config.lod ? p[0]->clusters.stats.points_run
                                                       : asset_.points.point_count);
            most_refined_ = std::max(most_refined_, p[0]->refined_count);
            for (int k = 1; k < 3; ++k)
                expect_identical(one, outputs(*p[k]),
                                 std::string(name) + ", " + std::to_string(k + 1) +
                                     " threads, frame " + std::to_string(f));
        }
        for (auto& q : p) stipple::pipeline_destroy(q.get());
    }

    uint32_t most_refined_ = 0;
};

TEST_F(PointStagesTest, ThreadsGiveByteIdenticalPointsOnTheWalk) {
    for (const bool lod : {true, false}) {
        stipple::FrameConfig config;
        config.lod = lod;
        uint32_t most_run = 0;
        compare_threads(config, lod ? "walk, LOD" : "walk, no LOD", &most_run);
        // The ranges really were split (thread_pool_run runs small counts on one thread).
        EXPECT_GE(most_run, 3 * stipple::kMinPointsPerThread);
    }
}

TEST_F(PointStagesTest, ThreadsGiveByteIdenticalPointsInARefiningCloseUp) {
    stipple::FrameConfig config;
    config.zoom = 6.0f;
    config.constant_tone = 0.6f;
    uint32_t most_run = 0;
    compare_threads(config, "close-up", &most_run);
    EXPECT_GE(most_run, 3 * stipple::kMinPointsPerThread);
    EXPECT_GT(most_refined_, 1000u);  // the run-time refinement's points were compared too
}

// pipeline_frame with a worker runs the point part beside the mesh pass
// (runtime/frame_pipeline.cpp): the same points, dots and pixels as on one thread, the stage
// times still reported.
TEST_F(PointStagesTest, FramesBesideTheMeshPassGiveTheSameBytes) {
    for (const float zoom : {1.0f, 6.0f}) {  // a full view and a refining close-up
        std::unique_ptr<Pipeline> p[2];
        for (int k = 0; k < 2; ++k) {
            stipple::FrameConfig config;
            config.zoom = zoom;
            config.constant_tone = 0.6f;
            config.threads = k + 1;
            p[k] = std::make_unique<Pipeline>();
            ASSERT_TRUE(stipple::pipeline_init(p[k].get(), asset_, gl_.gl(), config).ok());
        }
        const size_t bytes = size_t(p[0]->config.width) * size_t(p[0]->config.height) * 4;
        std::vector<uint8_t> rgba[2] = {std::vector<uint8_t>(bytes), std::vector<uint8_t>(bytes)};
        for (int f = 0; f < 6; ++f) {
            stipple::StageTimes t[2];
            Outputs o[2];
            for (int k = 0; k < 2; ++k) {
                stipple::pipeline_frame(p[k].get(), 0, float(f) / 7.0f, &t[k]);
                o[k] = outputs(*p[k]);
                stipple::renderer_read_color(&p[k]->renderer, rgba[k].data());
            }
            const std::string what =
                "zoom " + std::to_string(zoom) + ", frame " + std::to_string(f);
            EXPECT_GT(o[0].drawn, 100u) << what;
            expect_identical(o[0], o[1], what);
            EXPECT_TRUE(rgba[0] == rgba[1]) << what;
            EXPECT_GT(t[1].place, 0.0) << what;  // timed on the worker, added to the frame's
            EXPECT_GT(t[1].size, 0.0) << what;
        }
        EXPECT_EQ(p[1]->pool.threads, 2);  // lent to the point part and given back
        for (auto& q : p) stipple::pipeline_destroy(q.get());
    }
}

TEST_F(PointStagesTest, ThreadsGiveByteIdenticalPointsOnBothSimdPaths) {
    stipple::point_simd_force(stipple::PointSimd::baseline);
    stipple::FrameConfig config;
    uint32_t most_run = 0;
    compare_threads(config, "walk, baseline SIMD", &most_run);
}

// The pipeline's frames on the baseline path and on the run-time path: the same bytes.
TEST_F(PointStagesTest, SimdPathsGiveByteIdenticalFrames) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    for (const bool lod : {true, false}) {
        stipple::FrameConfig config;
        config.lod = lod;
        config.threads = 2;
        auto p = std::make_unique<Pipeline>();
        ASSERT_TRUE(stipple::pipeline_init(p.get(), asset_, gl_.gl(), config).ok());
        for (int f = 0; f < 6; ++f) {
            stipple::AnimationState state;
            state.clip = 0;
            state.time = float(f) / 7.0f;
            stipple::point_simd_force(stipple::PointSimd::baseline);
            stipple::pipeline_update(p.get(), state, nullptr);
            const Outputs base = outputs(*p);
            for (const PointSimd simd : {PointSimd::avx2, PointSimd::avx512}) {
                if (simd > stipple::point_simd_detected()) continue;  // no AVX-512 here
                stipple::point_simd_force(simd);
                ASSERT_EQ(stipple::point_simd(), simd);
                stipple::pipeline_update(p.get(), state, nullptr);
                expect_identical(base, outputs(*p),
                                 std::string(lod ? "LOD" : "no LOD") + ", frame " +
                                     std::to_string(f) + ", " + stipple::point_simd_name(simd));
            }
        }
        stipple::pipeline_destroy(p.get());
    }
}

// Each kernel against its scalar original on hostile inputs: zero and NaN normals, points
// behind the eye and the camera plane, no neighbours, every scale sign, lists with tails.
TEST_F(PointStagesTest, SimdKernelsMatchTheScalarCodeOnEdgeCases) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    // The asset's points with every 17th point's neighbours removed (no-neighbour branches).
    stipple::PointsView pts = asset_.points;
    const uint32_t n = pts.point_count;
    std::vector<uint32_t> offsets(n + 1, 0), neighbours;
    for (uint32_t i = 0; i < n; ++i) {
        offsets[i] = uint32_t(neighbours.size());
        if (i % 17 == 3) continue;
        for (uint32_t k = pts.neighbour_offsets[i]; k < pts.neighbour_offsets[i + 1]; ++k)
            neighbours.push_back(pts.neighbours[k]);
    }
    offsets[n] = uint32_t(neighbours.size());
    pts.neighbour_offsets = offsets.data();
    pts.neighbours = neighbours.data();
    pts.neighbour_count = offsets[n];
    const stipple::MeshView& m = asset_.mesh;
    std::vector<float> vn(m.normals, m.normals + size_t(m.vertex_count) * 3);
    for (uint32_t v = 0; v < m.vertex_count; v += 97)
        vn[size_t(v) * 3] = vn[size_t(v) * 3 + 1] = vn[size_t(v) * 3 + 2] =
            0.0f;  // degenerate normals: the zero-length branch
    vn[3] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> scale(n);
    std::vector<float> bind(size_t(n) * 3), bind_n(size_t(n) * 3);
    stipple::place_points(pts, m.indices, m.positions, m.normals, bind.data(), bind_n.data());
    stipple::relevance_scale(pts, bind.data(), scale.data());
    // In the first half only: the second half's blocks of 16 all take the area measure (the
    // AVX-512 step; a block with another scale goes to the AVX2 one).
    for (uint32_t i = 0; i < n / 2; i += 13) scale[i] = -std::fabs(scale[i]);  // mean distance
    for (uint32_t i = 5; i < n / 2; i += 29) scale[i] = 0.0f;                  // fallback
    scale[7] = std::numeric_limits<float>::quiet_NaN();
    stipple::SizeParams params;
    params.view_projection = glm::mat4(1.0f);
    params.view_projection[1][1] = 2.0f;
    params.view_projection[2][3] = -1.0f;
    params.view_projection[3][3] = 0.5f;  // some points behind the camera plane (w <= 0)
    params.eye = glm::vec3(0.2f, 1.0f, 0.4f);
    params.light_count = 2;
    params.light_direction[1] = glm::normalize(glm::vec3(1.0f, -1.0f, 0.3f));
    params.light_intensity[1] = 0.5f;
    params.ambient = 0.1f;
    std::vector<uint32_t> list;
    for (uint32_t i = 0; i < n; i += 3) list.push_back(i);
    list.resize(list.size() - list.size() % 8 - 3);        // a tail of 5
    std::vector<float> pairs(size_t(m.vertex_count) * 8);  // place's AVX2 input
    stipple::pair_vertices(m.vertex_count, m.positions, vn.data(), pairs.data());
    std::vector<uint32_t> quads(size_t(n) * 4);  // relevance's fixed-stride neighbours
    ASSERT_TRUE(stipple::quad_neighbours(pts, quads.data()));
    std::vector<stipple::PointHost> hosts(n);  // place's 16-byte hosts
    ASSERT_TRUE(stipple::point_hosts(pts, m.indices, m.vertex_count, hosts.data()));
    struct Run {
        std::vector<float> pos, nrm, radius, size;
    } run[5];
    // baseline, AVX2 on the asset's arrays, on its own records, with relevance and size fused,
    // and fused 16 points a step (AVX-512, where the CPU has it: else the AVX2 fused again)
    for (int path = 0; path < 5; ++path) {
        stipple::point_simd_force(path == 0   ? PointSimd::baseline
                                  : path == 4 ? PointSimd::avx512
                                              : PointSimd::avx2);
        Run& r = run[path];
        r.pos.assign(size_t(n) * 3 + stipple::kSimdPadFloats, -1.0f);  // 16-byte loads
        r.nrm.assign(size_t(n) * 3 + stipple::kSimdPadFloats, -1.0f);
        r.radius.assign(n, -1.0f);
        r.size.assign(n, -1.0f);
        stipple::PointStageFrame f;
        f.points = &pts;
        f.indices = m.indices;
        f.vertex_positions = m.positions;
        f.vertex_normals = vn.data();
        f.vertex_pairs = pairs.data();
        f.neighbour_quads = path >= 2 ? quads.data() : nullptr;
        f.point_hosts = path >= 2 ? hosts.data() : nullptr;
        f.scale = scale.data();
        f.fallback_radius = pts.radius;
        f.params = &params;
        f.positions = r.pos.data();
        f.normals = r.nrm.data();
        f.radius = r.radius.data();
        f.size = r.size.data();
        stipple::ThreadPool pool;                              // one thread: the kernels alone
        stipple::point_stage_place(&pool, f, nullptr, n - 3);  // a tail, and 3 points unplaced
        stipple::point_stage_place(&pool, f, list.data(), uint32_t(list.size()));
        if (path >= 3) {
            ASSERT_TRUE(stipple::point_stage_relevance_size(&pool, f, nullptr, n - 3));
            ASSERT_TRUE(
                stipple::point_stage_relevance_size(&pool, f, list.data(), uint32_t(list.size())));
            continue;
        }
        stipple::point_stage_relevance(&pool, f, nullptr, n - 3);
        stipple::point_stage_relevance(&pool, f, list.data(), uint32_t(list.size()));
        stipple::point_stage_size(&pool, f, nullptr, n - 3);
        stipple::point_stage_size(&pool, f, list.data(), uint32_t(list.size()));
    }
    for (int path = 1; path < 5; ++path) {
        EXPECT_TRUE(same_bytes(run[0].pos, run[path].pos)) << path;
        EXPECT_TRUE(same_bytes(run[0].nrm, run[path].nrm)) << path;
        EXPECT_TRUE(same_bytes(run[0].radius, run[path].radius)) << path;
        EXPECT_TRUE(same_bytes(run[0].size, run[path].size)) << path;
    }
    uint32_t hidden = 0, drawn = 0;
    for (float s : run[1].size) {
        hidden += s == 0.0f;
        drawn += s > 0.0f;
    }
    EXPECT_GT(hidden, n / 10);  // the inputs reached both sides of every branch
    EXPECT_GT(drawn, n / 100);
    EXPECT_EQ(run[1].size[n - 1], -1.0f);  // outside every range: untouched
}

// The vertex pairs place and the clusters' normal bounds read: position and normal copied bit
// for bit, the normal's length and its inverse in the spare lanes (0 and 0 for no normal).
TEST(VertexPairs, CarryPositionNormalLengthAndInverse) {
    const float positions[6] = {1.0f, -2.0f, 3.5f, 0.0f, 0.0f, 0.0f};
    const float normals[6] = {3.0f, 4.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    float pairs[16];
    std::fill(pairs, pairs + 16, -7.0f);
    stipple::pair_vertices(2, positions, normals, pairs);
    for (int v = 0; v < 2; ++v)
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(pairs[v * 8 + k], positions[v * 3 + k]) << v << " " << k;
            EXPECT_EQ(pairs[v * 8 + 4 + k], normals[v * 3 + k]) << v << " " << k;
        }
    EXPECT_EQ(pairs[3], 5.0f);
    EXPECT_EQ(pairs[7], 0.2f);
    EXPECT_EQ(pairs[11], 0.0f);
    EXPECT_EQ(pairs[15], 0.0f);
}

TEST(PointStagesConfig, ThreadsAreResolvedAndRangeChecked) {
    stipple::FrameConfig c;
    stipple::FrameConfig out;
    EXPECT_EQ(stipple::default_frame_config().threads, 1);
    c.threads = 0;
    ASSERT_TRUE(stipple::resolve_frame_config(c, &out).ok());
    EXPECT_GE(out.threads, 1);
    EXPECT_LE(out.threads, stipple::kMaxAutoThreads);
    for (const int bad : {-1, stipple::kMaxPoolThreads + 1}) {
        c.threads = bad;
        const stipple::Status st = stipple::resolve_frame_config(c, &out);
        EXPECT_EQ(st.code, stipple::StatusCode::invalid_argument);
        EXPECT_NE(std::string(st.message).find("threads"), std::string::npos) << st.message;
    }
    // The C description: 0 keeps the default, -1 asks for the hardware's, others are checked.
    stipple_player_desc d = {}, resolved;
    for (const int ok : {0, -1, 3, stipple::kMaxPoolThreads}) {
        d.threads = ok;
        EXPECT_EQ(stipple_player_desc_resolve(&d, &resolved), STIPPLE_OK) << ok;
    }
    for (const int bad : {-2, stipple::kMaxPoolThreads + 1}) {
        d.threads = bad;
        EXPECT_EQ(stipple_player_desc_resolve(&d, &resolved), STIPPLE_ERROR_INVALID_ARGUMENT)
            << bad;
    }
}

// The pool's ranges cover [0, count) exactly once, whatever the count, over many tasks in a
// row (workers that wake late must not run a range twice or run an old task's range).
TEST(ThreadPool, RangesCoverEveryIndexOnce) {
    for (const int threads : {1, 2, 3, 8}) {
        stipple::ThreadPool pool;
        ASSERT_TRUE(stipple::thread_pool_init(&pool, threads).ok());
        for (const uint32_t count : {0u, 1u, 7u, 4095u, 100003u}) {
            std::vector<int> hits(count, 0);
            const int tasks = count > 10000 ? 20 : 300;
            for (int t = 0; t < tasks; ++t)
                stipple::thread_pool_run(
                    &pool, count, 1,
                    [](void* context, uint32_t begin, uint32_t end) {
                        int* h = static_cast<int*>(context);
                        for (uint32_t i = begin; i < end; ++i) h[i] += 1;
                    },
                    hits.data());
            EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), int(count) * tasks);
            EXPECT_EQ(std::count(hits.begin(), hits.end(), tasks), std::ptrdiff_t(count));
        }
        stipple::thread_pool_destroy(&pool);
        EXPECT_EQ(pool.threads, 1);
    }
}

}  // namespace

// The vertex pairs (runtime/point_simd.h) from both paths, on 23 vertices (a tail of 3) whose
// normals include zero, NaN, infinite, subnormal and huge ones: the same bytes, and |n|, 1/|n|
// as stated (1/|n| = 0 where |n| is not > 0).
TEST(PointSimdPairs, Avx2PairsMatchTheScalarPairs) {
    if (!stipple::has_avx2(stipple::point_simd_detected()))
        GTEST_SKIP() << "this CPU has no AVX2 (or STIPPLE_SIMD=baseline): one path only";
    const uint32_t n = 23;
    std::vector<float> positions(n * 3), normals(n * 3);
    for (uint32_t i = 0; i < n * 3; ++i) {
        positions[i] = 0.37f * float(i) - 3.0f;
        normals[i] = std::sin(1.7f * float(i));
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float special[6][3] = {{0, 0, 0},      {nan, 0, 1},       {inf, 0, 0},
                                 {1e-40f, 0, 0}, {1e20f, 1e20f, 0}, {-0.0f, -0.0f, -0.0f}};
    for (int k = 0; k < 6; ++k)
        for (int c = 0; c < 3; ++c) normals[size_t(k * 4 + 1) * 3 + c] = special[k][c];
    std::vector<float> scalar(n * 8, -1.0f), avx2(n * 8, -2.0f);
    stipple::pair_vertices(n, positions.data(), normals.data(), scalar.data());
    stipple::pair_vertices_avx2(n, positions.data(), normals.data(), avx2.data());
    EXPECT_TRUE(same_bytes(scalar, avx2));
    EXPECT_EQ(scalar[1 * 8 + 3], 0.0f);  // zero normal: |n| = 0, 1/|n| = 0
    EXPECT_EQ(scalar[1 * 8 + 7], 0.0f);
    EXPECT_EQ(scalar[5 * 8 + 7], 0.0f);  // NaN: 1/|n| = 0
    EXPECT_EQ(scalar[9 * 8 + 3], inf);
    EXPECT_EQ(scalar[9 * 8 + 7], 0.0f);
    EXPECT_FLOAT_EQ(scalar[0 * 8 + 3] * scalar[0 * 8 + 7], 1.0f);
}
