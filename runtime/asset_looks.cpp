// The LOOK section: per-point material colour, per-triangle parts with their flags and base
// colours, and crease edges (thesis §7.1 crease lines, §7.4 transparency, §8.6 colour),
// validated in place and exposed as LooksView. Layout: runtime/asset_format.h LooksHeader.
#include <cstring>

#include "runtime/asset_limits.h"
#include "runtime/asset_parse.h"

namespace stipple::detail {

namespace {

// Bytes the header's counts need, in 64 bits (no count can overflow it).
uint64_t looks_bytes(const format::LooksHeader& h) {
    return sizeof(format::LooksHeader) + uint64_t(h.crease_count) * 16 +
           uint64_t(h.point_colour_count) * 4 + uint64_t(h.part_count) * 5 +
           uint64_t(h.triangle_part_count) * 2;
}

// The counts: within the limits, fitting the section exactly, agreeing with MESH and PNTQ.
Status check_header(const format::LooksHeader& h, size_t size, const Asset& a) {
    if (h.reserved != 0) return load_failure(LoadError::bad_value, "LOOK: reserved bytes not 0");
    Status st = check_limit("LOOK", "part count", h.part_count, limits::kMaxParts);
    if (!st.ok()) return st;
    if (looks_bytes(h) != size)
        return load_failure(LoadError::malformed_section,
                            "LOOK: size %zu does not match %u point colours, %u parts, %u "
                            "triangle parts, %u creases",
                            size, h.point_colour_count, h.part_count, h.triangle_part_count,
                            h.crease_count);
    if (h.point_colour_count == 0 && h.part_count == 0 && h.crease_count == 0)
        return load_failure(LoadError::zero_count, "LOOK: no colours, parts or creases");
    if (h.point_colour_count != 0 && h.point_colour_count != a.points.point_count)
        return load_failure(LoadError::malformed_section,
                            "LOOK: %u point colours for %u points (must be 0 or equal)",
                            h.point_colour_count, a.points.point_count);
    if ((h.part_count == 0) != (h.triangle_part_count == 0) ||
        (h.part_count != 0 && h.triangle_part_count != a.mesh.triangle_count))
        return load_failure(LoadError::malformed_section,
                            "LOOK: %u triangle parts for %u parts and %u triangles (must be 0 "
                            "with 0 parts, else the triangle count)",
                            h.triangle_part_count, h.part_count, a.mesh.triangle_count);
    return {};
}

// Crease i: vertices inside the mesh, two distinct faces inside it.
Status check_crease(const uint32_t* c, uint32_t i, const MeshView& mesh) {
    if (c[0] >= mesh.vertex_count || c[1] >= mesh.vertex_count)
        return load_failure(LoadError::out_of_range,
                            "LOOK: crease %u vertices (%u, %u) past vertex count %u", i, c[0], c[1],
                            mesh.vertex_count);
    if (c[2] >= mesh.triangle_count || c[3] >= mesh.triangle_count || c[2] == c[3])
        return load_failure(LoadError::out_of_range,
                            "LOOK: crease %u faces (%u, %u) not two triangles of %u", i, c[2], c[3],
                            mesh.triangle_count);
    return {};
}

}  // namespace

Status parse_looks(Reader r, Asset* a) {
    const format::LooksHeader* h = r.take<format::LooksHeader>(1);
    if (!h)
        return load_failure(LoadError::malformed_section,
                            "LOOK: %zu bytes, shorter than its header", r.size);
    Status st = check_header(*h, r.size, *a);
    if (!st.ok()) return st;
    // Every count now fits the section's bytes: the takes below cannot fail.
    const uint32_t* creases = r.take<uint32_t>(size_t(h->crease_count) * 4);
    const uint8_t* point_colour = r.take<uint8_t>(size_t(h->point_colour_count) * 4);
    const uint8_t* part_colour = r.take<uint8_t>(size_t(h->part_count) * 4);
    const uint16_t* triangle_part = r.take<uint16_t>(h->triangle_part_count);
    const uint8_t* part_flags = r.take<uint8_t>(h->part_count);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "LOOK: arrays do not fill the section");
    for (uint32_t i = 0; i < h->crease_count; ++i) {
        st = check_crease(creases + size_t(i) * 4, i, a->mesh);
        if (!st.ok()) return st;
    }
    for (uint32_t t = 0; t < h->triangle_part_count; ++t)
        if (triangle_part[t] >= h->part_count)
            return load_failure(LoadError::out_of_range,
                                "LOOK: triangle %u part %u >= part count %u", t,
                                unsigned(triangle_part[t]), h->part_count);
    for (uint32_t p = 0; p < h->part_count; ++p)
        if (part_flags[p] & ~format::kLookPartKnownFlags)
            return load_failure(LoadError::bad_value, "LOOK: part %u flags 0x%02x unknown", p,
                                unsigned(part_flags[p]));
    LooksView& v = a->looks;
    v.point_colour = h->point_colour_count ? point_colour : nullptr;
    v.part_count = h->part_count;
    v.triangle_part = h->part_count ? triangle_part : nullptr;
    v.part_flags = h->part_count ? part_flags : nullptr;
    v.part_colour = h->part_count ? part_colour : nullptr;
    v.crease_count = h->crease_count;
    v.creases = h->crease_count ? creases : nullptr;
    return {};
}

}  // namespace stipple::detail
