// The PTRE section: the particle tree of view-dependent particles (GI'01 §3;
// runtime/particle_tree.h, docs/particles.md), one parent per point of the hierarchy,
// validated in place: the count is the hierarchy's, and every parent precedes its child
// (coarse to fine), so the runtime can walk it without further checks.
#include "runtime/asset_parse.h"

namespace stipple::detail {

Status parse_particles(Reader r, Asset* a) {
    const uint32_t count = r.u32();
    if (!r.ok)
        return load_failure(LoadError::malformed_section, "PTRE: %zu bytes, shorter than its count",
                            r.size);
    if (count != a->points.point_count)
        return load_failure(LoadError::malformed_section,
                            "PTRE: %u parents for %u points of the hierarchy", count,
                            a->points.point_count);
    const uint32_t* parent = r.take<uint32_t>(count);
    if (!parent || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "PTRE: %u parents do not fill its %zu bytes", count, r.size);
    for (uint32_t i = 0; i < count; ++i)
        if (parent[i] != format::kNoParticleParent && parent[i] >= i)
            return load_failure(LoadError::out_of_range,
                                "PTRE: point %u's parent %u does not precede it", i, parent[i]);
    a->particle_parent = parent;
    return {};
}

}  // namespace stipple::detail
