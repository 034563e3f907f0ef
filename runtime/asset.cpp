#include "runtime/asset.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

#include "anim/finite.h"
#include "runtime/asset_format.h"
#include "runtime/point_codec.h"

namespace stipple {

namespace {

// Bounds-checked cursor over one section. Every take() checks the remaining size first,
// so a lying count can only produce an error, never an out-of-bounds view.
struct Reader {
    const uint8_t* data;
    size_t size;
    size_t at = 0;
    bool ok = true;

    template <typename T>
    const T* take(size_t count) {
        size_t align = alignof(T);
        size_t start = (at + align - 1) / align * align;
        if (!ok || count > (size - start) / sizeof(T) || start > size) {
            ok = false;
            return nullptr;
        }
        at = start + count * sizeof(T);
        return reinterpret_cast<const T*>(data + start);
    }
    uint32_t u32() {
        const uint32_t* p = take<uint32_t>(1);
        return p ? *p : 0;
    }
};

Status parse_mesh(Reader r, MeshView* m) {
    m->vertex_count = r.u32();
    m->triangle_count = r.u32();
    m->positions = r.take<float>(size_t(m->vertex_count) * 3);
    m->normals = r.take<float>(size_t(m->vertex_count) * 3);
    m->indices = r.take<uint32_t>(size_t(m->triangle_count) * 3);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "MESH: size does not match %u vertices, %u triangles", m->vertex_count,
                            m->triangle_count);
    if (m->vertex_count == 0 || m->triangle_count == 0)
        return load_failure(LoadError::malformed_section, "MESH: empty mesh");
    for (size_t i = 0; i < size_t(m->triangle_count) * 3; ++i)
        if (m->indices[i] >= m->vertex_count)
            return load_failure(LoadError::out_of_range, "MESH: index %u at %zu >= vertex count %u",
                                m->indices[i], i, m->vertex_count);
    if (!all_finite(m->positions, size_t(m->vertex_count) * 3) ||
        !all_finite(m->normals, size_t(m->vertex_count) * 3))
        return load_failure(LoadError::bad_value, "MESH: non-finite position or normal");
    return {};
}

Status parse_skin(Reader r, uint32_t vertex_count, SkinView* s) {
    anim::Skeleton& k = s->skeleton;
    k.node_count = r.u32();
    k.joint_count = r.u32();
    k.parents = r.take<int32_t>(k.node_count);
    k.rest = r.take<anim::Trs>(k.node_count);
    k.joint_nodes = r.take<uint32_t>(k.joint_count);
    k.inverse_bind = r.take<float>(size_t(k.joint_count) * 16);
    s->joints = r.take<uint16_t>(size_t(vertex_count) * 4);
    s->weights = r.take<float>(size_t(vertex_count) * 4);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "SKIN: size does not match %u nodes, %u joints", k.node_count,
                            k.joint_count);
    if (k.joint_count == 0 || k.joint_count > 65535)
        return load_failure(LoadError::malformed_section, "SKIN: joint count %u not in [1, 65535]",
                            k.joint_count);
    const anim::DataError e = anim::check_skeleton(k);  // parents, joint nodes, finite rest
    if (e != anim::DataError::ok)
        return load_failure(
            e == anim::DataError::non_finite_value ? LoadError::bad_value : LoadError::out_of_range,
            "SKIN: skeleton of %u nodes, %u joints: %s", k.node_count, k.joint_count,
            anim::data_error_name(e));
    for (size_t i = 0; i < size_t(vertex_count) * 4; ++i)
        if (s->joints[i] >= k.joint_count)
            return load_failure(LoadError::out_of_range,
                                "SKIN: vertex %zu joint %u >= joint count %u", i / 4, s->joints[i],
                                k.joint_count);
    if (!all_finite(s->weights, size_t(vertex_count) * 4))
        return load_failure(LoadError::bad_value, "SKIN: non-finite weight");
    return {};
}

// Columns of one key's value: the value width, three times that for CUBICSPLINE.
uint64_t columns_of(const format::ChannelRecordV2& c) {
    uint64_t width = c.path == 1 ? 4 : c.path == 3 ? c.weight_count : 3;
    return c.interp == 2 ? width * 3 : width;
}

