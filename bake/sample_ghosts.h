// Ghost samples for open surfaces (bake/sample_elimination.h): the surface continued
// across its boundary by its mirror image, sampled like the surface, so that samples near
// the boundary have the neighbours they would have if the surface went on. Internal to the
// sample elimination.
#pragma once
#include <cstdint>
#include <vector>

#include "bake/surface_samples.h"

namespace stipple::bake::elimination {

// Open surfaces. Where a surface ends, its samples have fewer neighbours, weigh less and
// outlive the others: every prefix is denser along the boundary (a plane at 20k points:
// 1.5-1.7x the mean density within half a spacing of its border, docs/hierarchy.md). Yuksel
// 2015 notes this for bounded domains. Here the surface is continued across its boundary,
// `width` deep, by its mirror image, sampled independently: "ghost" samples, eliminated like
// the others, that never become points. The samples near a boundary then have the
// neighbours they would have if the surface went on. (Mirroring the real samples instead,
// in their weights, is not enough: a sample sees its neighbours' images but not its own, so
// the samples on the edge, whose images are themselves, count double for their neighbours
// and crowd the edge (4.8x within 1/8 spacing); counting its own image too empties a band of
// a quarter spacing along the edge. Measured, docs/hierarchy.md.)
//
// The boundary: the edges of one face once the input is welded by exact position (as
// bake/silhouette_edges.h does, so UV and normal seams are not edges of one face). Each has the
// unit direction in its face's plane, perpendicular to the edge, pointing away from the
// face: the normal of the plane the surface near it is mirrored across. Degenerate faces'
// edges are left out (no direction; they have no samples).
struct Boundary {
    std::vector<Vec3> a, b, out, face_normal;
    std::vector<uint32_t> face;
    double length = 0;
    // Per triangle, the triangles across its edges (kNoFace: none), 3 each; only if there
    // is a boundary.
    std::vector<uint32_t> across;
    uint32_t size() const { return uint32_t(a.size()); }
};

Boundary boundary_of(const RawScene& s, const Triangles& t);

// Appends to *s the ghosts of the boundary: samples at `density` per unit area, uniform on
// the triangles within `width` of a boundary edge (the same systematic sampling as the
// surface's, with their own random numbers), each mirrored across the plane of its nearest
// boundary edge. Nearest over the surface: each triangle near the boundary gets the edge
// nearest to its centroid, passed on from triangle to neighbouring triangle (nearest first,
// Dijkstra), so that another part that passes near an edge is not mirrored; a sample takes
// the nearest of its triangle's, its neighbours' and its own boundary edges. Edges count only
// on the sample's side of the surface (normals less than ~120 degrees apart) and within 45
// degrees of the edge's face's inward direction. A ghost is dropped where a real sample lies
// beyond the plane nearer to it than the plane (give or take the spacing of the samples
// tested): there the surface goes on (a crack, a part that meets another, a concave corner,
// the far side of a hole), and the mirror image would lie on it.
void add_ghosts(const Triangles& t, const Boundary& edges, double density, double width, Rng* rng,
                Samples* s);

// How deep the surface is continued across its boundary: 2 spacings of the 512-point prefix
// (or of all the points, if fewer), at most a strip of half the surface's area. The ghosts'
// own boundary is as crowded as any and must stay out of the real samples' reach at every
// prefix that matters: a prefix is even at the boundary once the width is about half its
// spacing or more (square, 0-0.5 spacing band, 60 / 125 / 250 / 500 points, width in
// spacings of 512: 1/2 -> 0.63 / 0.66 / 0.85 / 1.00, 1 -> 0.88 / 1.01 / 1.07 / 1.00,
// 2 -> 1.13 / 0.97 / 1.02 / 1.03). The ghosts cost (boundary length x width) / area more
// samples, fewer where they are hidden: 34 % on SimpleSkin (a 1 x 2 plane), 5 % on
// teapot.obj (its openings), 2 % on the bunny (holes in its base).
double ghost_width(double area, double boundary_length, uint32_t points);

}  // namespace stipple::bake::elimination
