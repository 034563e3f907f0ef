#include "bake/raw_anim_view.h"

#include <cstring>

namespace stipple::bake {

void make_anim_view(const RawScene& scene, RawAnimView* view) {
    *view = RawAnimView();
    for (const RawNode& node : scene.nodes) {
        view->parents.push_back(node.parent);
        anim::Trs trs;
        std::memcpy(trs.translation, node.translation, sizeof(trs.translation));
        std::memcpy(trs.rotation, node.rotation, sizeof(trs.rotation));
        std::memcpy(trs.scale, node.scale, sizeof(trs.scale));
        view->rest.push_back(trs);
    }
    size_t channel_total = 0;
    for (const RawClip& clip : scene.clips) channel_total += clip.channels.size();
    view->channels.reserve(channel_total);  // clips point into it: no reallocation below
    for (const RawClip& clip : scene.clips) {
        const size_t first = view->channels.size();
        for (const RawChannel& c : clip.channels) {
            view->channels.push_back({c.node, anim::Path(c.path), anim::Interp(c.interp),
                                      uint32_t(c.times.size()), c.times.data(), c.values.data(),
                                      c.weight_begin, c.weight_count});
        }
        view->clips.push_back({clip.name.c_str(), clip.duration, uint32_t(clip.channels.size()),
                               view->channels.data() + first});
    }
    for (const RawMorphTarget& t : scene.morph_targets) {
        view->morph_targets.push_back({t.weight, t.vertex_begin, t.vertex_count,
                                       t.position_deltas.data(),
                                       t.normal_deltas.empty() ? nullptr : t.normal_deltas.data()});
    }
    view->skeleton = {
        uint32_t(scene.nodes.size()),       view->parents.data(),     view->rest.data(),
        uint32_t(scene.joint_nodes.size()), scene.joint_nodes.data(), scene.inverse_bind.data()};
    view->morph = {uint32_t(scene.morph_weights.size()), scene.morph_weights.data(),
                   uint32_t(view->morph_targets.size()), view->morph_targets.data()};
}

}  // namespace stipple::bake