// The CLIP section's records and pools, as read (sizes checked, contents not yet).
struct ClipSection {
    uint32_t clip_count, channel_count, time_array_count, time_count, range_count, code_count,
        name_bytes;
    const format::ClipRecord* clips;
    const format::ChannelRecordV2* channels;
    const format::TimeArrayRecord* arrays;
    const float* times;
    const float* ranges;
    const uint16_t* codes;
    const char* names;
};

Status read_clip_section(Reader r, ClipSection* c) {
    uint32_t n[7];
    for (uint32_t& x : n) x = r.u32();
    *c = {n[0], n[1], n[2], n[3], n[4], n[5], n[6]};
    c->clips = r.take<format::ClipRecord>(c->clip_count);
    c->channels = r.take<format::ChannelRecordV2>(c->channel_count);
    c->arrays = r.take<format::TimeArrayRecord>(c->time_array_count);
    c->times = r.take<float>(c->time_count);
    c->ranges = r.take<float>(c->range_count);
    c->codes = r.take<uint16_t>(c->code_count);
    c->names = r.take<char>(c->name_bytes);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "CLIP: size does not match %u clips, %u channels", c->clip_count,
                            c->channel_count);
    if (c->name_bytes == 0 || c->names[c->name_bytes - 1] != '\0')
        return load_failure(LoadError::malformed_section, "CLIP: name pool not NUL-terminated");
    if (!all_finite(c->times, c->time_count) || !all_finite(c->ranges, c->range_count))
        return load_failure(LoadError::bad_value, "CLIP: non-finite key time or range");
    return {};
}

// Every time array and channel record lies inside its pools; *value_total = decoded floats.
Status check_channel_records(const ClipSection& c, uint64_t* value_total) {
    for (uint32_t i = 0; i < c.time_array_count; ++i)
        if (c.arrays[i].offset > c.time_count ||
            c.arrays[i].count > c.time_count - c.arrays[i].offset)
            return load_failure(LoadError::out_of_range,
                                "CLIP: time array %u outside the time pool", i);
    *value_total = 0;
    for (uint32_t i = 0; i < c.channel_count; ++i) {
        const format::ChannelRecordV2& ch = c.channels[i];
        const uint64_t columns = columns_of(ch), values = columns * ch.key_count;
        if (ch.path > 3 || ch.interp > 2 || ch.time_array >= c.time_array_count || columns == 0 ||
            c.arrays[ch.time_array].count != ch.key_count || ch.codes_offset > c.code_count ||
            values > c.code_count - ch.codes_offset || ch.ranges_offset > c.range_count ||
            columns * 2 > c.range_count - ch.ranges_offset)
            return load_failure(LoadError::out_of_range,
                                "CLIP: channel %u (path %u, interp %u, %u keys) outside its pools",
                                i, ch.path, ch.interp, ch.key_count);
        *value_total += values;
    }
    return {};
}

// Decodes every channel's 16-bit codes into a->clip_values and fills a->channel_storage.
void decode_channels(const ClipSection& c, Asset* a) {
    float* out = a->clip_values.get();
    for (uint32_t i = 0; i < c.channel_count; ++i) {
        const format::ChannelRecordV2& ch = c.channels[i];
        const uint64_t columns = columns_of(ch);
        const float* range = c.ranges + ch.ranges_offset;
        const uint16_t* code = c.codes + ch.codes_offset;
        for (uint64_t k = 0; k < ch.key_count; ++k)
            for (uint64_t col = 0; col < columns; ++col) {
                const float lo = range[col * 2], hi = range[col * 2 + 1];
                out[k * columns + col] =
                    lo + (hi - lo) * (float(code[k * columns + col]) / 65535.0f);
            }
        a->channel_storage[i] = {ch.node,
                                 anim::Path(ch.path),
                                 anim::Interp(ch.interp),
                                 ch.key_count,
                                 c.times + c.arrays[ch.time_array].offset,
                                 out,
                                 ch.weight_begin,
                                 ch.weight_count};
        out += columns * ch.key_count;
    }
}

