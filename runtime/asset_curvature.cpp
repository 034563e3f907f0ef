// The CURV section: each point's principal curvature direction and its confidence, the
// curvature orientation field of view-dependent particles (GI'01 §1 "orientation fields";
// runtime/particle_transform.h, docs/particles.md). Validated in place: the count is the
// hierarchy's and the two byte arrays fill the section exactly. Every byte value is a valid
// angle (mod pi) and a valid confidence, so nothing else needs checking.
#include "runtime/asset_parse.h"

namespace stipple::detail {

Status parse_curvature(Reader r, Asset* a) {
    const uint32_t count = r.u32();
    if (!r.ok)
        return load_failure(LoadError::malformed_section, "CURV: %zu bytes, shorter than its count",
                            r.size);
    if (count != a->points.point_count)
        return load_failure(LoadError::malformed_section,
                            "CURV: %u directions for %u points of the hierarchy", count,
                            a->points.point_count);
    const uint8_t* angle = r.take<uint8_t>(count);
    const uint8_t* confidence = r.take<uint8_t>(count);
    if (!angle || !confidence || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "CURV: %u directions do not fill its %zu bytes", count, r.size);
    a->points.curvature_angle = angle;
    a->points.curvature_confidence = confidence;
    a->points.curvature_count = count;
    return {};
}

}  // namespace stipple::detail
