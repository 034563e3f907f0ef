// glTF 2.0 skins, §3.7.3: skin 0's joints and inverse bind matrices, and per vertex the
// JOINTS_n/WEIGHTS_n influences pruned to the 4 the runtime skins with.
#include <algorithm>
#include <utility>

#include "anim/finite.h"
#include "bake/gltf_parts.h"

namespace stipple::bake::gltf {

namespace {

// Is skin 0 bound by a mesh node of the scene?
bool skin_used_in_scene(const Model& model, const NodeTable& nodes) {
    bool used = false;
    for (size_t gi : nodes.order) {
        if (model.nodes[gi].skin == 0 && model.nodes[gi].mesh >= 0) used = true;
    }
    return used;
}

// The inverse bind matrices of `joint_count` joints; absent ones are identities (§3.7.3).
BakeError read_inverse_bind(const Model& model, const tinygltf::Skin& skin, size_t joint_count,
                            std::vector<float>* inverse_bind) {
    if (skin.inverseBindMatrices < 0) {
        for (size_t j = 0; j < joint_count; ++j) {
            for (int k = 0; k < 16; ++k) inverse_bind->push_back(k % 5 == 0 ? 1.0f : 0.0f);
        }
        return BakeError();
    }
    const BakeError read =
        read_accessor(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, kF32, inverse_bind);
    if (!read.ok()) return prefixed("skin 0 inverseBindMatrices: ", read);
    if (inverse_bind->size() < joint_count * 16) {
        return malformed_input("skin 0: " + str(inverse_bind->size() / 16) +
                               " inverse bind matrices for " + str(joint_count) + " joints");
    }
    inverse_bind->resize(joint_count * 16);
    if (!all_finite(*inverse_bind))
        return malformed_input("skin 0: inverse bind matrices are not finite");
    return BakeError();
}

// One vertex's influences: (joint, summed weight) pairs.
using Influences = std::vector<std::pair<uint32_t, float>>;

// The JOINTS_n/WEIGHTS_n sets of a primitive, each 4 per vertex of the whole accessor.
struct InfluenceSets {
    std::vector<std::vector<uint32_t>> joints;
    std::vector<std::vector<float>> weights;
};

BakeError read_influence_sets(const MeshContext& ctx, const tinygltf::Primitive& prim,
                              const std::string& label, size_t vertex_count, InfluenceSets* sets) {
    for (int set = 0;; ++set) {
        const auto j = prim.attributes.find("JOINTS_" + str(set));
        const auto w = prim.attributes.find("WEIGHTS_" + str(set));
        if (j == prim.attributes.end() && w == prim.attributes.end()) break;
        if (j == prim.attributes.end() || w == prim.attributes.end()) {
            return malformed_input(label + ": JOINTS_" + str(set) + " and WEIGHTS_" + str(set) +
                                   " must come together");
        }
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        BakeError read =
            read_accessor(ctx.model, j->second, TINYGLTF_TYPE_VEC4, kU8 | kU16, &joints);
        if (!read.ok()) return prefixed(label + " JOINTS_" + str(set) + ": ", read);
        read =
            read_accessor(ctx.model, w->second, TINYGLTF_TYPE_VEC4, kF32 | kU8N | kU16N, &weights);
        if (!read.ok()) return prefixed(label + " WEIGHTS_" + str(set) + ": ", read);
        if (joints.size() != vertex_count * 4 || weights.size() != vertex_count * 4) {
            return malformed_input(label + ": JOINTS_" + str(set) + "/WEIGHTS_" + str(set) +
                                   " count differs from POSITION count " + str(vertex_count));
        }
        sets->joints.push_back(std::move(joints));
        sets->weights.push_back(std::move(weights));
    }
    return BakeError();
}

// Problems repaired while pruning influences, reported once per primitive.
struct InfluenceRepairs {
    size_t clamped = 0, unbound = 0, truncated = 0;
};

// Gathers the influences of vertex `old` over every set: negative weights clamp to 0,
// zero weights are dropped, repeated joints are summed.
BakeError gather_influences(const MeshContext& ctx, const InfluenceSets& sets,
                            const std::string& label, size_t old, Influences* influences,
                            InfluenceRepairs* repairs) {
    influences->clear();
    for (size_t set = 0; set < sets.joints.size(); ++set) {
        for (size_t c = 0; c < 4; ++c) {
            const uint32_t joint = sets.joints[set][old * 4 + c];
            float weight = sets.weights[set][old * 4 + c];
            if (!std::isfinite(weight)) {
                return malformed_input(label + ": vertex " + str(old) + " has a non-finite weight");
            }
            if (weight < 0.0f) {
                ++repairs->clamped;
                weight = 0.0f;
            }
            // A zero weight's joint index is never used; exporters often leave garbage.
            if (weight == 0.0f) continue;
            if (joint >= ctx.skin_joint_count) {
                return malformed_input(label + ": joint index " + str(size_t(joint)) +
                                       " out of range (skin 0 has " + str(ctx.skin_joint_count) +
                                       " joints)");
            }
            auto same = std::find_if(influences->begin(), influences->end(),
                                     [&](const auto& p) { return p.first == joint; });
            if (same != influences->end()) {
                same->second += weight;
            } else {
                influences->emplace_back(joint, weight);
            }
        }
    }
    return BakeError();
}

// Keeps the 4 largest influences, renormalised to sum 1, as vertex `v` of `out`.
void store_four_largest(Influences* influences, size_t v, Primitive* out,
                        InfluenceRepairs* repairs) {
    std::stable_sort(influences->begin(), influences->end(),
                     [](const auto& a, const auto& b) { return a.second > b.second; });
    if (influences->size() > 4) {
        ++repairs->truncated;
        influences->resize(4);
    }
    float sum = 0.0f;
    for (const auto& p : *influences) sum += p.second;
    if (!(sum > 0.0f)) {
        ++repairs->unbound;
        out->weights[v * 4] = 1.0f;  // joints stay 0: the whole vertex follows joint 0
        return;
    }
    for (size_t c = 0; c < influences->size(); ++c) {
        out->joints[v * 4 + c] = uint16_t((*influences)[c].first);
        out->weights[v * 4 + c] = (*influences)[c].second / sum;
    }
}

void warn_repairs(const InfluenceRepairs& r, const std::string& label,
                  std::vector<std::string>* warnings) {
    if (r.clamped) {
        warnings->push_back(label + ": " + str(r.clamped) + " negative weights clamped to 0");
    }
    if (r.unbound) {
        warnings->push_back(label + ": " + str(r.unbound) +
                            " vertices have no positive weight; bound to joint 0");
    }
    if (r.truncated) {
        warnings->push_back(label + ": " + str(r.truncated) +
                            " vertices have more than 4 influences; the 4 largest are kept");
    }
}

}  // namespace

BakeError read_skin(const Model& model, const NodeTable& nodes, std::vector<std::string>* warnings,
                    SkinTable* out) {
    if (model.skins.empty()) return BakeError();
    const tinygltf::Skin& skin = model.skins[0];
    const bool used_in_scene = skin_used_in_scene(model, nodes);
    if (skin.joints.empty() || skin.joints.size() > kMaxJoints) {
        return malformed_input("skin 0: joint count " + str(skin.joints.size()) +
                               " out of range [1, " + str(kMaxJoints) + "]");
    }
    for (int joint : skin.joints) {
        if (joint < 0 || size_t(joint) >= model.nodes.size()) {
            return malformed_input("skin 0: joint node " + str(joint) +
                                   " out of range (node count " + str(model.nodes.size()) + ")");
        }
        if (nodes.out_index[size_t(joint)] < 0) {
            if (used_in_scene) {
                return malformed_input("skin 0: joint node " + str(joint) + " is not in the scene");
            }
            warnings->push_back(
                "skin 0 is not used by the scene and its joints are not in it; "
                "skin ignored");
            out->joint_nodes.clear();
            return BakeError();
        }
        out->joint_nodes.push_back(uint32_t(nodes.out_index[size_t(joint)]));
    }
    out->present = true;
    return read_inverse_bind(model, skin, out->joint_nodes.size(), &out->inverse_bind);
}

// §3.7.3.3 "Skinned Mesh Attributes": the 4 largest influences per vertex, renormalised to
// sum 1.
BakeError read_skin_attributes(const MeshContext& ctx, const tinygltf::Primitive& prim,
                               const std::string& label, size_t vertex_count,
                               const std::vector<uint32_t>& used, Primitive* out) {
    InfluenceSets sets;
    const BakeError read = read_influence_sets(ctx, prim, label, vertex_count, &sets);
    if (!read.ok()) return read;
    if (sets.joints.empty()) return BakeError();  // not skinned

    InfluenceRepairs repairs;
    out->skinned = true;
    out->joints.assign(used.size() * 4, 0);
    out->weights.assign(used.size() * 4, 0.0f);
    Influences influences;
    for (size_t v = 0; v < used.size(); ++v) {
        const BakeError gathered =
            gather_influences(ctx, sets, label, used[v], &influences, &repairs);
        if (!gathered.ok()) return gathered;
        store_four_largest(&influences, v, out, &repairs);
    }
    warn_repairs(repairs, label, ctx.warnings);
    return BakeError();
}

// Reorders a skinned primitive's vertices by descending influence count (number of leading
// weights up to the last non-zero one), stable, and remaps its indices and morph deltas.
// The skinning job picks its kernel per block of 4 vertices from the largest count in the
// block, so grouped vertices run the 1-, 2- and 3-influence kernels instead of the 4 one.
void sort_by_influence_count(Primitive* prim) {
    const size_t n = prim->positions.size() / 3;
    std::vector<uint32_t> order(n);
    std::vector<int> count(n);
    for (size_t v = 0; v < n; ++v) {
        order[v] = uint32_t(v);
        int c = 1;
        for (int k = 0; k < 4; ++k) {
            if (prim->weights[v * 4 + size_t(k)] != 0.0f) c = k + 1;
        }
        count[v] = c;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return count[a] > count[b]; });
    bool identity = true;
    for (size_t v = 0; v < n; ++v) identity = identity && order[v] == v;
    if (identity) return;
    auto permute = [&](auto* values, size_t width) {
        if (values->empty()) return;
        std::remove_reference_t<decltype(*values)> sorted(values->size());
        for (size_t v = 0; v < n; ++v) {
            std::copy(values->begin() + long(order[v] * width),
                      values->begin() + long(order[v] * width + width),
                      sorted.begin() + long(v * width));
        }
        *values = std::move(sorted);
    };
    permute(&prim->positions, 3);
    permute(&prim->normals, 3);
    permute(&prim->weights, 4);
    permute(&prim->joints, 4);
    permute(&prim->uvs, 2);
    permute(&prim->colours, 4);
    for (auto& t : prim->target_positions) permute(&t, 3);
    for (auto& t : prim->target_normals) permute(&t, 3);
    std::vector<uint32_t> inverse(n);
    for (size_t v = 0; v < n; ++v) inverse[order[v]] = uint32_t(v);
    for (uint32_t& index : prim->indices) index = inverse[index];
}

}  // namespace stipple::bake::gltf
