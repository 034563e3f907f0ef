// The CPU point stages of a frame (place, relevance, size: Thesis Alg. 6.3, 6.4, 3.2) split
// over contiguous point ranges on the pipeline's thread pool (runtime/thread_pool.h), each
// range on the SIMD path chosen at run time (runtime/point_simd.h). A range writes only its
// own points' outputs and every point is computed by the same code wherever its range falls,
// so the results are byte-identical for any thread count. Each call returns when every range
// is done, so a stage sees all of the previous stage's outputs (relevance reads neighbours
// placed by other ranges).
#pragma once
#include <cstdint>

#include "runtime/asset.h"
#include "runtime/point_simd.h"
#include "runtime/stipple_size.h"
#include "runtime/thread_pool.h"

namespace stipple {

struct PointStageFrame {
    const PointsView* points = nullptr;
    const uint32_t* indices = nullptr;  // the mesh's triangles
    const float* vertex_positions = nullptr;
    const float* vertex_normals = nullptr;  // the posed mesh, 3 floats per vertex
    // The same as pair_vertices lays them out (runtime/point_simd.h), for AVX2 place; null:
    // place runs the scalar code.
    const float* vertex_pairs = nullptr;
    // The points' hosts as runtime/point_simd.h's point_hosts lays them out, for AVX2 place;
    // null: it reads the asset's host triangles and barycentrics.
    const PointHost* point_hosts = nullptr;
    // Each point's neighbours at a stride of 4 (runtime/point_simd.h's quad_neighbours), for
    // AVX2 relevance; null: it reads the asset's lists.
    const uint32_t* neighbour_quads = nullptr;
    const float* scale = nullptr;            // relevance_scale (point_placement.h)
    const float* fallback_radius = nullptr;  // radius of points without neighbours
    const SizeParams* params = nullptr;
    float* positions = nullptr;  // outputs: 3 floats per point
    float* normals = nullptr;
    float* radius = nullptr;
    float* size = nullptr;
};

struct Pipeline;  // runtime/frame_pipeline.h
// The pipeline's buffers for this frame's stages (the baked points' part of them).
PointStageFrame point_stage_frame(Pipeline* p);

// Fills the pipeline's vertex_pairs from the posed mesh (one pass over the vertices; the
// frame's point stages call it once, before the selection and any place).
void point_stage_pair_vertices(Pipeline* p);

// Below this many points per thread a stage runs on the caller alone.
inline constexpr uint32_t kMinPointsPerThread = 2048;

// Each stage over the points list[0 .. count), or the points 0 .. count - 1 when list is null.
void point_stage_place(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                       uint32_t count);
void point_stage_relevance(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                           uint32_t count);
void point_stage_size(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                      uint32_t count);
// Relevance and size in one pass over the points (issue 9 item 5, stage fusion: each point's
// position read once, its radius handed over in a register), with the bits of
// point_stage_relevance then point_stage_size. Only the AVX2 path has it: returns false, doing
// nothing, on the baseline path (the caller runs the two stages).
bool point_stage_relevance_size(ThreadPool* pool, const PointStageFrame& f, const uint32_t* list,
                                uint32_t count);

}  // namespace stipple
