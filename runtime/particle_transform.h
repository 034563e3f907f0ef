// Stage 3 of view-dependent particles, "transform/light particles" (GI'01 §2): each listed
// particle's screen position, depth, lit intensity, facing and an orientation vector projected
// into screen space, which stage 4 turns into a stroke. GI'01 used OpenGL feedback mode; here
// it runs on the CPU over the listed particles only (a few thousand a frame), which keeps the
// stage one loop over flat arrays and needs no GL round trip (docs/particles.md).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"
#include "runtime/memory.h"
#include "runtime/stipple_size.h"

namespace stipple {

// Where a stroke's direction comes from (GI'01 §1, "orientation fields"; thesis §2.5: stored
// on the surface so it turns with it).
enum class OrientationField : uint8_t {
    // A fixed random direction per particle in its host triangle's tangent frame
    // (runtime/stroke_anchor.h's surface_frame), drawn from the particle's id: it turns with
    // skinning and stays put from frame to frame (GI'01 §4 painterly).
    random = 0,
    // Perpendicular to the projected surface normal: strokes tangent to the outline (GI'01 §4
    // sketch, cartoon, charcoal).
    normal_tangent = 1,
    // Along the projected normal (across the outline).
    normal = 2,
    // The principal curvature direction the bake stored (CURV section, stipple-bake
    // --curvature; bake/principal_curvature.h): the direction of the larger |curvature| in
    // the host triangle's tangent frame, so it turns with skinning like `random`. Where the
    // asset has no CURV, or the point's confidence is below kCurvatureConfident (umbilic or
    // flat), the particle takes the random field's direction: an asset without CURV draws as
    // with `random`.
    curvature = 3,
};

// Confidence (format::kCurvatureConfidenceStep units) from which the curvature field uses
// the stored direction: (|k1| - |k2|) / (|k1| + |k2| + flat) >= 0.2 (docs/particles.md).
constexpr uint8_t kCurvatureConfident = 51;

// What the stage reads this frame: the posed mesh and the camera.
struct ParticleFrame {
    const PointsView* points = nullptr;
    const uint32_t* indices = nullptr;  // the mesh's triangles
    const float* positions = nullptr;   // posed vertices, 3 floats each
    const float* normals = nullptr;
    glm::mat4 view_projection = glm::mat4(1.0f);
    glm::vec3 eye = glm::vec3(0.0f);     // camera position, same space as the vertices
    int width = 0, height = 0;           // viewport, pixels
    float focal_px = 0.0f;               // pixels per unit at unit clip depth w
    const SizeParams* lights = nullptr;  // lighting() of runtime/stipple_size.h
    // Relevance radius per point this frame (Alg. 6.4's recomputed radii), or nullptr for the
    // baked radii.
    const float* radius = nullptr;
};

// The transformed particles, structure of arrays, `count` entries in list order.
struct ParticleSamples {
    uint32_t capacity = 0, count = 0;
    Buffer<uint32_t> id;
    Buffer<float> x, y, depth;  // pixels (origin top-left) and window depth in [0, 1]
    Buffer<float> radius_px;    // the relevance radius projected at the particle's depth
    Buffer<float> intensity;    // lighting in [0, 1]
    Buffer<float> facing;       // N.V: 1 facing the eye, 0 on the silhouette, < 0 away
    Buffer<float> angle;        // stroke direction on screen, radians (x right, y down)
    // How much of the orientation vector's length its projection keeps (1: it lies in the
    // image plane; 0: it points at the eye, where its screen angle is undefined).
    Buffer<float> foreshortening;
    Buffer<float> alpha;       // fade, from stage 1
    Buffer<uint8_t> unfolded;  // stage 1's questions: 1 if the particle is unfolded now
};

[[nodiscard]] bool particle_samples_init(ParticleSamples* s, uint32_t capacity);

// The random field's direction of particle `id`: an angle in [0, 2 pi) in the host's tangent
// frame, the same for every frame and every run.
float random_field_angle(uint32_t id);

// The curvature field's direction of particle `id` in the host's tangent frame: the stored
// principal direction where confident, else random_field_angle(id).
float curvature_field_angle(const PointsView& points, uint32_t id);

// Transforms particles ids[0 .. count): places each on its posed host triangle (Thesis Alg.
// 6.3), projects it and its orientation vector, lights it. Particles behind the camera get
// depth > 1 (stage 4 skips them). alpha[id] is copied through (nullptr: 1).
void transform_particles(const ParticleFrame& frame, const uint32_t* ids, uint32_t count,
                         const float* alpha, OrientationField field, ParticleSamples* out);

}  // namespace stipple