// Fills a->clip_storage from the clip records and checks each clip (anim::check_clip).
Status build_clips(const ClipSection& c, uint32_t node_count, uint32_t morph_slots, Asset* a) {
    for (uint32_t i = 0; i < c.clip_count; ++i) {
        const format::ClipRecord& rec = c.clips[i];
        if (rec.name_offset >= c.name_bytes || rec.channel_begin > c.channel_count ||
            rec.channel_count > c.channel_count - rec.channel_begin)
            return load_failure(LoadError::out_of_range,
                                "CLIP: clip %u name or channels out of range", i);
        a->clip_storage[i] = {c.names + rec.name_offset, rec.duration, rec.channel_count,
                              a->channel_storage.get() + rec.channel_begin};
        uint32_t bad = 0;
        anim::DataError e = anim::check_clip(a->clip_storage[i], node_count, morph_slots, &bad);
        if (e != anim::DataError::ok)
            return load_failure(
                e == anim::DataError::non_finite_value || e == anim::DataError::times_not_increasing
                    ? LoadError::bad_value
                    : LoadError::out_of_range,
                "CLIP: clip %u '%s' channel %u: %s", i, a->clip_storage[i].name, bad,
                anim::data_error_name(e));
    }
    return {};
}

// CLIP section: validates the records, then decodes every channel's 16-bit codes into one
// float pool allocated here, at load, so sampling reads plain floats.
Status parse_clips(Reader r, uint32_t node_count, uint32_t morph_slots, Asset* a) {
    ClipSection c;
    Status st = read_clip_section(r, &c);
    uint64_t value_total = 0;
    if (st.ok()) st = check_channel_records(c, &value_total);
    if (!st.ok()) return st;
    a->clip_values.reset(new (std::nothrow) float[size_t(value_total) + 1]);
    a->channel_storage.reset(new (std::nothrow) anim::Channel[c.channel_count + 1]);
    a->clip_storage.reset(new (std::nothrow) anim::Clip[c.clip_count + 1]);
    if (!a->clip_values || !a->channel_storage || !a->clip_storage)
        return load_failure(LoadError::out_of_memory, "CLIP: out of memory");
    decode_channels(c, a);
    st = build_clips(c, node_count, morph_slots, a);
    if (!st.ok()) return st;
    a->clip_count = c.clip_count;
    a->clips = a->clip_storage.get();
    return {};
}

// MRPH section: default weight per slot, target records and their delta pool.
Status parse_morph(Reader r, uint32_t vertex_count, Asset* a) {
    const uint32_t slots = r.u32(), target_count = r.u32(), delta_count = r.u32();
    const float* defaults = r.take<float>(slots);
    const format::MorphTargetRecord* records = r.take<format::MorphTargetRecord>(target_count);
    const float* deltas = r.take<float>(delta_count);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "MRPH: size does not match %u targets",
                            target_count);
    if (!all_finite(deltas, delta_count))
        return load_failure(LoadError::bad_value, "MRPH: non-finite delta");
    a->morph_target_storage.reset(new (std::nothrow) anim::MorphTarget[target_count + 1]);
    if (!a->morph_target_storage)
        return load_failure(LoadError::out_of_memory, "MRPH: out of memory");
    for (uint32_t i = 0; i < target_count; ++i) {
        const format::MorphTargetRecord& t = records[i];
        const uint64_t need = uint64_t(t.vertex_count) * 3;
        if (t.position_offset > delta_count || need > delta_count - t.position_offset ||
            (t.normal_offset != format::kNoDeltas &&
             (t.normal_offset > delta_count || need > delta_count - t.normal_offset)))
            return load_failure(LoadError::out_of_range, "MRPH: target %u deltas outside the pool",
                                i);
        a->morph_target_storage[i] = {
            t.weight, t.vertex_begin, t.vertex_count, deltas + t.position_offset,
            t.normal_offset == format::kNoDeltas ? nullptr : deltas + t.normal_offset};
    }
    a->morph = {slots, defaults, target_count, a->morph_target_storage.get()};
    anim::DataError e = anim::check_morph(a->morph, vertex_count);
    if (e != anim::DataError::ok)
        return load_failure(LoadError::out_of_range, "MRPH: %s", anim::data_error_name(e));
    return {};
}

