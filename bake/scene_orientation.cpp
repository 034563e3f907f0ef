#include "bake/scene_orientation.h"

#include "runtime/asset_format.h"

namespace stipple::bake {

bool parse_up_axis(const std::string& text, uint32_t* out) {
    if (text == "y" || text == "Y") {
        *out = format::kUpY;
        return true;
    }
    if (text == "z" || text == "Z") {
        *out = format::kUpZ;
        return true;
    }
    return false;
}

void apply_up_axis(uint32_t up_axis, RawScene* scene) {
    scene->up_axis = up_axis == format::kUpZ ? format::kUpZ : format::kUpY;
    if (up_axis != format::kUpZ) return;
    if (!scene->animated()) {
        // (x, y, z) -> (x, z, -y): a rotation (determinant +1), so windings stay outward.
        for (std::vector<float>* v : {&scene->positions, &scene->normals})
            for (size_t i = 0; i + 2 < v->size(); i += 3) {
                const float y = (*v)[i + 1], z = (*v)[i + 2];
                (*v)[i + 1] = z;
                (*v)[i + 2] = -y;
            }
        return;
    }
    // A new root above every node: -90 degrees about +X, quaternion (-sin 45, 0, 0, cos 45).
    RawNode root;
    root.name = "stipple_z_up_to_y_up";
    root.rotation[0] = -0.70710678f;
    root.rotation[3] = 0.70710678f;
    for (RawNode& n : scene->nodes) n.parent = n.parent < 0 ? 0 : n.parent + 1;
    scene->nodes.insert(scene->nodes.begin(), root);
    for (uint32_t& n : scene->joint_nodes) ++n;
    for (uint32_t& n : scene->morph_weight_nodes) ++n;
    for (RawClip& clip : scene->clips)
        for (RawChannel& channel : clip.channels) ++channel.node;
}

}  // namespace stipple::bake
