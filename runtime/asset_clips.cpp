// The CLIP section: channel records over shared time, range and code pools, decoded at
// load into one float pool (docs/format.md). Split from asset.cpp.
#include <cstring>
#include <new>

#include "anim/finite.h"
#include "runtime/asset_format.h"
#include "runtime/asset_limits.h"
#include "runtime/asset_parse.h"

namespace stipple::detail {

namespace {

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
    Status st = check_limit("CLIP", "clip count", c->clip_count, limits::kMaxClips);
    if (st.ok()) st = check_limit("CLIP", "channel count", c->channel_count, limits::kMaxChannels);
    if (!st.ok()) return st;
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
        if (ch.key_count > limits::kMaxKeys ||
            (ch.path == 3 && ch.weight_count > limits::kMaxMorphSlots))
            return load_failure(LoadError::count_over_limit,
                                "CLIP: channel %u has %u keys (limit %u), %u weights (limit %u)", i,
                                ch.key_count, limits::kMaxKeys, ch.weight_count,
                                limits::kMaxMorphSlots);
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

}  // namespace

// CLIP section: validates the records, then decodes every channel's 16-bit codes into one
// float pool allocated here, at load, so sampling reads plain floats.
Status parse_clips(Reader r, uint32_t node_count, uint32_t morph_slots, DecodeBudget* budget,
                   Asset* a) {
    ClipSection c;
    Status st = read_clip_section(r, &c);
    uint64_t value_total = 0;
    if (st.ok()) st = check_channel_records(c, &value_total);
    // Channels may share key data (codes_offset), so the decoded floats are not bounded by
    // the section's size: charge them before allocating.
    if (st.ok())
        st = charge(budget,
                    (value_total + 1) * sizeof(float) +
                        (uint64_t(c.channel_count) + 1) * sizeof(anim::Channel) +
                        (uint64_t(c.clip_count) + 1) * sizeof(anim::Clip),
                    "CLIP");
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

}  // namespace stipple::detail