// One pass over the point stream (thesis §4.5 fields, coded as in point_codec.h). With
// out == nullptr it only counts neighbours so the caller can size the arrays.
Status decode_point_stream(codec::BitReader r, uint32_t point_count, float radius_max,
                           uint32_t triangle_count, uint32_t* host, PointsView* out,
                           uint32_t* neighbour_total) {
    uint32_t total = 0, list[codec::kMaxNeighbours];
    const float bary_scale = 1.0f / float((1u << codec::kBaryBits) - 1);
    for (uint32_t i = 0; i < point_count; ++i) {
        uint32_t u = r.bits(codec::kBaryBits), v = r.bits(codec::kBaryBits);
        uint32_t q = r.bits(codec::kRadiusBits), n = r.bits(codec::kCountBits);
        const int k = codec::neighbour_order(i);
        for (uint32_t j = 0; j < n && r.ok; ++j) {
            int64_t index =
                j == 0 ? int64_t(i) - r.zigzag(k) : int64_t(list[j - 1]) - 1 - r.golomb(k);
            if (index < 0 || index >= int64_t(point_count))
                return load_failure(LoadError::out_of_range,
                                    "PNTQ: point %u neighbour %lld out of range", i,
                                    static_cast<long long>(index));
            list[j] = uint32_t(index);
        }
        const int32_t reference = codec::host_reference(i, list, n);
        const uint32_t base = reference >= 0 ? host[reference] : i > 0 ? host[i - 1] : 0;
        host[i] = base + uint32_t(r.zigzag(reference >= 0 ? codec::kPredictedHostOrder
                                                          : codec::host_order(triangle_count)));
        if (!r.ok) break;
        if (host[i] >= triangle_count || u + v > (1u << codec::kBaryBits) - 1)
            return load_failure(LoadError::out_of_range,
                                "PNTQ: point %u host triangle %u (of %u) or barycentrics invalid",
                                i, host[i], triangle_count);
        if (out) {
            for (uint32_t j = 0; j < n; ++j)
                const_cast<uint32_t*>(out->neighbours)[total + j] = list[j];
            const_cast<float*>(out->bary_u)[i] = float(u) * bary_scale;
            const_cast<float*>(out->bary_v)[i] = float(v) * bary_scale;
            const_cast<float*>(out->radius)[i] =
                q == codec::kRadiusZero
                    ? 0.0f
                    : radius_max * std::exp2(-float(q) / codec::kRadiusStepsPerOctave);
            const_cast<uint32_t*>(out->neighbour_offsets)[i + 1] = total + n;
        }
        total += n;
    }
    if (!r.ok) return load_failure(LoadError::out_of_range, "PNTQ: stream ends early");
    *neighbour_total = total;
    return {};
}

Status parse_point_stream(Reader r, uint32_t triangle_count, Asset* a) {
    uint32_t point_count = r.u32();
    const float* radius_max = r.take<float>(1);
    const uint64_t* bit_count = r.take<uint64_t>(1);
    if (!r.ok || !std::isfinite(*radius_max) || *bit_count > uint64_t(r.size - r.at) * 8)
        return load_failure(LoadError::malformed_section, "PNTQ: header does not fit the section");
    const size_t bytes = size_t((*bit_count + 7) / 8);
    codec::BitReader bits{r.data + r.at, size_t(*bit_count)};
    if (r.at + bytes != r.size)
        return load_failure(LoadError::malformed_section, "PNTQ: %llu bits but %zu bytes follow",
                            static_cast<unsigned long long>(*bit_count), r.size - r.at);
    uint32_t total = 0;
    // Hosts are decoded in the first pass (later hosts are predicted from earlier ones);
    // the second pass fills the other arrays once the neighbour count is known.
    a->point_storage.reset(new (std::nothrow) uint32_t[size_t(point_count) + 1]);
    if (!a->point_storage) return load_failure(LoadError::out_of_memory, "PNTQ: out of memory");
    Status st = decode_point_stream(bits, point_count, *radius_max, triangle_count,
                                    a->point_storage.get(), nullptr, &total);
    if (!st.ok()) return st;
    // host (kept from the first pass), u, v, radius (one word each per point), offsets
    // (P + 1), neighbours.
    const size_t words = size_t(point_count) * 5 + 1 + total;
    std::unique_ptr<uint32_t[]> storage(new (std::nothrow) uint32_t[words]);
    if (!storage) return load_failure(LoadError::out_of_memory, "PNTQ: out of memory");
    std::memcpy(storage.get(), a->point_storage.get(), size_t(point_count) * 4);
    a->point_storage = std::move(storage);
    uint32_t* w = a->point_storage.get();
    PointsView& p = a->points;
    p.point_count = point_count;
    p.host_triangle = w;
    p.bary_u = reinterpret_cast<const float*>(w + point_count);
    p.bary_v = reinterpret_cast<const float*>(w + size_t(point_count) * 2);
    p.radius = reinterpret_cast<const float*>(w + size_t(point_count) * 3);
    p.neighbour_offsets = w + size_t(point_count) * 4;
    p.neighbours = w + size_t(point_count) * 5 + 1;
    p.neighbour_count = total;
    w[size_t(point_count) * 4] = 0;
    // The same bytes passed the first pass, so this one cannot fail; its status is returned
    // all the same rather than assumed.
    return decode_point_stream(bits, point_count, *radius_max, triangle_count, w, &p, &total);
}

