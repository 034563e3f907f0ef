// Measurements of headless stipple frames for CI and for the corpus tables (docs/measure.md):
// tone inside the object's mask, screen-space evenness of the drawn dots, and frame-to-frame
// coherence (persistence and pops) from stipple-play's dot lists. No GL; PNGs are read with stb.
//
// Conventions: images are top row first, as stored in PNG; dot coordinates are pixels with the
// origin at the top-left corner of the image (stipple-play's dots_NNNN.csv), so a dot at
// (x, y) lies in pixel (floor(x), floor(y)). Every loader reports failure with `false` and a
// one-line message in `*error` (when `error` is not null); nothing throws or aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stipple::measure {

// Which pixels show the object. `inside` holds width * height bytes (0 or 1), top row first.
struct Mask {
    int width = 0, height = 0;
    std::vector<uint8_t> inside;
    // False outside the image.
    bool at(int x, int y) const {
        return x >= 0 && y >= 0 && x < width && y < height &&
               inside[size_t(y) * size_t(width) + size_t(x)] != 0;
    }
};

// An RGBA8 image, top row first.
struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// Rec.709 luminance of an RGBA8 pixel in [0, 1] (the weights the frame tests use,
// tests/common/fixtures.h).
double luminance(const uint8_t* rgba_pixel);

// Reads any PNG stb can decode (grey, grey+alpha, RGB, RGBA) as RGBA8.
bool load_png(const std::string& path, Image* image, std::string* error);

// A pixel is inside when its luminance is > 0.99. This reads both a mask PNG (white object on
// black, stipple-play --mask-out) and the legacy "paper frame" (a frame rendered with
// `--tone 0 --background 808080 --no-silhouettes`, where the object is the white paper).
Mask mask_from_image(const Image& image);
bool load_mask_png(const std::string& path, Mask* mask, std::string* error);

// Rows and columns spanned by the mask (inclusive) and its pixel count; all -1 and 0 when empty.
struct MaskExtent {
    int top = -1, bottom = -1, left = -1, right = -1;
    size_t pixels = 0;
};
MaskExtent mask_extent(const Mask& mask);

// Mean darkness 1 - luminance over the inside pixels of an RGBA8 image of w x h pixels (top row
// first) whose size must equal the mask's. `pixels` (optional) receives the number of inside
// pixels averaged. 0 with 0 pixels when the mask is empty or the sizes differ.
double mean_tone(const uint8_t* rgba, int w, int h, const Mask& mask, size_t* pixels);
// The same over the image rows [row_begin, row_end) only (clamped to the image): a band.
double mean_tone_rows(const uint8_t* rgba, int w, int h, const Mask& mask, int row_begin,
                      int row_end, size_t* pixels);

// One drawn dot: stable point id (64-bit: run-time refined points get ids >= 2^32), centre in
// pixels (origin top-left) and diameter in pixels.
struct Dot {
    uint64_t id = 0;
    float x = 0, y = 0, size = 0;
};

// Reads stipple-play's dots_NNNN.csv: a header line, then `id,x,y,size` per line. Blank lines
// are skipped; any other malformed line is an error naming its line number.
bool load_dots_csv(const std::string& path, std::vector<Dot>* dots, std::string* error);

// Screen-space evenness of the dots whose centre pixel is inside the mask ("counted" dots).
//   dots:          counted dots;
//   median_nn, mean_nn: median and mean distance from a counted dot to its nearest other dot
//                  (any dot of the list, counted or not: the neighbour may sit just outside);
//   nn_cv:         stddev / mean of those distances (population stddev); 0 for a perfect
//                  lattice, ~0.52 for uniform random points (a Poisson process);
//   clump_share:   fraction of counted dots whose NN distance is < 0.5 x median_nn
//                  (Poisson: 1 - 2^(-1/4) ~ 0.159);
//   blocks_inside: whole block x block squares of the image tiling (from the top-left corner;
//                  partial squares at the right and bottom edges are ignored) all of whose
//                  pixels are inside the mask;
//   empty_blocks:  inside blocks that contain no counted dot centre.
// Nearest neighbours come from a 2-d tree: O(n log n) for any spread, clumped or not.
struct Evenness {
    size_t dots = 0;
    double median_nn = 0, mean_nn = 0, nn_cv = 0, clump_share = 0;
    int blocks_inside = 0, empty_blocks = 0;
};
Evenness evenness(const std::vector<Dot>& dots, const Mask& mask, int block = 16);

