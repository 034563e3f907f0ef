#include "bake/asset_writer.h"

#include <cstdio>
#include <cstring>

#include "bake/point_codec_encode.h"
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

std::vector<uint8_t> clip_section(const RawScene& s) {
    std::vector<format::ClipRecord> clips;
    std::vector<format::ChannelRecord> channels;
    std::vector<float> pool;
    std::string names;
    for (const RawClip& c : s.clips) {
        clips.push_back({uint32_t(names.size()), uint32_t(channels.size()),
                         uint32_t(c.channels.size()), c.duration});
        names += c.name;
        names += '\0';
        for (const RawChannel& ch : c.channels) {
            format::ChannelRecord r = {};
            r.node = ch.node;
            r.path = uint8_t(ch.path);
            r.interp = uint8_t(ch.interp);
            r.key_count = uint32_t(ch.times.size());
            r.times_offset = uint32_t(pool.size());
            pool.insert(pool.end(), ch.times.begin(), ch.times.end());
            r.values_offset = uint32_t(pool.size());
            pool.insert(pool.end(), ch.values.begin(), ch.values.end());
            channels.push_back(r);
        }
    }
    if (names.empty()) names.push_back('\0');
    Bytes b;
    b.u32(uint32_t(clips.size()));
    b.u32(uint32_t(channels.size()));
    b.u32(uint32_t(pool.size()));
    b.u32(uint32_t(names.size()));
    b.put(clips);
    b.put(channels);
    b.put(pool);
    b.put(names.data(), names.size());
    return b.v;
}

std::vector<uint8_t> points_section(const PointHierarchy& p) {
    Bytes b;
    b.u32(uint32_t(p.size()));
    b.put(p.host_triangle);
    b.put(p.bary_u);
    b.put(p.bary_v);
    b.put(p.radius);
    return b.v;
}

std::vector<uint8_t> neighbours_section(const PointHierarchy& p) {
    Bytes b;
    b.u32(uint32_t(p.size()));
    b.u32(uint32_t(p.neighbours.size()));
    b.put(p.neighbour_offsets);
    b.put(p.neighbours);
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

}  // namespace

std::vector<uint8_t> encode_asset(const RawScene& scene, const PointHierarchy& points,
                                  const AssetOptions& options) {
    struct Section {
        uint32_t tag;
        std::vector<uint8_t> bytes;
    };
    std::vector<Section> sections;
    sections.push_back({format::kTagMesh, mesh_section(scene)});
    if (scene.animated()) {
        sections.push_back({format::kTagSkin, skin_section(scene)});
        if (!scene.clips.empty()) sections.push_back({format::kTagClips, clip_section(scene)});
    }
    if (options.version == 0) {
        sections.push_back({format::kTagPoints, points_section(points)});
        sections.push_back({format::kTagNeighbours, neighbours_section(points)});
    } else {
        sections.push_back({format::kTagPointStream, point_stream_section(points, uint32_t(scene.triangle_count()))});
    }
    sections.push_back({format::kTagEdges, edges_section(scene)});

    std::vector<format::SectionEntry> table(sections.size());
    uint64_t offset = sizeof(format::FileHeader) + table.size() * sizeof(format::SectionEntry);
    for (size_t i = 0; i < sections.size(); ++i) {
        offset = (offset + format::kSectionAlign - 1) / format::kSectionAlign * format::kSectionAlign;
        const std::vector<uint8_t>& bytes = sections[i].bytes;
        table[i] = {sections[i].tag, format::crc32(bytes.data(), bytes.size()), offset,
                    bytes.size()};
        offset += bytes.size();
    }
    format::FileHeader h = {};
    std::memcpy(h.magic, format::kMagic, 4);
    h.version = options.version;
    h.endian_tag = format::kEndianTag;
    h.section_count = uint32_t(table.size());
    h.table_crc = format::crc32(table.data(), table.size() * sizeof(format::SectionEntry));
    h.file_size = offset;

    std::vector<uint8_t> out(offset, 0);
    std::memcpy(out.data(), &h, sizeof(h));
    std::memcpy(out.data() + sizeof(h), table.data(), table.size() * sizeof(format::SectionEntry));
    for (size_t i = 0; i < sections.size(); ++i)
        std::memcpy(out.data() + table[i].offset, sections[i].bytes.data(), sections[i].bytes.size());
    return out;
}

bool write_asset(const std::string& path, const std::vector<uint8_t>& bytes, std::string* error) {
    std::string tmp = path + ".tmp";
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) {
        *error = "cannot open '" + tmp + "' for writing";
        return false;
    }
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    ok = (std::fclose(f) == 0) && ok;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        *error = "cannot write '" + path + "'";
        return false;
    }
    return true;
}

}  // namespace stipple::bake