Status parse_edges(Reader r, const MeshView& m, EdgesView* e) {
    e->edge_count = r.u32();
    e->edges = r.take<uint32_t>(size_t(e->edge_count) * 4);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "EDGE: size does not match %u edges",
                            e->edge_count);
    for (uint32_t i = 0; i < e->edge_count; ++i) {
        const uint32_t* x = e->edges + size_t(i) * 4;
        if (x[0] >= m.vertex_count || x[1] >= m.vertex_count || x[2] >= m.triangle_count ||
            (x[3] >= m.triangle_count && x[3] != format::kNoFace))
            return load_failure(LoadError::out_of_range,
                                "EDGE: edge %u (%u, %u, faces %u, %u) out of range", i, x[0], x[1],
                                x[2], x[3]);
    }
    return {};
}

// SIDE section: runs of double-sided triangles, expanded into one flag per triangle (and,
// with an EDGE section, one per edge for the boundary rims) in storage allocated here.
Status parse_sides(Reader r, const MeshView& m, Asset* a) {
    SidesView& s = a->sides;
    s.run_count = r.u32();
    s.runs = r.take<uint32_t>(size_t(s.run_count) * 2);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "SIDE: size does not match %u runs",
                            s.run_count);
    uint64_t end = 0, total = 0;
    for (uint32_t i = 0; i < s.run_count; ++i) {
        const uint64_t first = s.runs[i * 2], count = s.runs[i * 2 + 1];
        if (count == 0 || first < end || first + count > m.triangle_count)
            return load_failure(
                LoadError::out_of_range,
                "SIDE: run %u (triangles %llu, +%llu) empty, overlapping or beyond %u "
                "triangles",
                i, static_cast<unsigned long long>(first), static_cast<unsigned long long>(count),
                m.triangle_count);
        end = first + count;
        total += count;
    }
    s.triangle_count = uint32_t(total);
    if (total == 0) return {};
    const size_t bytes = size_t(m.triangle_count) + a->edges.edge_count;
    a->side_storage.reset(new (std::nothrow) uint8_t[bytes]);
    if (!a->side_storage) return load_failure(LoadError::out_of_memory, "SIDE: out of memory");
    uint8_t* flags = a->side_storage.get();
    std::memset(flags, 0, bytes);
    for (uint32_t i = 0; i < s.run_count; ++i)
        std::memset(flags + s.runs[i * 2], 1, s.runs[i * 2 + 1]);
    s.triangle_double_sided = flags;
    if (a->edges.edge_count > 0) {
        uint8_t* boundary = flags + m.triangle_count;
        for (uint32_t i = 0; i < a->edges.edge_count; ++i) {
            const uint32_t* e = a->edges.edges + size_t(i) * 4;
            boundary[i] = e[3] == format::kNoFace && flags[e[2]];
        }
        a->edges.double_sided_boundary = boundary;
    }
    return {};
}

