// Frame measurements (tools/frame_measure.h) on synthetic data whose answers are known
// analytically. The stipple-measure CLI: tests/tools/test_measure_cli.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "tests/common/fixtures.h"
#include "tools/frame_measure.h"
#include "tools/image_write.h"

namespace {

namespace m = stipple::measure;

m::Mask full_mask(int w, int h) {
    m::Mask mask;
    mask.width = w;
    mask.height = h;
    mask.inside.assign(size_t(w) * size_t(h), 1);
    return mask;
}

// Inside exactly on [x0, x1) x [y0, y1).
m::Mask rect_mask(int w, int h, int x0, int y0, int x1, int y1) {
    m::Mask mask = full_mask(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            mask.inside[size_t(y) * size_t(w) + size_t(x)] = x >= x0 && x < x1 && y >= y0 && y < y1;
    return mask;
}

// Dots at (offset + spacing * i, offset + spacing * j) for i, j < n, ids from `first_id`.
std::vector<m::Dot> square_grid(int n, float spacing, float offset, uint64_t first_id = 0) {
    std::vector<m::Dot> dots;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            dots.push_back(
                {first_id++, offset + spacing * float(i), offset + spacing * float(j), 2});
    return dots;
}

TEST(FrameMeasure, SquareGridIsPerfectlyEven) {
    const std::vector<m::Dot> dots = square_grid(64, 8, 4);
    const m::Evenness e = m::evenness(dots, full_mask(512, 512));
    EXPECT_EQ(e.dots, 64u * 64u);
    EXPECT_NEAR(e.median_nn, 8.0, 1e-9);
    EXPECT_NEAR(e.mean_nn, 8.0, 1e-9);
    EXPECT_NEAR(e.nn_cv, 0.0, 1e-9);
    EXPECT_EQ(e.clump_share, 0.0);
    EXPECT_EQ(e.blocks_inside, 32 * 32);
    EXPECT_EQ(e.empty_blocks, 0);
}

TEST(FrameMeasure, HexGridIsPerfectlyEven) {
    std::vector<m::Dot> dots;
    const double spacing = 6, row = spacing * std::sqrt(3.0) / 2;
    uint64_t id = 0;
    for (int j = 0; j < 80; ++j)
        for (int i = 0; i < 80; ++i)
            dots.push_back(
                {id++, float(3 + spacing * i + (j % 2 ? spacing / 2 : 0)), float(3 + row * j), 1});
    const m::Evenness e = m::evenness(dots, full_mask(512, 512));
    EXPECT_EQ(e.dots, 80u * 80u);
    EXPECT_NEAR(e.median_nn, spacing, 1e-4);
    EXPECT_LT(e.nn_cv, 1e-4);  // float coordinates
    EXPECT_EQ(e.clump_share, 0.0);
}

// Each added dot sits a quarter spacing from a grid dot: both of them have NN = 2 < 0.5 x 8.
TEST(FrameMeasure, QuarterSpacingDotsAreExactlyTheClumps) {
    std::vector<m::Dot> dots = square_grid(64, 8, 4);
    const int added = 10;
    for (int k = 0; k < added; ++k) {
        const m::Dot& host = dots[size_t(k * 400 + 37)];
        dots.push_back({100000u + uint64_t(k), host.x + 2, host.y, 2});
    }
    const m::Evenness e = m::evenness(dots, full_mask(512, 512));
    EXPECT_EQ(e.dots, 64u * 64u + added);
    EXPECT_NEAR(e.median_nn, 8.0, 1e-9);
    EXPECT_DOUBLE_EQ(e.clump_share, double(2 * added) / double(64 * 64 + added));
}

// A Poisson process: NN distances are Rayleigh distributed, so CV = sqrt(4/pi - 1) ~ 0.5227
// and P(d < median / 2) = 1 - 2^(-1/4) ~ 0.1591. Counting only an inner window (neighbours
// come from every dot) removes the border bias.
TEST(FrameMeasure, UniformRandomPointsMatchThePoissonProcess) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(0.0f, 2000.0f);
    std::vector<m::Dot> dots(200000);
    for (size_t i = 0; i < dots.size(); ++i) dots[i] = {i, u(rng), u(rng), 1};
    const m::Evenness e = m::evenness(dots, rect_mask(2000, 2000, 100, 100, 1900, 1900));
    EXPECT_GT(e.dots, 150000u);
    const double lambda = 200000.0 / (2000.0 * 2000.0);
    EXPECT_NEAR(e.nn_cv, std::sqrt(4 / M_PI - 1), 0.01);
    EXPECT_NEAR(e.clump_share, 1 - std::pow(2.0, -0.25), 0.01);
    EXPECT_NEAR(e.mean_nn, 0.5 / std::sqrt(lambda), 0.01 / std::sqrt(lambda));
    EXPECT_NEAR(e.median_nn, std::sqrt(std::log(2.0) / (M_PI * lambda)), 0.01 / std::sqrt(lambda));
}

TEST(FrameMeasure, HundredThousandDotsTakeWellUnderASecond) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<m::Dot> dots(100000);
    for (size_t i = 0; i < dots.size(); ++i) dots[i] = {i, 1280 * u(rng), 720 * u(rng), 1};
    // Also a clustered half: many dots per grid cell must not make it quadratic.
    for (size_t i = 0; i < 50000; ++i) dots[i].x *= 0.01f, dots[i].y *= 0.01f;
    for (size_t i = 50000; i < 51000; ++i) dots[i].x = 640, dots[i].y = 360;  // duplicates
    const m::Mask mask = full_mask(1280, 720);
    const auto start = std::chrono::steady_clock::now();
    const m::Evenness e = m::evenness(dots, mask);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("evenness of 100k dots: %.3f s\n", seconds);
    EXPECT_EQ(e.dots, 100000u);
    EXPECT_LT(seconds, 1.0);
}

