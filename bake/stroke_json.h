// Explicit paintstrokes from a JSON file (stipple-bake --strokes; docs/strokes.md has the
// schema): wires, water, anything drawn by hand rather than grown from the point hierarchy.
#pragma once
#include <string>

#include "bake/bake_error.h"
#include "bake/raw_scene.h"
#include "bake/stroke_data.h"

namespace stipple::bake {

// Parses `text` and appends its strokes to `out` (nothing on error). Joint anchors resolve
// their "joint" name against the scene's joints (RawScene::joint_nodes' node names); surface
// anchors check their triangle against the mesh. Errors: malformed_input, one line naming
// the stroke index and the field ("strokes[2].points[1]: radius -1 not > 0").
[[nodiscard]] BakeError parse_strokes_json(const std::string& text, const RawScene& scene,
                                           BakedStrokes* out);

// Reads `path` (io error naming it if it cannot) and parses it as above; messages start
// with the path.
[[nodiscard]] BakeError load_strokes_json(const std::string& path, const RawScene& scene,
                                          BakedStrokes* out);

}  // namespace stipple::bake