// BNDS section: the input's up axis, the rest-pose box and one box per clip.
Status parse_bounds(Reader r, Asset* a) {
    BoundsView& b = a->bounds;
    b.up_axis = r.u32();
    const uint32_t clip_count = r.u32();
    const float* rest = r.take<float>(6);
    b.clips = r.take<float>(size_t(clip_count) * 6);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "BNDS: size does not match %u clip boxes",
                            clip_count);
    if (clip_count != a->clip_count)
        return load_failure(LoadError::malformed_section, "BNDS: %u clip boxes for %u clips",
                            clip_count, a->clip_count);
    if (b.up_axis != format::kUpY && b.up_axis != format::kUpZ)
        return load_failure(LoadError::bad_value, "BNDS: up axis %u is neither 1 (+Y) nor 2 (+Z)",
                            b.up_axis);
    for (uint32_t box = 0; box <= clip_count; ++box) {
        const float* x = box == 0 ? rest : b.clips + size_t(box - 1) * 6;
        if (!all_finite(x, 6) || x[0] > x[3] || x[1] > x[4] || x[2] > x[5]) {
            if (box == 0)
                return load_failure(LoadError::bad_value, "BNDS: rest box not finite or min > max");
            return load_failure(LoadError::bad_value, "BNDS: clip %u box not finite or min > max",
                                box - 1);
        }
    }
    std::memcpy(b.rest, rest, sizeof(b.rest));
    b.present = true;
    return {};
}

const format::SectionEntry* find_section(const format::SectionEntry* table, uint32_t count,
                                         uint32_t tag) {
    for (uint32_t i = 0; i < count; ++i)
        if (table[i].tag == tag) return &table[i];
    return nullptr;
}

Status parse(const uint8_t* bytes, size_t size, Asset* a) {
    if (size < sizeof(format::FileHeader) || std::memcmp(bytes, format::kMagic, 4) != 0)
        return load_failure(LoadError::bad_magic, "not a .stip asset (bad magic)");
    format::FileHeader h;
    std::memcpy(&h, bytes, sizeof(h));
    if (h.endian_tag != format::kEndianTag)
        return load_failure(LoadError::wrong_endianness,
                            "asset byte order does not match this machine");
    if (h.version < format::kOldestVersion || h.version > format::kVersion)
        return load_failure(LoadError::unsupported_version,
                            "asset format version %u, this runtime reads %u to %u", h.version,
                            format::kOldestVersion, format::kVersion);
    a->version = h.version;
    if (h.file_size != size)
        return load_failure(LoadError::truncated, "asset is %zu bytes but its header says %llu",
                            size, static_cast<unsigned long long>(h.file_size));
    if (h.section_count > 64 ||
        sizeof(format::FileHeader) + h.section_count * sizeof(format::SectionEntry) > size)
        return load_failure(LoadError::truncated,
                            "section table (%u entries) does not fit the file", h.section_count);
    const auto* table = reinterpret_cast<const format::SectionEntry*>(bytes + sizeof(h));
    if (format::crc32(table, h.section_count * sizeof(format::SectionEntry)) != h.table_crc)
        return load_failure(LoadError::checksum_mismatch, "section table checksum mismatch");
    for (uint32_t i = 0; i < h.section_count; ++i) {
        const format::SectionEntry& s = table[i];
        char tag[5] = {char(s.tag), char(s.tag >> 8), char(s.tag >> 16), char(s.tag >> 24), 0};
        if (s.offset % format::kSectionAlign != 0 || s.offset > size || s.size > size - s.offset)
            return load_failure(LoadError::truncated,
                                "%s: section [%llu, +%llu) outside the %zu-byte file", tag,
                                static_cast<unsigned long long>(s.offset),
                                static_cast<unsigned long long>(s.size), size);
        if (format::crc32(bytes + s.offset, s.size) != s.crc)
            return load_failure(LoadError::checksum_mismatch,
                                "%s: checksum mismatch (corrupted asset)", tag);
    }
    const uint32_t tags[kSectionCount] = {
        format::kTagMesh,  format::kTagSkin,  format::kTagClips,  format::kTagPointStream,
        format::kTagEdges, format::kTagMorph, format::kTagBounds, format::kTagSides};
    const format::SectionEntry* sec[kSectionCount];
    for (int i = 0; i < kSectionCount; ++i) {
        // Version 2 had no BNDS or SIDE; like any unknown tag there, they are ignored.
        const bool known = h.version >= 3 || (i != kSectionBounds && i != kSectionSides);
        sec[i] = known ? find_section(table, h.section_count, tags[i]) : nullptr;
        a->section_size[i] = sec[i] ? sec[i]->size : 0;
    }
    if (!sec[0] || !sec[3])
        return load_failure(LoadError::missing_section, "asset lacks a %s section",
                            !sec[0] ? "MESH" : "PNTQ");
    if ((sec[2] || sec[5]) && !sec[1])
        return load_failure(LoadError::missing_section, "%s section without SKIN",
                            sec[2] ? "CLIP" : "MRPH");
    auto reader = [&](const format::SectionEntry* s) {
        return Reader{bytes + s->offset, size_t(s->size)};
    };
    Status st = parse_mesh(reader(sec[0]), &a->mesh);
    if (st.ok() && sec[1]) {
        a->skinned = true;
        st = parse_skin(reader(sec[1]), a->mesh.vertex_count, &a->skin);
    }
    if (st.ok() && sec[5]) st = parse_morph(reader(sec[5]), a->mesh.vertex_count, a);
    if (st.ok() && sec[2])
        st = parse_clips(reader(sec[2]), a->skin.skeleton.node_count, a->morph.weight_count, a);
    if (st.ok()) st = parse_point_stream(reader(sec[3]), a->mesh.triangle_count, a);
    if (st.ok() && sec[4]) st = parse_edges(reader(sec[4]), a->mesh, &a->edges);
    if (st.ok() && sec[kSectionSides]) st = parse_sides(reader(sec[kSectionSides]), a->mesh, a);
    if (st.ok() && sec[kSectionBounds]) st = parse_bounds(reader(sec[kSectionBounds]), a);
    return st;
}

}  // namespace