// A 64x64 hole in a grid of dots every 4 px: aligned with the 16-px blocks it empties 4x4
// blocks; shifted by 8 px it empties only the 3x3 blocks wholly inside it.
TEST(FrameMeasure, EmptyBlocksAreCountedExactly) {
    auto with_hole = [](int x0, int y0) {
        std::vector<m::Dot> dots;
        for (const m::Dot& d : square_grid(64, 4, 2))
            if (!(d.x >= x0 && d.x < x0 + 64 && d.y >= y0 && d.y < y0 + 64)) dots.push_back(d);
        return dots;
    };
    const m::Mask mask = full_mask(256, 256);
    m::Evenness e = m::evenness(with_hole(64, 64), mask);
    EXPECT_EQ(e.blocks_inside, 256);
    EXPECT_EQ(e.empty_blocks, 16);
    e = m::evenness(with_hole(72, 72), mask);
    EXPECT_EQ(e.empty_blocks, 9);
    e = m::evenness(with_hole(72, 72), mask, 8);
    EXPECT_EQ(e.blocks_inside, 32 * 32);
    EXPECT_EQ(e.empty_blocks, 64);

    // A block counts only if all its pixels are inside; dots outside the mask are not counted.
    m::Mask holed = mask;
    holed.inside[5 * 256 + 5] = 0;
    e = m::evenness(with_hole(64, 64), holed);
    EXPECT_EQ(e.blocks_inside, 255);
    e = m::evenness(square_grid(64, 4, 2), rect_mask(256, 256, 0, 0, 128, 256));
    EXPECT_EQ(e.dots, 32u * 64u);
    EXPECT_EQ(e.blocks_inside, 8 * 16);
    EXPECT_EQ(e.empty_blocks, 0);
    // Partial blocks at the right/bottom edges are ignored.
    e = m::evenness({}, full_mask(40, 20));
    EXPECT_EQ(e.blocks_inside, 2);
    EXPECT_EQ(e.empty_blocks, 2);
    EXPECT_EQ(e.dots, 0u);
}

// Left half black, right half white, mid-grey stripe; the mask selects known parts.
TEST(FrameMeasure, ToneInsideTheMask) {
    const int w = 100, h = 50;
    std::vector<uint8_t> rgba(size_t(w) * h * 4, 255);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t v = x < 50 ? 0 : 255;
            if (y >= 40) v = 128;
            uint8_t* p = &rgba[(size_t(y) * w + size_t(x)) * 4];
            p[0] = p[1] = p[2] = v;
        }
    size_t pixels = 0;
    EXPECT_NEAR(m::mean_tone(rgba.data(), w, h, rect_mask(w, h, 25, 0, 75, 40), &pixels), 0.5,
                1e-12);
    EXPECT_EQ(pixels, 50u * 40u);
    EXPECT_NEAR(m::mean_tone(rgba.data(), w, h, rect_mask(w, h, 0, 0, 50, 40), &pixels), 1.0,
                1e-12);
    EXPECT_NEAR(m::mean_tone(rgba.data(), w, h, rect_mask(w, h, 0, 40, 100, 50), &pixels),
                1.0 - 128.0 / 255.0, 1e-12);
    EXPECT_NEAR(m::mean_tone_rows(rgba.data(), w, h, full_mask(w, h), 45, 1000, &pixels),
                1.0 - 128.0 / 255.0, 1e-12);
    EXPECT_EQ(pixels, 500u);
    EXPECT_EQ(m::mean_tone(rgba.data(), w, h, full_mask(w + 1, h), &pixels), 0.0);  // size mismatch
    EXPECT_EQ(pixels, 0u);
}

