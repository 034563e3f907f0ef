#include "runtime/asset.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <system_error>

#include "anim/finite.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"
#include "runtime/asset_parse.h"

namespace stipple {

namespace detail {

Status charge(DecodeBudget* budget, uint64_t bytes, const char* section) {
    if (bytes > budget->limit - budget->used)
        return load_failure(
            LoadError::decoded_size_limit,
            "%s: decoding needs %llu more bytes, over the limit of %llu (%llu taken)", section,
            static_cast<unsigned long long>(bytes), static_cast<unsigned long long>(budget->limit),
            static_cast<unsigned long long>(budget->used));
    budget->used += bytes;
    return {};
}

Status check_limit(const char* section, const char* what, uint64_t count, uint64_t limit) {
    if (count <= limit) return {};
    return load_failure(LoadError::count_over_limit, "%s: %s %llu over the limit of %llu", section,
                        what, static_cast<unsigned long long>(count),
                        static_cast<unsigned long long>(limit));
}

}  // namespace detail

namespace {

using detail::check_limit;
using detail::DecodeBudget;
using detail::Reader;

// Each normal is zero (no direction: the bake writes one for a vertex whose faces are all
// degenerate, and skinning keeps it zero) or of unit length within the tolerance.
Status check_normals(const float* normals, uint32_t vertex_count) {
    const float tol = limits::kNormalLengthTolerance;
    for (uint32_t v = 0; v < vertex_count; ++v) {
        const float* n = normals + size_t(v) * 3;
        const float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (len2 != 0.0f && !(len2 >= (1 - tol) * (1 - tol) && len2 <= (1 + tol) * (1 + tol)))
            return load_failure(LoadError::bad_normal,
                                "MESH: vertex %u normal length %g is neither 0 nor 1 (+-%g)", v,
                                double(std::sqrt(len2)), double(tol));
    }
    return {};
}

Status parse_mesh(Reader r, MeshView* m) {
    m->vertex_count = r.u32();
    m->triangle_count = r.u32();
    Status st = check_limit("MESH", "vertex count", m->vertex_count, limits::kMaxVertices);
    if (st.ok())
        st = check_limit("MESH", "triangle count", m->triangle_count, limits::kMaxTriangles);
    if (!st.ok()) return st;
    m->positions = r.take<float>(size_t(m->vertex_count) * 3);
    m->normals = r.take<float>(size_t(m->vertex_count) * 3);
    m->indices = r.take<uint32_t>(size_t(m->triangle_count) * 3);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section,
                            "MESH: size does not match %u vertices, %u triangles", m->vertex_count,
                            m->triangle_count);
    if (m->vertex_count == 0 || m->triangle_count == 0)
        return load_failure(LoadError::zero_count, "MESH: empty mesh (%u vertices, %u triangles)",
                            m->vertex_count, m->triangle_count);
    for (size_t i = 0; i < size_t(m->triangle_count) * 3; ++i)
        if (m->indices[i] >= m->vertex_count)
            return load_failure(LoadError::out_of_range, "MESH: index %u at %zu >= vertex count %u",
                                m->indices[i], i, m->vertex_count);
    if (!all_finite(m->positions, size_t(m->vertex_count) * 3) ||
        !all_finite(m->normals, size_t(m->vertex_count) * 3))
        return load_failure(LoadError::bad_value, "MESH: non-finite position or normal");
    return check_normals(m->normals, m->vertex_count);
}

// Each vertex's 4 weights are in [0, 1] and sum to 1 within the tolerance (the bake writes
// w / sum in floats: a few 1e-7 off).
Status check_weights(const float* weights, uint32_t vertex_count) {
    for (uint32_t v = 0; v < vertex_count; ++v) {
        const float* w = weights + size_t(v) * 4;
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) {
            if (!(w[k] >= 0.0f && w[k] <= 1.0f))
                return load_failure(LoadError::bad_skin_weight,
                                    "SKIN: vertex %u weight %d is %g, not in [0, 1]", v, k,
                                    double(w[k]));
            sum += w[k];
        }
        if (std::fabs(sum - 1.0f) > limits::kWeightSumTolerance)
            return load_failure(LoadError::bad_skin_weight,
                                "SKIN: vertex %u weights sum to %g, not 1 (+-%g)", v, double(sum),
                                double(limits::kWeightSumTolerance));
    }
    return {};
}

Status parse_skin(Reader r, uint32_t vertex_count, SkinView* s) {
    anim::Skeleton& k = s->skeleton;
    k.node_count = r.u32();
    k.joint_count = r.u32();
    Status st = check_limit("SKIN", "node count", k.node_count, limits::kMaxNodes);
    if (st.ok()) st = check_limit("SKIN", "joint count", k.joint_count, limits::kMaxJoints);
    if (!st.ok()) return st;
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
    if (k.joint_count == 0 || k.node_count == 0)
        return load_failure(LoadError::zero_count, "SKIN: %u nodes, %u joints (need >= 1 each)",
                            k.node_count, k.joint_count);
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
    return check_weights(s->weights, vertex_count);
}

