// The depth pass's simplified occluder (OCCL section, docs/format.md; issue 9 item 5): the
// render mesh decimated by half-edge collapses only (OpenMesh's Decimater with a quadric
// priority, Garland & Heckbert), so no vertex moves and the occluder is an index buffer over a
// subset of the render mesh's own vertices, skinned for free by the runtime. Only the
// single-sided triangles take part (the depth pass draws the double-sided ones in full).
#pragma once
#include <cstdint>
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

struct BakedOccluder {
    std::vector<uint32_t> indices;  // 3 per triangle, render-mesh vertex indices
    // The largest one-sided gap between the occluder and the original surface, in the rest
    // pose and in sampled poses of every clip (object units): the depth pass pushes the
    // occluder back by this much, so no surface point is hidden by it.
    float deviation = 0.0f;
    bool empty() const { return indices.empty(); }
};

// Decimates the single-sided triangles of `scene` to about `ratio` (0 < ratio < 1) of their
// number. Empty when the mesh has no single-sided triangles.
BakedOccluder bake_occluder(const RawScene& scene, double ratio);

// The deviation of bake_occluder, the largest over the rest pose and the clips' poses
// (bake/scene_poser.h) of two one-sided gaps (bake/triangle_grid.h): how far a point of the
// original single-sided surface (vertices and triangle centres) lies behind the occluder, and
// how far a point of the occluder (7 per triangle) lies in front of the surface, each against
// the nearest triangle's outward normal. Exposed for tests.
float occluder_deviation(const RawScene& scene, const std::vector<uint32_t>& occluder);

}  // namespace stipple::bake
