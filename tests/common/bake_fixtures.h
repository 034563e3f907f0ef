// Bake-side test fixtures shared by the section and stroke tests (tests/bake/): the bundled
// torus prepared as stipple-bake prepares a model, and a two-triangle square with a
// four-point hierarchy for encoding hand-made sections.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "bake/scene_orientation.h"
#include "bake/vertex_normals.h"

namespace stipple {
namespace test {

// assets/torus.obj (major radius 1 around +Y, minor radius 0.4) imported, oriented outward,
// with normals and a hierarchy of `point_count` points; built once per count and process.
struct Torus {
    bake::RawScene scene;
    bake::PointHierarchy points;
};

inline const Torus& prepared_torus(uint32_t point_count) {
    static std::map<uint32_t, std::unique_ptr<Torus>> built;
    std::unique_ptr<Torus>& slot = built[point_count];
    if (!slot) {
        slot = std::make_unique<Torus>();
        const bake::BakeError e =
            bake::import_scene(std::string(STIPPLE_SOURCE_DIR) + "/assets/torus.obj", &slot->scene);
        EXPECT_TRUE(e.ok()) << e.message;
        bake::orient_outward(&slot->scene);
        bake::assign_normals(bake::NormalConfig(), &slot->scene);
        bake::HierarchyConfig config;
        config.point_count = point_count;
        const bake::BakeError made =
            bake::build_point_hierarchy(slot->scene, config, &slot->points, nullptr);
        EXPECT_TRUE(made.ok()) << made.message;
    }
    return *slot;
}

// The unit square in z = 0 as two triangles, and four points on it (coarse to fine, each
// with one neighbour): the smallest scene and hierarchy an asset encodes.
inline void tiny_square(bake::RawScene* s, bake::PointHierarchy* p) {
    s->positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    s->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    s->indices = {0, 1, 2, 0, 2, 3};
    p->host_triangle = {0, 1, 1, 0};
    p->bary_u = {0.25f, 0.5f, 0.0f, 0.6f};
    p->bary_v = {0.25f, 0.5f, 1.0f, 0.2f};
    p->radius = {0.8f, 0.5f, 0.3f, 0.2f};
    p->neighbour_offsets = {0, 1, 2, 3, 4};
    p->neighbours = {1, 0, 0, 0};
}

}  // namespace test
}  // namespace stipple