// MRPH section: default weight per slot, target records and their delta pool.
Status parse_morph(Reader r, uint32_t vertex_count, DecodeBudget* budget, Asset* a) {
    const uint32_t slots = r.u32(), target_count = r.u32(), delta_count = r.u32();
    Status st = check_limit("MRPH", "target count", target_count, limits::kMaxMorphTargets);
    if (st.ok()) st = check_limit("MRPH", "slot count", slots, limits::kMaxMorphSlots);
    if (!st.ok()) return st;
    const float* defaults = r.take<float>(slots);
    const format::MorphTargetRecord* records = r.take<format::MorphTargetRecord>(target_count);
    const float* deltas = r.take<float>(delta_count);
    if (!r.ok || r.at != r.size)
        return load_failure(LoadError::malformed_section, "MRPH: size does not match %u targets",
                            target_count);
    if (!all_finite(deltas, delta_count))
        return load_failure(LoadError::bad_value, "MRPH: non-finite delta");
    st = charge(budget, (uint64_t(target_count) + 1) * sizeof(anim::MorphTarget), "MRPH");
    if (!st.ok()) return st;
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
Status parse_sides(Reader r, const MeshView& m, DecodeBudget* budget, Asset* a) {
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
    const Status st = charge(budget, bytes, "SIDE");
    if (!st.ok()) return st;
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

// The sections version 3 added (each optional), after MESH, SKIN and PNTQ they refer to.
Status parse_version3_sections(const uint8_t* bytes, const format::SectionEntry* const* sec,
                               DecodeBudget* budget, Asset* a) {
    auto reader = [&](const format::SectionEntry* s) {
        return Reader{bytes + s->offset, size_t(s->size)};
    };
    Status st;
    if (sec[kSectionSides]) st = parse_sides(reader(sec[kSectionSides]), a->mesh, budget, a);
    if (st.ok() && sec[kSectionBounds]) st = parse_bounds(reader(sec[kSectionBounds]), a);
    if (st.ok() && sec[kSectionStrokes])
        st = detail::parse_strokes(reader(sec[kSectionStrokes]), a);
    if (st.ok() && sec[kSectionLooks]) st = detail::parse_looks(reader(sec[kSectionLooks]), a);
    if (st.ok() && sec[kSectionParticles])
        st = detail::parse_particles(reader(sec[kSectionParticles]), a);
    if (st.ok() && sec[kSectionCurvature])
        st = detail::parse_curvature(reader(sec[kSectionCurvature]), a);
    if (st.ok() && sec[kSectionOccluder])
        st = detail::parse_occluder(reader(sec[kSectionOccluder]), a);
    return st;
}

Status parse(const uint8_t* bytes, size_t size, DecodeBudget* budget, Asset* a) {
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
    if (h.section_count > limits::kMaxSections ||
        sizeof(format::FileHeader) + h.section_count * sizeof(format::SectionEntry) > size)
        return load_failure(LoadError::truncated,
                            "section table (%u entries) does not fit the file", h.section_count);
    const auto* table = reinterpret_cast<const format::SectionEntry*>(bytes + sizeof(h));
    // STIPPLE_FUZZ_SKIP_CRC: fuzz builds only (CMake option, needs STIPPLE_FUZZ; docs/fuzzing.md)
    // skip both CRC comparisons so mutated assets reach the decoders. Never set otherwise.
#ifndef STIPPLE_FUZZ_SKIP_CRC
    if (format::crc32(table, h.section_count * sizeof(format::SectionEntry)) != h.table_crc)
        return load_failure(LoadError::checksum_mismatch, "section table checksum mismatch");
#endif
    for (uint32_t i = 0; i < h.section_count; ++i) {
        const format::SectionEntry& s = table[i];
        char tag[5] = {char(s.tag), char(s.tag >> 8), char(s.tag >> 16), char(s.tag >> 24), 0};
        if (s.offset % format::kSectionAlign != 0 || s.offset > size || s.size > size - s.offset)
            return load_failure(LoadError::truncated,
                                "%s: section [%llu, +%llu) outside the %zu-byte file", tag,
                                static_cast<unsigned long long>(s.offset),
                                static_cast<unsigned long long>(s.size), size);
#ifndef STIPPLE_FUZZ_SKIP_CRC
        if (format::crc32(bytes + s.offset, s.size) != s.crc)
            return load_failure(LoadError::checksum_mismatch,
                                "%s: checksum mismatch (corrupted asset)", tag);
#endif
    }
    const uint32_t tags[kSectionCount] = {
        format::kTagMesh,    format::kTagSkin,  format::kTagClips,     format::kTagPointStream,
        format::kTagEdges,   format::kTagMorph, format::kTagBounds,    format::kTagSides,
        format::kTagStrokes, format::kTagLooks, format::kTagParticles, format::kTagCurvature,
        format::kTagOccluder};
    const format::SectionEntry* sec[kSectionCount];
    for (int i = 0; i < kSectionCount; ++i) {
        // Version 2 had no BNDS, SIDE, STRK or LOOK (kSectionBounds and after); like any
        // unknown tag there, they are ignored.
        const bool known = h.version >= 3 || i < kSectionBounds;
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
    if (st.ok() && sec[5]) st = parse_morph(reader(sec[5]), a->mesh.vertex_count, budget, a);
    if (st.ok() && sec[2])
        st = detail::parse_clips(reader(sec[2]), a->skin.skeleton.node_count, a->morph.weight_count,
                                 budget, a);
    if (st.ok()) st = detail::parse_point_stream(reader(sec[3]), a->mesh.triangle_count, budget, a);
    if (st.ok() && sec[4]) st = parse_edges(reader(sec[4]), a->mesh, &a->edges);
    return st.ok() ? parse_version3_sections(bytes, sec, budget, a) : st;
}

// The file's bytes are in out->storage: validates and decodes them.
Status parse_stored(size_t size, const LoadOptions& options, Asset* out) {
    out->file_size = size;
    DecodeBudget budget;
    budget.limit = decoded_size_limit(size, options);
    Status st = parse(out->storage.get(), size, &budget, out);
    if (!st.ok()) *out = Asset();
    return st;
}

}  // namespace

uint64_t decoded_size_limit(size_t file_size, const LoadOptions& options) {
    if (options.max_decoded_bytes != 0) return options.max_decoded_bytes;
    return uint64_t(file_size) * limits::kDecodedPerFileByte + limits::kDecodedFloorBytes;
}

Status load_asset_memory(const void* data, size_t size, Asset* out, const LoadOptions& options) {
    if (!out) return load_failure(LoadError::invalid_argument, "no asset to load into");
    *out = Asset();
    if (!data || size == 0)
        return load_failure(LoadError::invalid_argument, "no asset bytes (data %s, size %zu)",
                            data ? "given" : "NULL", size);
    // 16-byte aligned copy so every typed view is aligned.
    out->storage.reset(new (std::nothrow) uint8_t[size + 16]);
    if (!out->storage)
        return load_failure(LoadError::out_of_memory, "out of memory for a %zu-byte asset", size);
    std::memcpy(out->storage.get(), data, size);
    return parse_stored(size, options, out);
}

Status load_asset_file(const char* path, Asset* out, const LoadOptions& options) {
    if (!out || !path)
        return load_failure(LoadError::invalid_argument, "no %s",
                            out ? "path" : "asset to load into");
    *out = Asset();
    // Only regular files: a directory "opens" and reports a size of 2^63 - 1, and a device
    // such as /dev/zero never ends.
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (ec)
        return load_failure(LoadError::io_error, "cannot open '%s': %s", path,
                            std::strerror(ec.value()));
    if (std::filesystem::is_directory(st))
        return load_failure(LoadError::io_error, "'%s' is a directory", path);
    if (!std::filesystem::is_regular_file(st))
        return load_failure(LoadError::io_error, "'%s' is not a regular file", path);
    FILE* f = std::fopen(path, "rb");
    if (!f)
        return load_failure(LoadError::io_error, "cannot open '%s': %s", path,
                            std::strerror(errno));
    std::fseek(f, 0, SEEK_END);
    long len = std::ftell(f);
    std::fseek(f, 0, SEEK_SET);
    if (len < 0) {
        std::fclose(f);
        return load_failure(LoadError::io_error, "cannot read '%s': %s", path,
                            std::strerror(errno));
    }
    if (uint64_t(len) > limits::kMaxAssetFileBytes) {
        std::fclose(f);
        return load_failure(LoadError::count_over_limit,
                            "'%s' is %lld bytes, over the limit of %llu", path, (long long)len,
                            (unsigned long long)limits::kMaxAssetFileBytes);
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
    if (got != size) {
        *out = Asset();
        return load_failure(LoadError::io_error, "short read on '%s'", path);
    }
    return parse_stored(size, options, out);
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
    static const char* const kNames[kSectionCount] = {"MESH", "SKIN", "CLIP", "PNTQ", "EDGE",
                                                      "MRPH", "BNDS", "SIDE", "STRK", "LOOK",
                                                      "PTRE", "CURV", "OCCL"};
    return section >= 0 && section < kSectionCount ? kNames[section] : "?";
}

}  // namespace stipple
