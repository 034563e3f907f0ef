#include "tools/frame_measure.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace stipple::measure {

namespace {

void set_error(std::string* error, const std::string& message) {
    if (error) *error = message;
}

bool is_inside_pixel(const uint8_t* p) {
    return luminance(p) > 0.99;
}

// Felzenszwalb-Huttenlocher 1D squared distance transform of f (n samples) into d.
// v and z are scratch of n and n + 1 entries. Differences of f are taken before adding the
// squares so that two equal "infinite" samples cancel exactly.
void squared_distance_1d(const double* f, int n, double* d, int* v, double* z) {
    const double inf = std::numeric_limits<double>::infinity();
    int k = 0;
    v[0] = 0;
    z[0] = -inf;
    z[1] = inf;
    for (int q = 1; q < n; ++q) {
        double s = 0;
        for (;;) {  // z[0] = -inf and s is finite, so k never drops below 0
            const int p = v[k];
            s = ((f[q] - f[p]) + double(q) * q - double(p) * p) / (2.0 * (q - p));
            if (s > z[k] || k == 0) break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = inf;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        const double dq = q - v[k];
        d[q] = dq * dq + f[v[k]];
    }
}

// Parses a whole field as an unsigned 64-bit integer / finite float.
bool parse_u64(const char* begin, const char* end, uint64_t* out) {
    if (begin == end || *begin < '0' || *begin > '9') return false;
    std::string text(begin, end);
    errno = 0;
    char* stop = nullptr;
    const unsigned long long v = std::strtoull(text.c_str(), &stop, 10);
    if (errno != 0 || *stop != '\0') return false;
    *out = uint64_t(v);
    return true;
}

bool parse_float(const char* begin, const char* end, float* out) {
    if (begin == end) return false;
    std::string text(begin, end);
    char* stop = nullptr;
    const float v = std::strtof(text.c_str(), &stop);
    if (stop == text.c_str() || *stop != '\0' || !std::isfinite(v)) return false;
    *out = v;
    return true;
}

double median_of(std::vector<double> values) {
    if (values.empty()) return 0;
    const size_t mid = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + long(mid), values.end());
    double m = values[mid];
    if (values.size() % 2 == 0) {
        const double lower = *std::max_element(values.begin(), values.begin() + long(mid));
        m = 0.5 * (m + lower);
    }
    return m;
}

double median_size(const std::vector<Dot>& dots) {
    std::vector<double> sizes;
    sizes.reserve(dots.size());
    for (const Dot& d : dots) sizes.push_back(d.size);
    return median_of(std::move(sizes));
}

std::vector<uint64_t> sorted_ids(const std::vector<Dot>& dots) {
    std::vector<uint64_t> ids;
    ids.reserve(dots.size());
    for (const Dot& d : dots) ids.push_back(d.id);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

bool contains(const std::vector<uint64_t>& sorted, uint64_t id) {
    return std::binary_search(sorted.begin(), sorted.end(), id);
}

// True when the dot's centre pixel is more than `margin` px inside the mask.
bool deep_inside(const Dot& d, const Mask& mask, const std::vector<float>& distance, float margin) {
    const int x = int(std::floor(d.x)), y = int(std::floor(d.y));
    if (!mask.at(x, y)) return false;
    return distance[size_t(y) * size_t(mask.width) + size_t(x)] > margin;
}

// Nearest-neighbour queries over the dots: an implicit 2-d tree (each range [lo, hi) of
// `order` splits at its middle element along the wider axis of the range). O(n log n) to build
// and about O(log n) per query whatever the distribution: a uniform grid degrades to O(n^2)
// when many dots pile up in a few cells, which is exactly what clumps are.
class NearestTree {
  public:
    explicit NearestTree(const std::vector<Dot>& dots) : dots_(dots) {
        order_.resize(dots.size());
        for (size_t i = 0; i < order_.size(); ++i) order_[i] = uint32_t(i);
        split_y_.assign(dots.size(), 0);
        build(0, order_.size());
    }

    // Squared distance from dots[i] to its nearest other dot; infinity when it is alone.
    double nearest_squared(size_t i) const {
        double best = std::numeric_limits<double>::infinity();
        search(0, order_.size(), uint32_t(i), &best);
        return best;
    }

  private:
    static constexpr size_t kLeaf = 8;

    float coord(uint32_t i, bool y) const { return y ? dots_[i].y : dots_[i].x; }

    void build(size_t lo, size_t hi) {
        if (hi - lo <= kLeaf) return;
        float x0 = std::numeric_limits<float>::max(), y0 = x0;
        float x1 = std::numeric_limits<float>::lowest(), y1 = x1;
        for (size_t k = lo; k < hi; ++k) {
            const Dot& d = dots_[order_[k]];
            x0 = std::min(x0, d.x), x1 = std::max(x1, d.x);
            y0 = std::min(y0, d.y), y1 = std::max(y1, d.y);
        }
        const bool y = (y1 - y0) > (x1 - x0);
        const size_t mid = lo + (hi - lo) / 2;
        std::nth_element(order_.begin() + long(lo), order_.begin() + long(mid),
                         order_.begin() + long(hi),
                         [&](uint32_t a, uint32_t b) { return coord(a, y) < coord(b, y); });
        split_y_[mid] = y;
        build(lo, mid);
        build(mid + 1, hi);
    }

    void consider(uint32_t k, uint32_t query, double* best) const {
        if (k == query) return;
        const double dx = double(dots_[k].x) - dots_[query].x;
        const double dy = double(dots_[k].y) - dots_[query].y;
        *best = std::min(*best, dx * dx + dy * dy);
    }

    void search(size_t lo, size_t hi, uint32_t query, double* best) const {
        if (hi - lo <= kLeaf) {
            for (size_t k = lo; k < hi; ++k) consider(order_[k], query, best);
            return;
        }
        const size_t mid = lo + (hi - lo) / 2;
        const bool y = split_y_[mid] != 0;
        consider(order_[mid], query, best);
        const double diff = double(coord(query, y)) - coord(order_[mid], y);
        if (diff < 0) {
            search(lo, mid, query, best);
            if (diff * diff < *best) search(mid + 1, hi, query, best);
        } else {
            search(mid + 1, hi, query, best);
            if (diff * diff < *best) search(lo, mid, query, best);
        }
    }

    const std::vector<Dot>& dots_;
    std::vector<uint32_t> order_;
    std::vector<uint8_t> split_y_;  // split axis of the range whose middle is this position
};

}  // namespace

double luminance(const uint8_t* p) {
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
}

bool load_png(const std::string& path, Image* image, std::string* error) {
    int w = 0, h = 0, channels = 0;
    uint8_t* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data) {
        const char* why = stbi_failure_reason();
        set_error(error, "cannot read PNG '" + path + "': " + (why ? why : "unknown error"));
        return false;
    }
    image->width = w;
    image->height = h;
    image->rgba.assign(data, data + size_t(w) * size_t(h) * 4);
    stbi_image_free(data);
    return true;
}