// The luminance > 0.99 rule reads a paper frame (white object on 808080) and a mask PNG.
TEST(FrameMeasure, MaskFromPaperFrameAndMaskPng) {
    const int w = 40, h = 30;
    std::vector<uint8_t> rgba(size_t(w) * h * 4, 0x80);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t* p = &rgba[(size_t(y) * w + size_t(x)) * 4];
            p[3] = 255;
            if (x >= 10 && x < 20 && y < 5) p[0] = p[1] = p[2] = 255;  // near the top
            if (x == 0 && y == 29) p[0] = p[1] = p[2] = 252;           // 0.988: outside
            if (x == 1 && y == 29) p[0] = p[1] = p[2] = 253;           // 0.992: inside
        }
    const std::string path = stipple::test::scratch_path("measure_paper.png");
    std::string error;
    ASSERT_TRUE(stipple::image::write_png(path.c_str(), w, h, rgba.data(), false, &error)) << error;
    m::Mask mask;
    ASSERT_TRUE(m::load_mask_png(path, &mask, &error)) << error;
    ASSERT_EQ(mask.width, w);
    ASSERT_EQ(mask.height, h);
    const m::MaskExtent e = m::mask_extent(mask);
    EXPECT_EQ(e.pixels, 10u * 5u + 1u);
    EXPECT_EQ(e.top, 0);
    EXPECT_EQ(e.bottom, 29);
    EXPECT_TRUE(mask.at(10, 0));
    EXPECT_FALSE(mask.at(10, 5));
    EXPECT_FALSE(mask.at(0, 29));
    EXPECT_TRUE(mask.at(1, 29));
    EXPECT_FALSE(m::load_mask_png(stipple::test::scratch_path("no_such_mask.png"), &mask, &error));
    EXPECT_NE(error.find("no_such_mask.png"), std::string::npos);
}

TEST(FrameMeasure, DistanceToOutsideIsEuclideanAndTheBorderIsOutside) {
    const m::Mask square = rect_mask(100, 100, 10, 10, 90, 90);
    std::vector<float> d = m::distance_to_outside(square);
    EXPECT_EQ(d[50 * 100 + 5], 0.0f);
    EXPECT_FLOAT_EQ(d[50 * 100 + 10], 1.0f);
    EXPECT_FLOAT_EQ(d[50 * 100 + 13], 4.0f);
    EXPECT_FLOAT_EQ(d[50 * 100 + 50], 40.0f);
    EXPECT_FLOAT_EQ(d[10 * 100 + 10], 1.0f);
    EXPECT_FLOAT_EQ(d[14 * 100 + 13], 4.0f);

    m::Mask full = full_mask(200, 200);
    d = m::distance_to_outside(full);
    EXPECT_FLOAT_EQ(d[0], 1.0f);
    EXPECT_FLOAT_EQ(d[10 * 200 + 5], 6.0f);
    full.inside[50 * 200 + 50] = 0;
    d = m::distance_to_outside(full);
    EXPECT_FLOAT_EQ(d[54 * 200 + 53], 5.0f);  // a 3-4-5 triangle
}

