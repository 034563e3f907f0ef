// SIMD chosen at run time for the CPU point stages (issue 9 item 5). When the CPU has AVX2
// (cpuid, once), place (Alg. 6.3), relevance (Alg. 6.4) and size (Alg. 3.2) run the kernels of
// runtime/point_simd_avx2.cpp (compiled for AVX2 by a target pragma, with -ffp-contract=off
// and no FMA): size and relevance (its area measure) 8 points per step, each point's data
// loaded on its own and transposed into lanes (AVX2 gathers measured slower than those loads);
// place one point per step with its position and normal in the lanes of one vector; where the CPU
// also has AVX-512 (F, VL, DQ, BW), relevance and size fused run 16 points per step
// (runtime/point_simd_avx512.cpp). Otherwise the
// baseline: the scalar code of point_placement.cpp / stipple_size.cpp (SSE2 scalar on x86-64; NEON
// targets keep it too). Each kernel does the same IEEE operations in the same order as the scalar
// code (no FMA, no reciprocal approximations, the same NaN behaviour in comparisons and clamps), so
// both paths give the same bits (tests/runtime/test_point_stages.cpp checks it).
#pragma once
#include <cstddef>
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/stipple_size.h"

// 1 where the AVX2 kernels are compiled (x86 with GCC or clang, whose target pragmas and
// intrinsics they use), else 0: their entry points are then stubs never called.
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define STIPPLE_AVX2_KERNELS 1
#else
#define STIPPLE_AVX2_KERNELS 0
#endif