Mask mask_from_image(const Image& image) {
    Mask m;
    m.width = image.width;
    m.height = image.height;
    const size_t n = size_t(image.width) * size_t(image.height);
    m.inside.resize(n);
    for (size_t i = 0; i < n; ++i) m.inside[i] = is_inside_pixel(&image.rgba[i * 4]) ? 1 : 0;
    return m;
}

bool load_mask_png(const std::string& path, Mask* mask, std::string* error) {
    Image image;
    if (!load_png(path, &image, error)) return false;
    *mask = mask_from_image(image);
    return true;
}

MaskExtent mask_extent(const Mask& mask) {
    MaskExtent e;
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (!mask.inside[size_t(y) * size_t(mask.width) + size_t(x)]) continue;
            if (e.pixels == 0) e.top = y, e.left = x, e.right = x;
            e.bottom = y;
            e.left = std::min(e.left, x);
            e.right = std::max(e.right, x);
            ++e.pixels;
        }
    return e;
}

double mean_tone_rows(const uint8_t* rgba, int w, int h, const Mask& mask, int row_begin,
                      int row_end, size_t* pixels) {
    if (pixels) *pixels = 0;
    if (w != mask.width || h != mask.height) return 0;
    row_begin = std::max(row_begin, 0);
    row_end = std::min(row_end, h);
    double sum = 0;
    size_t n = 0;
    for (int y = row_begin; y < row_end; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (!mask.inside[i]) continue;
            sum += 1.0 - luminance(rgba + i * 4);
            ++n;
        }
    if (pixels) *pixels = n;
    return n ? sum / double(n) : 0.0;
}