// Frame f: ids 1..10; f+1 keeps 1..8 and adds 11..14. Pops: a big dot appearing deep inside
// (11), one with a 64-bit id (14), and a big dot vanishing deep inside (9); not a pop: one
// appearing 3 px from the edge (12), a small one (13), one vanishing 2 px from the edge (10).
TEST(FrameMeasure, FramePairPersistenceAndPops) {
    const m::Mask mask = rect_mask(100, 100, 10, 10, 90, 90);
    std::vector<m::Dot> before, after;
    for (uint64_t id = 1; id <= 8; ++id) before.push_back({id, 50.5f, 20.5f + 5 * float(id), 2});
    before.push_back({9, 40.5f, 40.5f, 2});
    before.push_back({10, 88.5f, 50.5f, 2});
    for (uint64_t id = 1; id <= 8; ++id) after.push_back({id, 50.7f, 20.5f + 5 * float(id), 2});
    after.push_back({11, 30.5f, 50.5f, 2});
    after.push_back({12, 12.5f, 50.5f, 2});
    after.push_back({13, 60.5f, 60.5f, 0.5f});
    after.push_back({(uint64_t(1) << 32) + 3, 70.5f, 70.5f, 2});
    const m::FramePair p = m::frame_pair(before, mask, after, mask);
    EXPECT_DOUBLE_EQ(p.persistence, 0.8);
    EXPECT_EQ(p.appeared, 4u);
    EXPECT_EQ(p.vanished, 2u);
    EXPECT_EQ(p.pops, 3u);
    EXPECT_DOUBLE_EQ(p.pop_share, 3.0 / 12.0);

    // Exactly 4 px inside is not "more than 4 px"; 5 px is.
    std::vector<m::Dot> edge = before;
    edge.push_back({20, 13.5f, 50.5f, 2});
    EXPECT_EQ(m::frame_pair(before, mask, edge, mask).pops, 0u);
    edge.back().x = 14.5f;
    EXPECT_EQ(m::frame_pair(before, mask, edge, mask).pops, 1u);
    // Vanishing dots are judged in the mask of frame f.
    EXPECT_EQ(m::frame_pair(edge, mask, before, rect_mask(100, 100, 0, 0, 1, 1)).pops, 1u);
    EXPECT_EQ(m::frame_pair(edge, rect_mask(100, 100, 0, 0, 1, 1), before, mask).pops, 0u);

    // Identical frames: full persistence, no pops; empty frames: persistence 1, share 0.
    const m::FramePair same = m::frame_pair(before, mask, before, mask);
    EXPECT_EQ(same.persistence, 1.0);
    EXPECT_EQ(same.appeared + same.vanished + same.pops, 0u);
    const m::FramePair empty = m::frame_pair({}, mask, {}, mask);
    EXPECT_EQ(empty.persistence, 1.0);
    EXPECT_EQ(empty.pop_share, 0.0);
}

// The same pair with the hidden dots of both frames: 9 vanished behind the mesh of f+1
// (occluded), 11 and 14 appeared from behind the mesh of f (disoccluded); what is left is
// dot 10 vanishing at the edge and 12, 13 appearing: persistence 8 / (10 - 1), one pop (none
// of 9, 11, 14 is one any more). A hidden id that was not lost changes nothing.
TEST(FrameMeasure, FramePairTellsOcclusionApart) {
    const m::Mask mask = rect_mask(100, 100, 10, 10, 90, 90);
    std::vector<m::Dot> before, after;
    for (uint64_t id = 1; id <= 8; ++id) before.push_back({id, 50.5f, 20.5f + 5 * float(id), 2});
    before.push_back({9, 40.5f, 40.5f, 2});
    before.push_back({10, 88.5f, 50.5f, 2});
    for (uint64_t id = 1; id <= 8; ++id) after.push_back({id, 50.7f, 20.5f + 5 * float(id), 2});
    after.push_back({11, 30.5f, 50.5f, 2});
    after.push_back({12, 12.5f, 50.5f, 2});
    after.push_back({13, 60.5f, 60.5f, 0.5f});
    after.push_back({15, 35.5f, 35.5f, 2});  // appears deep inside from nowhere: a pop
    const uint64_t far_id = (uint64_t(1) << 32) + 3;
    after.push_back({far_id, 70.5f, 70.5f, 2});
    const std::vector<m::Dot> hidden_before = {{11, 30.5f, 50.5f, 2}, {far_id, 70.5f, 70.5f, 2}};
    const std::vector<m::Dot> hidden_after = {{9, 40.6f, 40.5f, 2}, {30, 20.5f, 20.5f, 2}};
    const std::vector<float> d = m::distance_to_outside(mask);
    const m::FramePair p =
        m::frame_pair(before, mask, d, hidden_before, after, mask, d, hidden_after);
    EXPECT_TRUE(p.occlusion_known);
    EXPECT_DOUBLE_EQ(p.persistence, 0.8);  // the plain fields are unchanged
    EXPECT_EQ(p.pops, 4u);
    EXPECT_EQ(p.occluded, 1u);
    EXPECT_EQ(p.disoccluded, 2u);
    EXPECT_DOUBLE_EQ(p.persistence_unoccluded, 8.0 / 9.0);
    EXPECT_EQ(p.pops_unoccluded, 1u);
    EXPECT_DOUBLE_EQ(p.pop_share_unoccluded, 1.0 / 13.0);
    // Without hidden dots the occlusion-aware fields are the plain ones.
    const m::FramePair plain = m::frame_pair(before, mask, after, mask);
    EXPECT_FALSE(plain.occlusion_known);
    EXPECT_EQ(plain.occluded + plain.disoccluded, 0u);
    EXPECT_DOUBLE_EQ(plain.persistence_unoccluded, plain.persistence);
    EXPECT_EQ(plain.pops_unoccluded, plain.pops);
    // Everything lost was occluded: full persistence.
    const std::vector<m::Dot> all_hidden = {{9, 0, 0, 1}, {10, 0, 0, 1}};
    EXPECT_DOUBLE_EQ(
        m::frame_pair(before, mask, d, {}, after, mask, d, all_hidden).persistence_unoccluded, 1.0);
    const m::Coherence c = m::summarize({p, plain});
    EXPECT_FALSE(c.occlusion_known);  // one pair without hidden dots
    EXPECT_TRUE(m::summarize({p, p}).occlusion_known);
    EXPECT_EQ(c.occluded, 1u);
    EXPECT_EQ(c.pops_unoccluded, 1u + plain.pops);
    EXPECT_NEAR(c.mean_persistence_unoccluded, (8.0 / 9.0 + 0.8) / 2, 1e-12);
    EXPECT_DOUBLE_EQ(c.worst_persistence_unoccluded, 0.8);
    EXPECT_EQ(c.worst_persistence_unoccluded_pair, 1);
    EXPECT_EQ(c.max_pop_share_unoccluded_pair, 1);
}

