// The k nearest points within a radius, through a kd-tree: for the places where a uniform grid
// of the surface's spacing (bake/point_grid.h) holds far more points per cell than the
// spacing promises, because much surface is packed into little volume (the pages of a
// non-manifold star around their shared edge: docs/hierarchy.md, "Complexity"). A query
// costs O(log n + k) whatever the crowding, so the bake's neighbour lists stay bounded by k
// there. Header-only; deterministic (ties break by index).
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace stipple::bake {

// Grid cells hold more candidates than this around a query: the place is crowded, and the
// neighbour searches of the bake take the k nearest there instead of every point within
// the radius. On a surface the 27 cells around a point hold ~25-115 (measured on the bundled
// assets' elimination samples: at most 114), so the bakes of ordinary meshes do not change.
constexpr size_t kCrowdedCandidates = 256;

class NearestPoints {
  public:
    // `xyz`: 3 doubles per point, kept by pointer (it must outlive the queries).
    void build(const double* xyz, uint32_t count) {
        xyz_ = xyz;
        index_.resize(count);
        for (uint32_t i = 0; i < count; ++i) index_[i] = i;
        nodes_.clear();
        if (count > 0) (void)split(0, count);
        // The points again in tree order: a leaf reads neighbouring memory.
        sorted_.resize(size_t(count) * 3);
        for (uint32_t p = 0; p < count; ++p)
            for (int k = 0; k < 3; ++k) sorted_[size_t(p) * 3 + size_t(k)] = coord(index_[p], k);
        marks_.clear();
        parent_.clear();
        leaf_of_.clear();
    }

    // Marks point j (once): nearest_marked() sees only marked points, and skips subtrees
    // without one (a dynamic set, such as the points placed so far, in O(log n) per mark).
    void mark(uint32_t j) {
        if (marks_.empty()) {
            marks_.assign(nodes_.size(), 0);
            parent_.assign(nodes_.size(), 0);
            leaf_of_.assign(index_.size(), 0);
            for (uint32_t n = 0; n < nodes_.size(); ++n) {
                if (nodes_[n].left != 0) {
                    parent_[nodes_[n].left] = parent_[nodes_[n].right] = n;
                } else {
                    for (uint32_t p = nodes_[n].begin; p < nodes_[n].end; ++p)
                        leaf_of_[index_[p]] = n;
                }
            }
        }
        for (uint32_t n = leaf_of_[j];; n = parent_[n]) {
            ++marks_[n];
            if (n == 0) break;
        }
    }

    // nearest() among the marked points only.
    template <class Keep>
    void nearest_marked(const double q[3], uint32_t k, double radius2, Keep&& keep,
                        std::vector<std::pair<double, uint32_t>>* out) const {
        out->clear();
        if (marks_.empty() || k == 0) return;
        double offset[3] = {0, 0, 0};
        search(0, q, k, radius2, keep, 0.0, offset, out, true);
        std::sort_heap(out->begin(), out->end());
    }

    // Appends to *out (cleared first) the up to k points j nearest to q with squared distance
    // under radius2 and keep(j) true, as (squared distance, j) sorted ascending.
    template <class Keep>
    void nearest(const double q[3], uint32_t k, double radius2, Keep&& keep,
                 std::vector<std::pair<double, uint32_t>>* out) const {
        out->clear();
        if (nodes_.empty() || k == 0) return;
        double offset[3] = {0, 0, 0};
        search(0, q, k, radius2, keep, 0.0, offset, out);
        std::sort_heap(out->begin(), out->end());
    }

    // The points with squared distance to q under radius2, counted up to cap + 1 (the
    // search stops there: O(log n + cap)).
    uint32_t count_within(const double q[3], double radius2, uint32_t cap) const {
        uint32_t count = 0;
        auto counter = [&](uint32_t) { return ++count > cap; };
        if (!nodes_.empty()) (void)find_any(0, q, radius2, counter);
        return count;
    }

    // Is there a point j with squared distance to q under radius2 and keep(j) true?
    template <class Keep>
    bool any(const double q[3], double radius2, Keep&& keep) const {
        return !nodes_.empty() && find_any(0, q, radius2, keep);
    }

  private:
    struct Node {
        uint32_t begin, end;   // range of index_
        uint32_t left, right;  // children; left == 0: a leaf
        int axis;
        double at;  // split plane: left holds coordinates <= at, right >= at
    };
    static constexpr uint32_t kLeaf = 12;

    double coord(uint32_t i, int k) const { return xyz_[size_t(i) * 3 + size_t(k)]; }

    // Splits at the median of the widest axis; returns the node's index.
    uint32_t split(uint32_t begin, uint32_t end) {
        const uint32_t node = uint32_t(nodes_.size());
        nodes_.push_back(Node{begin, end, 0, 0, 0, 0.0});
        if (end - begin <= kLeaf) return node;
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        for (uint32_t p = begin; p < end; ++p)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], coord(index_[p], k));
                hi[k] = std::max(hi[k], coord(index_[p], k));
            }
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
        if (!(hi[axis] > lo[axis])) return node;  // all at one place: a leaf
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(index_.begin() + begin, index_.begin() + mid, index_.begin() + end,
                         [&](uint32_t a, uint32_t b) {
                             const double x = coord(a, axis), y = coord(b, axis);
                             return x < y || (x == y && a < b);
                         });
        const double at = coord(index_[mid], axis);
        const uint32_t left = split(begin, mid + 1);
        const uint32_t right = split(mid + 1, end);
        nodes_[node].left = left;
        nodes_[node].right = right;
        nodes_[node].axis = axis;
        nodes_[node].at = at;
        return node;
    }

    // bound: squared distance from q to the node's box (Arya and Mount's incremental
    // distance; offset[axis]: q's offset from the box along each axis).
    template <class Keep>
    void search(uint32_t n, const double q[3], uint32_t k, double radius2, Keep& keep, double bound,
                double offset[3], std::vector<std::pair<double, uint32_t>>* out,
                bool marked_only = false) const {
        if (marked_only && marks_[n] == 0) return;
        const Node& node = nodes_[n];
        if (node.left == 0) {
            for (uint32_t p = node.begin; p < node.end; ++p) {
                const uint32_t j = index_[p];
                double d2 = 0;
                for (int c = 0; c < 3; ++c) {
                    const double e = sorted_[size_t(p) * 3 + size_t(c)] - q[c];
                    d2 += e * e;
                }
                const std::pair<double, uint32_t> entry{d2, j};
                if (d2 >= radius2 || (out->size() == k && !(entry < out->front()))) continue;
                if (!keep(j)) continue;
                if (out->size() == k) {
                    std::pop_heap(out->begin(), out->end());
                    out->pop_back();
                }
                out->push_back(entry);
                std::push_heap(out->begin(), out->end());
            }
            return;
        }
        const double delta = q[node.axis] - node.at;
        const uint32_t near = delta <= 0 ? node.left : node.right;
        const uint32_t far = delta <= 0 ? node.right : node.left;
        search(near, q, k, radius2, keep, bound, offset, out, marked_only);
        const double old = offset[node.axis];
        const double far_bound = bound - old * old + delta * delta;
        if (far_bound < radius2 && (out->size() < k || far_bound <= out->front().first)) {
            offset[node.axis] = delta;
            search(far, q, k, radius2, keep, far_bound, offset, out, marked_only);
            offset[node.axis] = old;
        }
    }

    template <class Keep>
    bool find_any(uint32_t n, const double q[3], double radius2, Keep& keep) const {
        const Node& node = nodes_[n];
        if (node.left == 0) {
            for (uint32_t p = node.begin; p < node.end; ++p) {
                const uint32_t j = index_[p];
                double d2 = 0;
                for (int c = 0; c < 3; ++c) {
                    const double e = sorted_[size_t(p) * 3 + size_t(c)] - q[c];
                    d2 += e * e;
                }
                if (d2 < radius2 && keep(j)) return true;
            }
            return false;
        }
        const double delta = q[node.axis] - node.at;
        const uint32_t near = delta <= 0 ? node.left : node.right;
        const uint32_t far = delta <= 0 ? node.right : node.left;
        return find_any(near, q, radius2, keep) ||
               (delta * delta < radius2 && find_any(far, q, radius2, keep));
    }

    const double* xyz_ = nullptr;
    std::vector<uint32_t> index_;
    std::vector<double> sorted_;  // the points' coordinates in index_ order
    std::vector<Node> nodes_;
    std::vector<uint32_t> marks_;    // per node: marked points under it (empty: none yet)
    std::vector<uint32_t> parent_;   // per node (with marks_)
    std::vector<uint32_t> leaf_of_;  // per point (with marks_)
};

}  // namespace stipple::bake
