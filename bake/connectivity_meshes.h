// Meshes of hostile connectivity with a regular counterpart, for the bake's cost tests and
// benchmarks (docs/hierarchy.md, "Complexity") and `make-test-meshes`: every one lies in the
// unit disc / square of the z = 0 plane, normals left zero (the bake computes them).
#pragma once
#include <cmath>
#include <cstdint>

#include "bake/raw_scene.h"

namespace stipple::bake::meshes {

// n triangles around one centre vertex (a disc: the centre's valence is n).
inline RawScene fan(uint32_t n) {
    RawScene s;
    s.positions = {0, 0, 0};
    for (uint32_t a = 0; a < n; ++a) {
        const double t = 2 * M_PI * a / n;
        s.positions.insert(s.positions.end(), {float(std::cos(t)), float(std::sin(t)), 0});
    }
    for (uint32_t a = 0; a < n; ++a) s.indices.insert(s.indices.end(), {0, 1 + a, 1 + (a + 1) % n});
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// A regular grid of quads split in two, with n triangles (n even; as square as n allows).
inline RawScene grid(uint32_t n) {
    const uint32_t quads = n / 2;
    uint32_t cols = uint32_t(std::sqrt(double(quads)));
    while (cols > 1 && quads % cols) --cols;
    const uint32_t rows = quads / cols;
    RawScene s;
    for (uint32_t j = 0; j <= rows; ++j)
        for (uint32_t i = 0; i <= cols; ++i)
            s.positions.insert(s.positions.end(),
                               {float(2.0 * i / cols - 1), float(2.0 * j / rows - 1), 0});
    for (uint32_t j = 0; j < rows; ++j)
        for (uint32_t i = 0; i < cols; ++i) {
            const uint32_t a = j * (cols + 1) + i, b = a + 1, d = a + cols + 1, e = d + 1;
            s.indices.insert(s.indices.end(), {a, b, e, a, e, d});
        }
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// A non-manifold star: n triangles sharing the edge (0,0,-1)-(0,0,1), fanned around it
// like the pages of a book opened flat (each page a triangle to a point on the unit circle).
inline RawScene star(uint32_t n) {
    RawScene s;
    s.positions = {0, 0, -1, 0, 0, 1};
    for (uint32_t a = 0; a < n; ++a) {
        const double t = 2 * M_PI * a / n;
        s.positions.insert(s.positions.end(), {float(std::cos(t)), float(std::sin(t)), 0});
        s.indices.insert(s.indices.end(), {0, 1, 2 + a});
    }
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

// The fan as a triangle soup: every triangle has its own 3 vertices, so the centre is
// duplicated n times (welding by position joins them again).
inline RawScene duplicates(uint32_t n) {
    const RawScene f = fan(n);
    RawScene s;
    for (uint32_t v : f.indices) {
        s.positions.insert(s.positions.end(), &f.positions[size_t(v) * 3],
                           &f.positions[size_t(v) * 3] + 3);
        s.indices.push_back(uint32_t(s.indices.size()));
    }
    s.normals.assign(s.positions.size(), 0.0f);
    return s;
}

}  // namespace stipple::bake::meshes
