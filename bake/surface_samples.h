// Samples uniform in area on the input surface, shared by the sample elimination
// (bake/sample_elimination.cpp) and its ghost samples across an open boundary
// (bake/sample_ghosts.h). Internal to those two.
#pragma once
#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bake/bake_random.h"
#include "bake/raw_scene.h"

namespace stipple::bake::elimination {

using Vec3 = OpenMesh::Vec3d;

// Normals more than ~120 degrees apart: the two sides of a thin sheet (an ear, a fin),
// which must each get their own points, so they neither repel nor are neighbours.
constexpr double kSameSideDot = -0.5;

struct Triangles {
    std::vector<Vec3> corner;  // 3 per triangle
    std::vector<Vec3> normal;  // unit, 0 if degenerate
    std::vector<double> area;
    double total = 0;
};

Triangles triangles_of(const RawScene& s);

// Samples on the input surface, structure of arrays.
struct Samples {
    std::vector<double> xyz;  // 3 per sample
    std::vector<uint32_t> host;
    std::vector<float> u, v;  // barycentric weights of the host's 1st and 2nd corner
    // 1: a sample of the surface continued across its boundary (add_ghosts), never a point.
    std::vector<uint8_t> ghost;
    uint32_t size() const { return uint32_t(host.size()); }
    uint32_t reals() const {
        return size() - uint32_t(std::count(ghost.begin(), ghost.end(), uint8_t(1)));
    }
    void reserve(size_t n) {
        xyz.reserve(n * 3);
        host.reserve(n);
        u.reserve(n);
        v.reserve(n);
        ghost.reserve(n);
    }
    void push(const Samples& from, uint32_t i) {
        xyz.insert(xyz.end(), from.xyz.begin() + std::ptrdiff_t(i) * 3,
                   from.xyz.begin() + std::ptrdiff_t(i) * 3 + 3);
        host.push_back(from.host[i]);
        u.push_back(from.u[i]);
        v.push_back(from.v[i]);
        ghost.push_back(from.ghost[i]);
    }
    // Keeps sample order[k] at k (order: a permutation of a subset).
    void select(const std::vector<uint32_t>& order) {
        Samples s;
        s.reserve(order.size());
        for (uint32_t i : order) s.push(*this, i);
        *this = std::move(s);
    }
};

// `count` samples uniform in area: triangle t gets floor or ceil of count * area_t / A
// (systematic sampling along the running sum of areas, one random offset), each uniform
// inside its triangle.
Samples sample_surface(const Triangles& t, uint64_t count, Rng* rng);

}  // namespace stipple::bake::elimination
