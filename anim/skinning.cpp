// Linear blend skinning: glTF 2.0 §3.7.3 "Skins" / "Skinned Mesh Attributes"
// (skin matrix = sum over the 4 influences of weight * joint matrix), applied on the CPU.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "anim/anim.h"

namespace stipple::anim {

void skin_lbs(const SkinJob& job) {
    const uint32_t n = job.vertex_count;
    if (job.joint_count == 0) {
        // No joint to fall back on: the mesh stays in its bind pose.
        if (n == 0) return;
        std::memcpy(job.out_positions, job.in_positions, n * 3 * sizeof(float));
        std::memcpy(job.out_normals, job.in_normals, n * 3 * sizeof(float));
        return;
    }
    // Column-major joint matrices as flat floats: matrix j's column c, row r is at
    // skin[16 * j + 4 * c + r].
    const float* skin = &job.skin[0][0][0];
    const uint32_t joint_count = job.joint_count;
    // One uniform loop for every vertex (no branch on influence count, zero weights cost the
    // same as any other). The 16-float blend has a constant trip count and compiles to one SIMD
    // multiply-add per column and influence (GCC 12 -O3, plain SSE2); the position and normal
    // that follow are 3-wide and stay mostly scalar.
    for (uint32_t v = 0; v < n; ++v) {
        const uint16_t* jv = job.joints + 4 * static_cast<size_t>(v);
        const float* wv = job.weights + 4 * static_cast<size_t>(v);
        const float* m[4];
        for (int k = 0; k < 4; ++k) {
            // Out-of-range joint indices read joint 0: a bad asset can never read out of bounds.
            const uint32_t j = jv[k] < joint_count ? jv[k] : 0u;
            m[k] = skin + 16 * static_cast<size_t>(j);
        }
        float blended[16];
        for (int e = 0; e < 16; ++e) {
            blended[e] = wv[0] * m[0][e] + wv[1] * m[1][e] + wv[2] * m[2][e] + wv[3] * m[3][e];
        }

        const float* p = job.in_positions + 3 * static_cast<size_t>(v);
        const float* nrm = job.in_normals + 3 * static_cast<size_t>(v);
        float pos[4];
        float nor[4];
        for (int r = 0; r < 4; ++r) {
            pos[r] =
                blended[r] * p[0] + blended[4 + r] * p[1] + blended[8 + r] * p[2] + blended[12 + r];
            nor[r] = blended[r] * nrm[0] + blended[4 + r] * nrm[1] + blended[8 + r] * nrm[2];
        }
        // Renormalise the normal. Clamping the squared length (instead of branching) keeps a
        // degenerate zero normal at zero rather than NaN.
        const float len2 = nor[0] * nor[0] + nor[1] * nor[1] + nor[2] * nor[2];
        const float inv_len = 1.0f / std::sqrt(std::max(len2, 1e-30f));

        float* po = job.out_positions + 3 * static_cast<size_t>(v);
        float* no = job.out_normals + 3 * static_cast<size_t>(v);
        for (int r = 0; r < 3; ++r) {
            po[r] = pos[r];
            no[r] = nor[r] * inv_len;
        }
    }
}

}  // namespace stipple::anim