double mean_tone(const uint8_t* rgba, int w, int h, const Mask& mask, size_t* pixels) {
    return mean_tone_rows(rgba, w, h, mask, 0, h, pixels);
}

bool load_dots_csv(const std::string& path, std::vector<Dot>* dots, std::string* error) {
    dots->clear();
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        set_error(error, "cannot open '" + path + "': " + std::strerror(errno));
        return false;
    }
    std::string line;
    long line_number = 0;
    bool ok = true, header = false;
    int c = 0;
    auto parse_line = [&]() {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        ++line_number;
        if (!header) {
            header = true;
            if (line.rfind("id,x,y,size", 0) != 0) {
                set_error(error, path + ": line 1 is not the header 'id,x,y,size'");
                ok = false;
            }
            return;
        }
        if (line.empty()) return;
        const char* fields[5];
        const char* ends[4];
        int count = 0;
        const char* p = line.c_str();
        fields[0] = p;
        for (const char* q = p;; ++q) {
            if (*q == ',' || *q == '\0') {
                if (count < 4) ends[count] = q;
                ++count;
                if (*q == '\0') break;
                if (count < 5) fields[count] = q + 1;
            }
        }
        Dot d;
        if (count != 4 || !parse_u64(fields[0], ends[0], &d.id) ||
            !parse_float(fields[1], ends[1], &d.x) || !parse_float(fields[2], ends[2], &d.y) ||
            !parse_float(fields[3], ends[3], &d.size)) {
            set_error(error, path + ": line " + std::to_string(line_number) +
                                 " is not 'id,x,y,size' with an unsigned id and three numbers");
            ok = false;
            return;
        }
        dots->push_back(d);
    };
    while (ok && (c = std::fgetc(f)) != EOF) {
        if (c == '\n') {
            parse_line();
            line.clear();
        } else {
            line.push_back(char(c));
        }
    }
    if (ok && !line.empty()) parse_line();
    const bool read_error = std::ferror(f) != 0;
    std::fclose(f);
    if (ok && read_error) {
        set_error(error, "cannot read '" + path + "'");
        ok = false;
    }
    if (ok && !header) {
        set_error(error, path + ": empty file (no 'id,x,y,size' header)");
        ok = false;
    }
    if (!ok) dots->clear();
    return ok;
}

