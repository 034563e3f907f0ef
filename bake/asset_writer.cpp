#include "bake/asset_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "bake/atomic_file.h"
#include "bake/point_codec_encode.h"
#include "bake/scene_bounds.h"
#include "bake/silhouette_edges.h"
#include "runtime/asset_format.h"

namespace stipple::bake {

namespace {

// Little-endian byte sink. The bake only runs on little-endian hosts (checked in main).
struct Bytes {
    std::vector<uint8_t> v;
    template <typename T>
    void put(const T* data, size_t count) {
        align(alignof(T));
        const uint8_t* p = reinterpret_cast<const uint8_t*>(data);
        v.insert(v.end(), p, p + count * sizeof(T));
    }
    template <typename T>
    void put(const std::vector<T>& data) {
        put(data.data(), data.size());
    }
    void u32(uint32_t x) { put(&x, 1); }
    void align(size_t a) {
        while (v.size() % a) v.push_back(0);
    }
};

std::vector<uint8_t> mesh_section(const RawScene& s) {
    Bytes b;
    b.u32(uint32_t(s.vertex_count()));
    b.u32(uint32_t(s.triangle_count()));
    b.put(s.positions);
    b.put(s.normals);
    b.put(s.indices);
    return b.v;
}

std::vector<uint8_t> skin_section(const RawScene& s) {
    Bytes b;
    b.u32(uint32_t(s.nodes.size()));
    b.u32(uint32_t(s.joint_nodes.size()));
    for (const RawNode& n : s.nodes) b.put(&n.parent, 1);
    for (const RawNode& n : s.nodes) {
        b.put(n.translation, 3);
        b.put(n.rotation, 4);
        b.put(n.scale, 3);
    }
    b.put(s.joint_nodes);
    b.put(s.inverse_bind);
    b.put(s.joints);
    b.put(s.weights);
    return b.v;
}

// Columns of a channel's key value: width floats, three times that for CUBICSPLINE.
uint32_t channel_columns(const RawChannel& ch) {
    uint32_t width = ch.path == RawPath::rotation  ? 4
                     : ch.path == RawPath::weights ? ch.weight_count
                                                   : 3;
    return ch.interp == RawInterp::cubic_spline ? width * 3 : width;
}

// Version 2 CLIP section (runtime/asset_format.h ChannelRecordV2): indexed key times and
// 16-bit values over per-column ranges. Error per value <= (max - min) / 131070.
std::vector<uint8_t> clip_section(const RawScene& s) {
    std::vector<format::ClipRecord> clips;
    std::vector<format::ChannelRecordV2> channels;
    std::vector<format::TimeArrayRecord> time_arrays;
    std::vector<float> times, ranges;
    std::vector<uint16_t> codes;
    std::map<std::vector<float>, uint32_t> time_index;
    std::string names;
    for (const RawClip& c : s.clips) {
        clips.push_back({uint32_t(names.size()), uint32_t(channels.size()),
                         uint32_t(c.channels.size()), c.duration});
        names += c.name;
        names += '\0';
        for (const RawChannel& ch : c.channels) {
            auto [it, added] = time_index.emplace(ch.times, uint32_t(time_arrays.size()));
            if (added) {
                time_arrays.push_back({uint32_t(times.size()), uint32_t(ch.times.size())});
                times.insert(times.end(), ch.times.begin(), ch.times.end());
            }
            format::ChannelRecordV2 r = {};
            r.node = ch.node;
            r.path = uint8_t(ch.path);
            r.interp = uint8_t(ch.interp);
            r.key_count = uint32_t(ch.times.size());
            r.time_array = it->second;
            r.weight_begin = ch.weight_begin;
            r.weight_count = ch.weight_count;
            r.codes_offset = uint32_t(codes.size());
            r.ranges_offset = uint32_t(ranges.size());
            const uint32_t columns = channel_columns(ch);
            for (uint32_t col = 0; col < columns; ++col) {
                float lo = ch.values[col], hi = ch.values[col];
                for (size_t k = 0; k < ch.times.size(); ++k) {
                    lo = std::min(lo, ch.values[k * columns + col]);
                    hi = std::max(hi, ch.values[k * columns + col]);
                }
                ranges.push_back(lo);
                ranges.push_back(hi);
            }
            for (size_t k = 0; k < ch.times.size(); ++k)
                for (uint32_t col = 0; col < columns; ++col) {
                    float lo = ranges[r.ranges_offset + col * 2],
                          hi = ranges[r.ranges_offset + col * 2 + 1];
                    float x = ch.values[k * columns + col];
                    codes.push_back(
                        hi > lo ? uint16_t(std::lround(double(x - lo) / double(hi - lo) * 65535.0))
                                : 0);
                }
            channels.push_back(r);
        }
    }
    if (names.empty()) names.push_back('\0');
    Bytes b;
    for (size_t n : {clips.size(), channels.size(), time_arrays.size(), times.size(), ranges.size(),
                     codes.size(), names.size()})
        b.u32(uint32_t(n));
    b.put(clips);
    b.put(channels);
    b.put(time_arrays);
    b.put(times);
    b.put(ranges);
    b.put(codes);
    b.put(names.data(), names.size());
    return b.v;
}

// MRPH section: default weight per slot, target records, delta pool (floats).
std::vector<uint8_t> morph_section(const RawScene& s) {
    std::vector<format::MorphTargetRecord> records;
    std::vector<float> deltas;
    for (const RawMorphTarget& t : s.morph_targets) {
        format::MorphTargetRecord r = {t.weight, t.vertex_begin, t.vertex_count,
                                       uint32_t(deltas.size()), format::kNoDeltas};
        deltas.insert(deltas.end(), t.position_deltas.begin(), t.position_deltas.end());
        if (!t.normal_deltas.empty()) {
            r.normal_offset = uint32_t(deltas.size());
            deltas.insert(deltas.end(), t.normal_deltas.begin(), t.normal_deltas.end());
        }
        records.push_back(r);
    }
    Bytes b;
    b.u32(uint32_t(s.morph_weights.size()));
    b.u32(uint32_t(records.size()));
    b.u32(uint32_t(deltas.size()));
    b.put(s.morph_weights);
    b.put(records);
    b.put(deltas);
    return b.v;
}

std::vector<uint8_t> point_stream_section(const PointHierarchy& p, uint32_t triangle_count) {
    EncodedPoints e = encode_points(p, triangle_count);
    Bytes b;
    b.u32(uint32_t(p.size()));
    b.put(&e.radius_max, 1);
    b.put(&e.bit_count, 1);
    b.put(e.bytes);
    return b.v;
}

std::vector<uint8_t> edges_section(const RawScene& s) {
    std::vector<uint32_t> edges = silhouette_edges(s);
    Bytes b;
    b.u32(uint32_t(edges.size() / 4));
    b.put(edges);
    return b.v;
}

// SIDE section: the double-sided triangles as runs (one per glTF primitive, typically).
std::vector<uint8_t> sides_section(const RawScene& s) {
    std::vector<uint32_t> runs;
    for (size_t t = 0; t < s.double_sided.size(); ++t) {
        if (!s.double_sided[t]) continue;
        if (!runs.empty() && runs[runs.size() - 2] + runs.back() == t)
            ++runs.back();
        else
            runs.insert(runs.end(), {uint32_t(t), 1u});
    }
    Bytes b;
    b.u32(uint32_t(runs.size() / 2));
    b.put(runs);
    return b.v;
}

// BNDS section: up axis, rest-pose box, one box per clip.
std::vector<uint8_t> bounds_section(const RawScene& s) {
    SceneBounds bounds = compute_scene_bounds(s);
    Bytes b;
    b.u32(s.up_axis);
    b.u32(uint32_t(bounds.clips.size() / 6));
    b.put(bounds.rest, 6);
    b.put(bounds.clips);
    return b.v;
}

// STRK section: counts, stroke records, control point records.
std::vector<uint8_t> strokes_section(const BakedStrokes& s) {
    Bytes b;
    b.u32(uint32_t(s.strokes.size()));
    b.u32(uint32_t(s.points.size()));
    b.put(s.strokes);
    b.put(s.points);
    return b.v;
}

// LOOK section: header, creases, point colours, part colours, triangle parts, part flags
// (runtime/asset_format.h LooksHeader; the order aligns every array without padding).
std::vector<uint8_t> looks_section(const BakedLooks& l) {
    const format::LooksHeader h = {uint32_t(l.point_colour.size() / 4),
                                   uint32_t(l.part_flags.size()),
                                   uint32_t(l.part_flags.empty() ? 0 : l.triangle_part.size()),
                                   uint32_t(l.creases.size() / 4), 0};
    Bytes b;
    b.put(&h, 1);
    b.put(l.creases);
    b.put(l.point_colour);
    b.put(l.part_colour);
    if (!l.part_flags.empty()) b.put(l.triangle_part);
    b.put(l.part_flags);
    return b.v;
}

// PTRE: the point count, then one parent per point (runtime/asset_format.h).
std::vector<uint8_t> particles_section(const std::vector<uint32_t>& parents) {
    std::vector<uint8_t> b((parents.size() + 1) * 4);
    const uint32_t count = uint32_t(parents.size());
    std::memcpy(b.data(), &count, 4);
    if (count) std::memcpy(b.data() + 4, parents.data(), parents.size() * 4);
    return b;
}

// CURV: the point count, then the angles, then the confidences (runtime/asset_format.h).
std::vector<uint8_t> curvature_section(const BakedCurvature& c) {
    Bytes b;
    b.u32(uint32_t(c.angle.size()));
    b.put(c.angle);
    b.put(c.confidence);
    return b.v;
}

// OCCL: the triangle count, the deviation, then the indices (runtime/asset_format.h).
std::vector<uint8_t> occluder_section(const BakedOccluder& o) {
    Bytes b;
    b.u32(uint32_t(o.indices.size() / 3));
    b.put(&o.deviation, 1);
    b.put(o.indices);
    return b.v;
}

}  // namespace

std::vector<uint8_t> encode_asset(const RawScene& scene, const PointHierarchy& points,
                                  const BakedStrokes& strokes, const BakedLooks& looks,
                                  const std::vector<uint32_t>& particle_parents,
                                  const BakedCurvature& curvature, const BakedOccluder& occluder) {
    struct Section {
        uint32_t tag;
        std::vector<uint8_t> bytes;
    };
    std::vector<Section> sections;
    sections.push_back({format::kTagMesh, mesh_section(scene)});
    if (scene.animated()) {
        sections.push_back({format::kTagSkin, skin_section(scene)});
        if (!scene.clips.empty()) sections.push_back({format::kTagClips, clip_section(scene)});
        if (!scene.morph_weights.empty())
            sections.push_back({format::kTagMorph, morph_section(scene)});
    }
    sections.push_back(
        {format::kTagPointStream, point_stream_section(points, uint32_t(scene.triangle_count()))});
    sections.push_back({format::kTagEdges, edges_section(scene)});
    sections.push_back({format::kTagBounds, bounds_section(scene)});
    if (std::find(scene.double_sided.begin(), scene.double_sided.end(), 1) !=
        scene.double_sided.end())
        sections.push_back({format::kTagSides, sides_section(scene)});
    if (!strokes.empty()) sections.push_back({format::kTagStrokes, strokes_section(strokes)});
    if (!looks.empty()) sections.push_back({format::kTagLooks, looks_section(looks)});
    if (!particle_parents.empty() && particle_parents.size() == points.size())
        sections.push_back({format::kTagParticles, particles_section(particle_parents)});
    if (!curvature.angle.empty() && curvature.angle.size() == points.size() &&
        curvature.confidence.size() == points.size())
        sections.push_back({format::kTagCurvature, curvature_section(curvature)});
    if (!occluder.empty()) sections.push_back({format::kTagOccluder, occluder_section(occluder)});

    std::vector<format::SectionEntry> table(sections.size());
    uint64_t offset = sizeof(format::FileHeader) + table.size() * sizeof(format::SectionEntry);
    for (size_t i = 0; i < sections.size(); ++i) {
        offset =
            (offset + format::kSectionAlign - 1) / format::kSectionAlign * format::kSectionAlign;
        const std::vector<uint8_t>& bytes = sections[i].bytes;
        table[i] = {sections[i].tag, format::crc32(bytes.data(), bytes.size()), offset,
                    bytes.size()};
        offset += bytes.size();
    }
    format::FileHeader h = {};
    std::memcpy(h.magic, format::kMagic, 4);
    h.version = format::kVersion;
    h.endian_tag = format::kEndianTag;
    h.section_count = uint32_t(table.size());
    h.table_crc = format::crc32(table.data(), table.size() * sizeof(format::SectionEntry));
    h.file_size = offset;

    std::vector<uint8_t> out(offset, 0);
    std::memcpy(out.data(), &h, sizeof(h));
    std::memcpy(out.data() + sizeof(h), table.data(), table.size() * sizeof(format::SectionEntry));
    for (size_t i = 0; i < sections.size(); ++i)
        std::memcpy(out.data() + table[i].offset, sections[i].bytes.data(),
                    sections[i].bytes.size());
    return out;
}

BakeError write_asset(const std::string& path, const std::vector<uint8_t>& bytes) {
    return write_file_atomically(path, bytes);
}

}  // namespace stipple::bake