namespace stipple {

// Ordered by width: avx512 runs every AVX2 kernel, and the fused relevance + size 16 points a
// step (runtime/point_simd_avx512.cpp) where the CPU has AVX-512 F, VL, DQ and BW.
enum class PointSimd : uint8_t { baseline, avx2, avx512 };

// Whether `simd` runs the AVX2 kernels (avx2 and avx512 both do).
inline bool has_avx2(PointSimd simd) {
    return simd != PointSimd::baseline;
}

// The AVX2 kernels load a point's (or vertex's) x, y, z as one 16-byte load, so the arrays of 3
// floats each they read by index (point positions and normals, posed vertex positions) must
// have this many floats readable past their last entry; the pipeline allocates them so.
inline constexpr size_t kSimdPadFloats = 1;

// The widest path this CPU runs (cpuid once), capped by the environment's STIPPLE_SIMD
// (baseline or avx2; read once, at the first call).
PointSimd point_simd_detected();

// The path the point stages use now: point_simd_detected() unless point_simd_force chose
// another.
PointSimd point_simd();

// Forces a path for the whole process (tests and benches compare them); a path wider than
// point_simd_detected() falls back to that one. Call between frames, not while stages run.
void point_simd_force(PointSimd simd);

const char* point_simd_name(PointSimd simd);  // "baseline", "avx2", "avx512"

// The posed vertices as place's AVX2 kernel reads them: vertex v's position and normal in
// out[8 v .. 8 v + 8) as x y z |n| nx ny nz 1/|n| (one 32-byte load per host corner instead of
// two 12-byte loads from two arrays). Plain copies: the bits of positions and normals; |n| with
// glm::length's bits and 1/|n| (0 where |n| is not > 0) once per vertex for the clusters' normal
// bounds (runtime/normal_bounds.h), which visit each vertex from several clusters. Place blends
// all 8 lanes and keeps 3 of each half.
void pair_vertices(uint32_t count, const float* positions, const float* normals, float* out);
// The same bits, 4 vertices a step (only when point_simd() is avx2).
void pair_vertices_avx2(uint32_t count, const float* positions, const float* normals, float* out);

// Place's AVX2 input per baked point, 16 bytes in one line: its host triangle's vertex
// indices (resolved at load, 21 bits each) and its barycentrics, instead of the host
// triangle's index (then its three indices, a dependent load) and two more arrays.
struct PointHost {
    uint64_t corners;  // a | b << 21 | c << 42
    float u, v;
};
constexpr uint32_t kPointHostMaxVertices = 1u << 21;

// out[i] for every point; false (out not written) when the mesh has more vertices than
// kPointHostMaxVertices.
bool point_hosts(const PointsView& points, const uint32_t* indices, uint32_t vertex_count,
                 PointHost* out);

// Relevance's AVX2 input: each point's relevant neighbours at a fixed stride of 4,
// out[4 i .. 4 i + 4), a list shorter than 4 padded with i itself (its term is p - p = +0, which
// leaves every sum's bits as they are), each stored as its float offset in the positions, 3 times
// its index (the kernel's loads then need no multiply: 8% off relevance + size). One 16-byte
// record per point instead of two offsets and a list elsewhere. Returns false (out partly
// written) when a list holds more than 4 or there are more than kQuadMaxPoints points.
constexpr uint32_t kQuadMaxPoints = 1u << 30;
bool quad_neighbours(const PointsView& points, uint32_t* out);

// The AVX2 kernels over the points list[begin .. end) (list null: the points begin .. end);
// each writes only those points' outputs. Only call them when has_avx2(point_simd()). Place
// reads the vertices as pair_vertices lays them out, and the points' hosts from `hosts`
// (point_hosts) when it is not null.
void place_points_avx2(const PointsView& points, const uint32_t* indices, const PointHost* hosts,
                       const float* pairs, const uint32_t* list, uint32_t begin, uint32_t end,
                       float* out_positions, float* out_normals);
// Relevance reads the neighbours from `quads` (quad_neighbours) when it is not null.
void recompute_relevance_avx2(const PointsView& points, const uint32_t* quads,
                              const float* point_positions, const float* scale,
                              const float* fallback_radius, const uint32_t* list, uint32_t begin,
                              uint32_t end, float* out_radius);
void size_stipples_avx2(const SizeFrame& frame, const float* positions, const float* normals,
                        const float* radius, const uint32_t* list, uint32_t begin, uint32_t end,
                        float* out_size);
// Relevance and then size over the same points in one pass (issue 9 item 5, stage fusion):
// each point's position is read once and its radius reaches size in a register; writes
// out_radius and out_size with the bits of the two kernels above run one after the other.
void relevance_size_avx2(const PointsView& points, const uint32_t* quads, const SizeFrame& frame,
                         const float* positions, const float* normals, const float* scale,
                         const float* fallback_radius, const uint32_t* list, uint32_t begin,
                         uint32_t end, float* out_radius, float* out_size);

// relevance_size_avx2 16 points a step in AVX-512 lanes (runtime/point_simd_avx512.cpp), the
// same bits; only when point_simd() is avx512.
void relevance_size_avx512(const PointsView& points, const uint32_t* quads, const SizeFrame& frame,
                           const float* positions, const float* normals, const float* scale,
                           const float* fallback_radius, const uint32_t* list, uint32_t begin,
                           uint32_t end, float* out_radius, float* out_size);

// point_clusters_select.cpp's per-triangle squared stretches for triangles 0 .. count - 1,
// 8 at a time; returns how many it did (the caller runs the scalar code on the rest).
uint32_t triangle_stretch_avx2(const uint32_t* indices, const float* posed, const float* gram,
                               uint32_t count, float* area_ratio, float* edge_ratio);

// silhouette.cpp's triangle_facing for triangles 0 .. count - 1, 8 at a time (the same flags);
// returns how many it did (the caller runs the scalar code on the rest). `positions` must have
// kSimdPadFloats floats readable past its last vertex.
uint32_t triangle_facing_avx2(const uint32_t* indices, const float* positions, const float* eye,
                              uint32_t count, uint8_t* front);

// refinement_sigma.cpp's sigma2 into sigma[triangles[j]] for j in 0 .. count - 1, 4 at a time
// in double lanes (the same bits); returns how many it did (the caller runs the scalar code on
// the rest). Reads exactly 3 floats per vertex and per Gram entry: no padding needed.
uint32_t triangle_sigma2_avx2(const uint32_t* triangles, uint32_t count, const uint32_t* indices,
                              const float* posed, const float* bind_gram, float* sigma);

}  // namespace stipple
