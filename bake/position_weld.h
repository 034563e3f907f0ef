// Welding by exact position: vertices at the same position (-0 and +0 alike) are one vertex
// for connectivity, so seams split for UVs or normals do not cut the surface. Used by the
// silhouette edges, the normals' smoothing groups and the sample elimination's boundary.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bake/raw_scene.h"

namespace stipple::bake {

// Open-addressing hash tables (linear probing) for welding and edge matching: O(n), and the
// results do not depend on the table's order. The 64-bit finaliser of MurmurHash3:
inline uint64_t hash_mix(uint64_t x) {
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDull;
    x ^= x >> 33;
    x *= 0xC4CEB9FE1A85EC53ull;
    return x ^ (x >> 33);
}

// A power of two of at least 16 slots and twice `n`.
inline size_t hash_table_size(size_t n) {
    size_t size = 16;
    while (size < 2 * n) size *= 2;
    return size;
}

// Position class of every vertex, numbered in order of first occurrence. O(n).
std::vector<uint32_t> weld_by_position(const RawScene& scene);

}  // namespace stipple::bake