Evenness evenness(const std::vector<Dot>& dots, const Mask& mask, int block) {
    Evenness e;
    std::vector<size_t> counted;
    for (size_t i = 0; i < dots.size(); ++i)
        if (mask.at(int(std::floor(dots[i].x)), int(std::floor(dots[i].y)))) counted.push_back(i);
    e.dots = counted.size();

    if (dots.size() >= 2 && !counted.empty()) {
        const NearestTree tree(dots);
        std::vector<double> nn;
        nn.reserve(counted.size());
        for (size_t i : counted) {
            const double d2 = tree.nearest_squared(i);
            if (std::isfinite(d2)) nn.push_back(std::sqrt(d2));
        }
        if (!nn.empty()) {
            double sum = 0, sum2 = 0;
            for (double d : nn) sum += d;
            e.mean_nn = sum / double(nn.size());
            for (double d : nn) sum2 += (d - e.mean_nn) * (d - e.mean_nn);
            const double stddev = std::sqrt(sum2 / double(nn.size()));
            e.nn_cv = e.mean_nn > 0 ? stddev / e.mean_nn : 0;
            e.median_nn = median_of(nn);
            size_t clumped = 0;
            for (double d : nn) clumped += d < 0.5 * e.median_nn;
            e.clump_share = double(clumped) / double(nn.size());
        }
    }

    if (block >= 1) {
        const int bw = mask.width / block, bh = mask.height / block;
        std::vector<uint32_t> hits(size_t(bw) * size_t(bh), 0);
        for (size_t i : counted) {
            const int bx = int(std::floor(dots[i].x)) / block,
                      by = int(std::floor(dots[i].y)) / block;
            if (bx < bw && by < bh) ++hits[size_t(by) * size_t(bw) + size_t(bx)];
        }
        for (int by = 0; by < bh; ++by)
            for (int bx = 0; bx < bw; ++bx) {
                bool all = true;
                for (int y = by * block; all && y < (by + 1) * block; ++y)
                    for (int x = bx * block; x < (bx + 1) * block; ++x)
                        if (!mask.inside[size_t(y) * size_t(mask.width) + size_t(x)]) {
                            all = false;
                            break;
                        }
                if (!all) continue;
                ++e.blocks_inside;
                e.empty_blocks += hits[size_t(by) * size_t(bw) + size_t(bx)] == 0;
            }
    }
    return e;
}

std::vector<float> distance_to_outside(const Mask& mask) {
    // Pad by one pixel of "outside" on every side: the image border counts as outside.
    const int w = mask.width + 2, h = mask.height + 2;
    const double far = 1e20;
    std::vector<double> grid(size_t(w) * size_t(h), 0.0);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x)
            if (mask.inside[size_t(y) * size_t(mask.width) + size_t(x)])
                grid[size_t(y + 1) * size_t(w) + size_t(x + 1)] = far;
    const int n = std::max(w, h);
    const size_t count = size_t(n);
    std::vector<double> f(count), d(count), z(count + 1);
    std::vector<int> v(count);
    for (int x = 0; x < w; ++x) {  // columns
        for (int y = 0; y < h; ++y) f[size_t(y)] = grid[size_t(y) * size_t(w) + size_t(x)];
        squared_distance_1d(f.data(), h, d.data(), v.data(), z.data());
        for (int y = 0; y < h; ++y) grid[size_t(y) * size_t(w) + size_t(x)] = d[size_t(y)];
    }
    for (int y = 0; y < h; ++y) {  // rows
        double* row = &grid[size_t(y) * size_t(w)];
        std::copy(row, row + w, f.begin());
        squared_distance_1d(f.data(), w, d.data(), v.data(), z.data());
        std::copy(d.begin(), d.begin() + w, row);
    }
    std::vector<float> out(size_t(mask.width) * size_t(mask.height));
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x)
            out[size_t(y) * size_t(mask.width) + size_t(x)] =
                float(std::sqrt(grid[size_t(y + 1) * size_t(w) + size_t(x + 1)]));
    return out;
}

namespace {

// frame_pair over id sets; `hidden_before` / `hidden_after` null when occlusion is unknown.
FramePair compare_frames(const std::vector<Dot>& before, const Mask& mask_before,
                         const std::vector<float>& distance_before,
                         const std::vector<uint64_t>* hidden_before, const std::vector<Dot>& after,
                         const Mask& mask_after, const std::vector<float>& distance_after,
                         const std::vector<uint64_t>* hidden_after, float margin) {
    FramePair r;
    r.occlusion_known = hidden_before && hidden_after;
    const std::vector<uint64_t> ids_before = sorted_ids(before), ids_after = sorted_ids(after);
    size_t kept = 0;
    for (uint64_t id : ids_before) kept += contains(ids_after, id);
    r.persistence = ids_before.empty() ? 1.0 : double(kept) / double(ids_before.size());
    const double big_after = 0.5 * median_size(after), big_before = 0.5 * median_size(before);
    for (const Dot& d : after) {
        if (contains(ids_before, d.id)) continue;
        ++r.appeared;
        const bool pop = d.size > big_after && deep_inside(d, mask_after, distance_after, margin);
        const bool uncovered = r.occlusion_known && contains(*hidden_before, d.id);
        r.pops += pop;
        r.disoccluded += uncovered;
        r.pops_unoccluded += pop && !uncovered;
    }
    for (const Dot& d : before) {
        if (contains(ids_after, d.id)) continue;
        ++r.vanished;
        const bool pop =
            d.size > big_before && deep_inside(d, mask_before, distance_before, margin);
        const bool covered = r.occlusion_known && contains(*hidden_after, d.id);
        r.pops += pop;
        r.occluded += covered;
        r.pops_unoccluded += pop && !covered;
    }
    r.pop_share = after.empty() ? 0.0 : double(r.pops) / double(after.size());
    r.pop_share_unoccluded = after.empty() ? 0.0 : double(r.pops_unoccluded) / double(after.size());
    // An id listed twice in `before` but occluded once still leaves the set at most once.
    const size_t seen = ids_before.size() - std::min(r.occluded, ids_before.size());
    r.persistence_unoccluded = seen == 0 ? 1.0 : double(kept) / double(seen);
    return r;
}

}  // namespace

FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<float>& distance_before, const std::vector<Dot>& after,
                     const Mask& mask_after, const std::vector<float>& distance_after,
                     float margin) {
    return compare_frames(before, mask_before, distance_before, nullptr, after, mask_after,
                          distance_after, nullptr, margin);
}

FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<float>& distance_before,
                     const std::vector<Dot>& hidden_before, const std::vector<Dot>& after,
                     const Mask& mask_after, const std::vector<float>& distance_after,
                     const std::vector<Dot>& hidden_after, float margin) {
    const std::vector<uint64_t> hb = sorted_ids(hidden_before), ha = sorted_ids(hidden_after);
    return compare_frames(before, mask_before, distance_before, &hb, after, mask_after,
                          distance_after, &ha, margin);
}

FramePair frame_pair(const std::vector<Dot>& before, const Mask& mask_before,
                     const std::vector<Dot>& after, const Mask& mask_after, float margin) {
    return frame_pair(before, mask_before, distance_to_outside(mask_before), after, mask_after,
                      distance_to_outside(mask_after), margin);
}

Coherence summarize(const std::vector<FramePair>& pairs) {
    Coherence c;
    c.pairs = pairs.size();
    if (pairs.empty()) return c;
    c.worst_persistence = c.worst_persistence_unoccluded = 2;
    c.max_pop_share = c.max_pop_share_unoccluded = -1;
    c.occlusion_known = true;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const FramePair& p = pairs[i];
        c.mean_persistence += p.persistence;
        c.mean_pop_share += p.pop_share;
        c.pops += p.pops;
        if (p.persistence < c.worst_persistence)
            c.worst_persistence = p.persistence, c.worst_persistence_pair = int(i);
        if (p.pop_share > c.max_pop_share)
            c.max_pop_share = p.pop_share, c.max_pop_share_pair = int(i);
        c.occlusion_known = c.occlusion_known && p.occlusion_known;
        c.occluded += p.occluded;
        c.disoccluded += p.disoccluded;
        c.pops_unoccluded += p.pops_unoccluded;
        c.mean_persistence_unoccluded += p.persistence_unoccluded;
        c.mean_pop_share_unoccluded += p.pop_share_unoccluded;
        if (p.persistence_unoccluded < c.worst_persistence_unoccluded)
            c.worst_persistence_unoccluded = p.persistence_unoccluded,
            c.worst_persistence_unoccluded_pair = int(i);
        if (p.pop_share_unoccluded > c.max_pop_share_unoccluded)
            c.max_pop_share_unoccluded = p.pop_share_unoccluded,
            c.max_pop_share_unoccluded_pair = int(i);
    }
    c.mean_persistence /= double(pairs.size());
    c.mean_pop_share /= double(pairs.size());
    c.mean_persistence_unoccluded /= double(pairs.size());
    c.mean_pop_share_unoccluded /= double(pairs.size());
    return c;
}

}  // namespace stipple::measure