// For every pixel, the Euclidean distance from its centre to the centre of the nearest pixel
// that is outside the mask, where everything beyond the image border counts as outside (so a
// pixel on the image edge has distance 1). 0 for outside pixels. Exact (Felzenszwalb-
// Huttenlocher squared distance transform), O(width * height).
std::vector<float> distance_to_outside(const Mask& mask);

// Coherence between consecutive frames f (`before`) and f + 1 (`after`):
//   persistence: |ids(f) ∩ ids(f+1)| / |ids(f)| (1 when frame f has no dots);
//   appeared:    dots of f+1 whose id is not in f; vanished: dots of f whose id is not in f+1;
//   pops:        appeared dots with size > 0.5 x the median dot size of f+1 lying more than
//                `margin` px inside the mask of f+1 (distance_to_outside > margin), plus
//                vanished dots with size > 0.5 x the median size of f lying more than `margin`
//                px inside the mask of f: a big dot that blinks on or off in the middle of the
//                object, not at its outline where dots legitimately come and go;
//   pop_share:   pops / number of dots in f+1 (0 when f+1 has none).
// Duplicate ids within one frame are counted once for the id sets.
// With the dots each frame sized but the mesh in front hid (stipple-play --hidden-out,
// pipeline_hidden_dots), occlusion is told apart from dots the stippling dropped:
//   occluded:    vanished dots that f+1 still draws but hides (a leg passing in front);
//   disoccluded: appeared dots that f drew hidden (the leg passing on);
//   persistence_unoccluded: |ids(f) ∩ ids(f+1)| / (|ids(f)| - occluded) (1 when that is 0);
//   pops_unoccluded, pop_share_unoccluded: the pops that are neither occluded nor disoccluded.
// Without them (occlusion_known false) the *_unoccluded fields equal the plain ones.
struct FramePair {
    double persistence = 1;
    size_t appeared = 0, vanished = 0, pops = 0;
    double pop_share = 0;
    bool occlusion_known = false;
    size_t occluded = 0, disoccluded = 0, pops_unoccluded = 0;
    double persistence_unoccluded = 1, pop_share_unoccluded = 0;
};
constexpr float kPopMargin = 4.0f;
FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<Dot>& after, const Mask& mask_after,
                     float margin = kPopMargin);
// The same with precomputed distance_to_outside() fields (sizes must match the masks').
FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<float>& distance_before, const std::vector<Dot>& after,
                     const Mask& mask_after, const std::vector<float>& distance_after,
                     float margin = kPopMargin);
// The same with the hidden dots of both frames (the occlusion-aware fields).
FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<float>& distance_before,
                     const std::vector<Dot>& hidden_before, const std::vector<Dot>& after,
                     const Mask& mask_after, const std::vector<float>& distance_after,
                     const std::vector<Dot>& hidden_after, float margin = kPopMargin);

// Summary of a sequence of pairs (pair i is frames i -> i + 1 of the sequence). Worst and max
// give the pair index; all zero (and -1) for an empty sequence.
// The *_unoccluded values summarise the pairs' occlusion-aware fields (occlusion_known: every
// pair had hidden dots).
struct Coherence {
    size_t pairs = 0, pops = 0;
    double mean_persistence = 0, worst_persistence = 0, mean_pop_share = 0, max_pop_share = 0;
    int worst_persistence_pair = -1, max_pop_share_pair = -1;
    bool occlusion_known = false;
    size_t occluded = 0, disoccluded = 0, pops_unoccluded = 0;
    double mean_persistence_unoccluded = 0, worst_persistence_unoccluded = 0;
    double mean_pop_share_unoccluded = 0, max_pop_share_unoccluded = 0;
    int worst_persistence_unoccluded_pair = -1, max_pop_share_unoccluded_pair = -1;
};
Coherence summarize(const std::vector<FramePair>& pairs);

}  // namespace stipple::measure
