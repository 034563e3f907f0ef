// Paintstrokes as the bake writes them: the STRK section's records (runtime/asset_format.h,
// docs/format.md), built by bake/fur.h (hair on the point hierarchy) and bake/stroke_json.h
// (explicit strokes from a JSON file), written by encode_asset (bake/asset_writer.h).
#pragma once
#include <vector>

#include "runtime/asset_format.h"

namespace stipple::bake {

// Strokes in the order they are written; each stroke's control points are the run
// [first_point, first_point + point_count) of `points`, runs ascending and contiguous.
struct BakedStrokes {
    std::vector<format::StrokeRecord> strokes;
    std::vector<format::StrokePointRecord> points;
    bool empty() const { return strokes.empty(); }
};

// Appends `more` after `into`, shifting its first_point by the points already there.
inline void append_strokes(const BakedStrokes& more, BakedStrokes* into) {
    const uint32_t base = uint32_t(into->points.size());
    for (format::StrokeRecord s : more.strokes) {
        s.first_point += base;
        into->strokes.push_back(s);
    }
    into->points.insert(into->points.end(), more.points.begin(), more.points.end());
}

}  // namespace stipple::bake
