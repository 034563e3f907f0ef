// A uniform grid over points in 3D for neighbour queries: points sorted by cell, and an
// open-addressing table from cell to its run of points. Header-only and dependency-free, so
// the bake and stipple-inspect share it. Deterministic: the visiting order depends only on
// the positions and the cell size.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace stipple::bake {

class PointGrid {
  public:
    // `xyz` holds 3 doubles per point; visit() reports indices into it. cell > 0.
    void build(const double* xyz, uint32_t count, double cell) {
        cell_ = cell;
        for (int k = 0; k < 3; ++k) lo_[k] = 1e300;
        for (uint32_t i = 0; i < count; ++i)
            for (int k = 0; k < 3; ++k) lo_[k] = std::min(lo_[k], xyz[size_t(i) * 3 + size_t(k)]);
        std::vector<std::pair<uint64_t, uint32_t>> keyed(count);
        for (uint32_t i = 0; i < count; ++i) keyed[i] = {key_of(xyz + size_t(i) * 3), i};
        std::sort(keyed.begin(), keyed.end());
        order_.resize(count);
        for (uint32_t i = 0; i < count; ++i) order_[i] = keyed[i].second;
        size_t cells = 0;
        for (uint32_t i = 0; i < count; ++i)
            cells += (i == 0 || keyed[i].first != keyed[i - 1].first);
        size_t size = 16;
        while (size < 2 * cells) size *= 2;
        mask_ = size - 1;
        table_.assign(size, Slot());
        for (uint32_t i = 0; i < count;) {
            uint32_t j = i;
            while (j < count && keyed[j].first == keyed[i].first) ++j;
            size_t h = hash(keyed[i].first);
            while (table_[h].count) h = (h + 1) & mask_;
            table_[h] = Slot{keyed[i].first, i, j - i};
            i = j;
        }
    }

    double cell() const { return cell_; }
    // The points in the order visit() reports them cell by cell (sorted by cell, then index).
    const std::vector<uint32_t>& order() const { return order_; }
    // Cell coordinate of x along axis k (0, 1, 2): points of one cell are visited alike.
    int64_t cell_of(double x, int k) const { return coord(x, k); }

    // Calls f(index) for every point in the cells within `ring` cells of q's cell.
    template <class F>
    void visit(const double q[3], int ring, F&& f) const {
        if (table_.empty()) return;
        int64_t c[3];
        for (int k = 0; k < 3; ++k) c[k] = coord(q[k], k);
        for (int64_t x = c[0] - ring; x <= c[0] + ring; ++x)
            for (int64_t y = c[1] - ring; y <= c[1] + ring; ++y)
                for (int64_t z = c[2] - ring; z <= c[2] + ring; ++z) {
                    if (x < 0 || y < 0 || z < 0 || x > kMax || y > kMax || z > kMax) continue;
                    const Slot* s = find(pack(x, y, z));
                    if (!s) continue;
                    for (uint32_t i = s->begin; i < s->begin + s->count; ++i) f(order_[i]);
                }
    }

  private:
    struct Slot {
        uint64_t key = 0;
        uint32_t begin = 0, count = 0;  // count 0: empty slot
    };
    static constexpr int64_t kMax = (int64_t(1) << 21) - 1;

    int64_t coord(double x, int k) const {
        const double c = std::floor((x - lo_[k]) / cell_);
        return c < 0 ? 0 : (c > double(kMax) ? kMax : int64_t(c));
    }
    static uint64_t pack(int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x) << 42) | (uint64_t(y) << 21) | uint64_t(z);
    }
    uint64_t key_of(const double* p) const {
        return pack(coord(p[0], 0), coord(p[1], 1), coord(p[2], 2));
    }
    // The product's high half folded in: alone, its bits 20+ ignored x (key bits 42+) for tables
    // under 2^22 slots, and a flat mesh's cells chained by row (relax on a fan: 78 % of the time).
    size_t hash(uint64_t key) const {
        const uint64_t h = key * 0x9E3779B97F4A7C15ull;
        return size_t(h ^ (h >> 32)) & mask_;
    }
    const Slot* find(uint64_t key) const {
        for (size_t h = hash(key);; h = (h + 1) & mask_) {
            if (!table_[h].count) return nullptr;
            if (table_[h].key == key) return &table_[h];
        }
    }

    double cell_ = 1, lo_[3] = {0, 0, 0};
    std::vector<uint32_t> order_;
    std::vector<Slot> table_;
    size_t mask_ = 0;
};

}  // namespace stipple::bake