TEST(FrameMeasure, SequenceSummary) {
    std::vector<m::FramePair> pairs(3);
    pairs[0].persistence = 1.0, pairs[0].pop_share = 0.0;
    pairs[1].persistence = 0.7, pairs[1].pop_share = 0.03, pairs[1].pops = 3;
    pairs[2].persistence = 0.9, pairs[2].pop_share = 0.06, pairs[2].pops = 6;
    const m::Coherence c = m::summarize(pairs);
    EXPECT_EQ(c.pairs, 3u);
    EXPECT_NEAR(c.mean_persistence, 2.6 / 3, 1e-12);
    EXPECT_DOUBLE_EQ(c.worst_persistence, 0.7);
    EXPECT_EQ(c.worst_persistence_pair, 1);
    EXPECT_DOUBLE_EQ(c.max_pop_share, 0.06);
    EXPECT_EQ(c.max_pop_share_pair, 2);
    EXPECT_NEAR(c.mean_pop_share, 0.03, 1e-12);
    EXPECT_EQ(c.pops, 9u);
    EXPECT_EQ(m::summarize({}).pairs, 0u);
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

TEST(FrameMeasure, LoadsDotsCsvWith64BitIds) {
    const std::string path = stipple::test::scratch_path("measure_dots.csv");
    write_text(path, "id,x,y,size\r\n3,1.50,2.25,3.000\r\n\r\n4294967301,10,20,0.5\n");
    std::vector<m::Dot> dots;
    std::string error;
    ASSERT_TRUE(m::load_dots_csv(path, &dots, &error)) << error;
    ASSERT_EQ(dots.size(), 2u);
    EXPECT_EQ(dots[0].id, 3u);
    EXPECT_FLOAT_EQ(dots[0].y, 2.25f);
    EXPECT_EQ(dots[1].id, (uint64_t(1) << 32) + 5);
    EXPECT_FLOAT_EQ(dots[1].size, 0.5f);

    write_text(path, "id,x,y,size\n1,2,3,4\n5,6,seven,8\n");
    EXPECT_FALSE(m::load_dots_csv(path, &dots, &error));
    EXPECT_NE(error.find("line 3"), std::string::npos) << error;
    EXPECT_TRUE(dots.empty());
    write_text(path, "id,x,y,size\n-1,2,3,4\n");
    EXPECT_FALSE(m::load_dots_csv(path, &dots, &error));
    write_text(path, "id,x,y,size\n1,2,3,4,5\n");
    EXPECT_FALSE(m::load_dots_csv(path, &dots, &error));
    write_text(path, "");
    EXPECT_FALSE(m::load_dots_csv(path, &dots, &error));
    EXPECT_FALSE(m::load_dots_csv(stipple::test::scratch_path("no_such_dots.csv"), &dots, &error));
    EXPECT_NE(error.find("no_such_dots.csv"), std::string::npos);
}

}  // namespace
