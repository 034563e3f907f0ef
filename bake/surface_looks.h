// The LOOK section's data (runtime/asset_format.h LooksHeader, docs/format.md): each baked
// point's material colour (thesis §8.6: dots may take the surface colour), the parts with
// their flags and base colours (§7.4 transparency by stipples), and crease edges (§7.1).
#pragma once
#include <cstdint>
#include <vector>

#include "bake/point_hierarchy.h"
#include "bake/raw_scene.h"

namespace stipple::bake {

struct BakedLooks {
    std::vector<uint8_t> point_colour;    // 4 per point (RGBA8, linear), or empty
    std::vector<uint8_t> part_colour;     // 4 per part (RGBA8, linear baseColorFactor)
    std::vector<uint8_t> part_flags;      // per part, format::kLookPart* bits
    std::vector<uint16_t> triangle_part;  // per triangle when part_flags is not empty
    std::vector<uint32_t> creases;        // 4 per crease: vertex a, vertex b, face 0, face 1
    bool empty() const { return point_colour.empty() && part_flags.empty() && creases.empty(); }
};

struct LooksConfig {
    bool creases = true;           // find crease edges
    float crease_degrees = 40.0f;  // faces meeting at more than this make a crease
};

// What the LOOK section says about `scene`: only what differs from one white opaque part
// without creases, so such a mesh gets an empty BakedLooks (and no LOOK section).
BakedLooks bake_looks(const RawScene& scene, const PointHierarchy& points,
                      const LooksConfig& config);

// Thesis §7.1: the edges of the mesh, welded by position like the silhouette edges
// (bake/silhouette_edges.h), whose two faces' normals differ by more than `degrees`.
// Boundary edges are not creases (silhouettes already draw boundaries). Same layout and
// order as silhouette_edges().
std::vector<uint32_t> crease_edges(const RawScene& scene, float degrees);

// Part `part`'s base colour at texture coordinates (u, v): the factor times the texture
// (bilinear, wrapped per its sampler; texels sRGB-decoded), linear RGBA in [0, 1]. A point's
// colour is this times the vertex colour (RawScene::colours) at the point.
void base_colour_at(const RawScene& scene, const RawPart& part, float u, float v, float out[4]);

}  // namespace stipple::bake