Status load_asset_memory(const void* data, size_t size, Asset* out) {
    *out = Asset();
    // 16-byte aligned copy so every typed view is aligned.
    out->storage.reset(new (std::nothrow) uint8_t[size + 16]);
    if (!out->storage)
        return load_failure(LoadError::out_of_memory, "out of memory for a %zu-byte asset", size);
    std::memcpy(out->storage.get(), data, size);
    out->file_size = size;
    Status st = parse(out->storage.get(), size, out);
    if (!st.ok()) *out = Asset();
    return st;
}

Status load_asset_file(const char* path, Asset* out) {
    *out = Asset();
    FILE* f = std::fopen(path, "rb");
    if (!f) return load_failure(LoadError::io_error, "cannot open '%s'", path);
    std::fseek(f, 0, SEEK_END);
    long len = std::ftell(f);
    std::fseek(f, 0, SEEK_SET);
    if (len < 0) {
        std::fclose(f);
        return load_failure(LoadError::io_error, "cannot read '%s'", path);
    }
    size_t size = size_t(len);
    out->storage.reset(new (std::nothrow) uint8_t[size + 16]);
    if (!out->storage) {
        std::fclose(f);
        return load_failure(LoadError::out_of_memory, "out of memory for '%s' (%zu bytes)", path,
                            size);
    }
    size_t got = std::fread(out->storage.get(), 1, size, f);
    std::fclose(f);
    if (got != size) return load_failure(LoadError::io_error, "short read on '%s'", path);
    out->file_size = size;
    Status st = parse(out->storage.get(), size, out);
    if (!st.ok()) *out = Asset();
    return st;
}

int find_clip(const Asset& asset, const char* name) {
    for (uint32_t i = 0; i < asset.clip_count; ++i)
        if (std::strcmp(asset.clips[i].name, name) == 0) return int(i);
    char* end = nullptr;
    long index = std::strtol(name, &end, 10);
    if (end != name && *end == '\0' && index >= 0 && index < long(asset.clip_count))
        return int(index);
    return -1;
}

const char* section_name(int section) {
    static const char* const kNames[kSectionCount] = {"MESH", "SKIN", "CLIP", "PNTQ",
                                                      "EDGE", "MRPH", "BNDS", "SIDE"};
    return section >= 0 && section < kSectionCount ? kNames[section] : "?";
}

}  // namespace stipple
