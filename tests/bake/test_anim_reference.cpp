// An independent reference for the whole animation pipeline.
//
// The reference evaluates a glTF file straight from tinygltf's parsed data, in double
// precision, following the glTF 2.0 specification as plainly as possible: node TRS or
// matrix (§3.5.3), animation samplers with STEP / LINEAR (slerp with acos and sin) /
// CUBICSPLINE (Appendix C), morph targets (§3.7.2.2), and skinning with the spec's joint
// matrix = global transform of the joint * inverse bind matrix, weighted by the file's
// JOINTS_0/WEIGHTS_0 (§3.7.3). It shares no code with the importer or anim/.
//
// The pipeline under test: bake::import_gltf -> RawAnimView -> SamplingJob (with a context)
// -> LocalToModelJob -> JointMatrixJob -> MorphJob -> SkinningJob (LBS, SIMD and scalar).
// The importer drops unused vertices and reorders the rest, so positions are compared per
// triangle corner: the importer keeps node (depth-first preorder), primitive and triangle
// order, so corner i of the merged index list is corner i of the reference's list.
//
// Assets: CesiumMan, RiggedFigure, RiggedSimple, SimpleSkin (assets/), and two files
// generated here: a CUBICSPLINE-animated two-joint bar, and a morph-target asset (skinned
// and rigid node-parented meshes, default weights on mesh and node, LINEAR and CUBICSPLINE
// weights channels). Every clip is sampled at 26 times; the bound is 1e-4 of the bounding
// box diagonal.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anim/anim.h"
#include "bake/asset_writer.h"
#include "bake/raw_anim_view.h"
#include "bake/scene_import.h"
#include "runtime/asset.h"
#include "tests/common/bake_result.h"
#include "tests/common/scratch.h"

namespace {

using glm::dmat4;
using glm::dquat;
using glm::dvec3;
using glm::dvec4;

// ---------------------------------------------------------------------------------------
// Reference evaluator (double precision, straight from tinygltf)

// Accessor elements as doubles, count * components, with byteStride and normalized
// integers (§3.6.2.2). The test assets use no sparse accessors.
std::vector<double> read_doubles(const tinygltf::Model& m, int index) {
    const tinygltf::Accessor& a = m.accessors[size_t(index)];
    EXPECT_FALSE(a.sparse.isSparse);
    const int n = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int csize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    std::vector<double> out(a.count * size_t(n), 0.0);
    if (a.bufferView < 0) return out;
    const tinygltf::BufferView& view = m.bufferViews[size_t(a.bufferView)];
    const size_t stride = view.byteStride ? view.byteStride : size_t(n * csize);
    const unsigned char* base =
        m.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    for (size_t i = 0; i < a.count; ++i) {
        for (int c = 0; c < n; ++c) {
            const unsigned char* p = base + i * stride + size_t(c * csize);
            double v = 0;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                    float f;
                    std::memcpy(&f, p, 4);
                    v = f;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    v = a.normalized ? *p / 255.0 : *p;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    uint16_t u;
                    std::memcpy(&u, p, 2);
                    v = a.normalized ? u / 65535.0 : u;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                    uint32_t u;
                    std::memcpy(&u, p, 4);
                    v = u;
                    break;
                }
                default:
                    ADD_FAILURE() << "component type " << a.componentType
                                  << " not in the reference";
            }
            out[i * size_t(n) + size_t(c)] = v;
        }
    }
    return out;
}

struct RefTrs {
    dvec3 t{0.0};
    dquat r{1.0, 0.0, 0.0, 0.0};
    dvec3 s{1.0};
};

dmat4 trs_matrix(const RefTrs& x) {
    dmat4 m = glm::mat4_cast(x.r);
    for (int c = 0; c < 3; ++c) m[c] *= x.s[c];
    m[3] = dvec4(x.t, 1.0);
    return m;
}

// slerp on the shortest arc, exact (glTF 2.0 Appendix C). Keys are unit quaternions by
// the spec; SimpleSkin's are written with 3-4 digits (|q| = 1.00024), so they are
// normalised first, as the importer does.
dquat ref_slerp(dquat a, dquat b, double s) {
    a = glm::normalize(a);
    b = glm::normalize(b);
    double d = glm::dot(a, b);
    if (d < 0) {
        b = -b;
        d = -d;
    }
    if (d > 1.0 - 1e-15) return glm::normalize(a * (1 - s) + b * s);
    const double theta = std::acos(std::min(d, 1.0));
    const double k0 = std::sin((1 - s) * theta) / std::sin(theta);
    const double k1 = std::sin(s * theta) / std::sin(theta);
    return glm::normalize(a * k0 + b * k1);
}

// Evaluates sampler `si` of animation `anim` at time t: `width` doubles.
std::vector<double> eval_sampler(const tinygltf::Model& m, const tinygltf::Animation& anim, int si,
                                 double t, size_t width, bool rotation) {
    const tinygltf::AnimationSampler& s = anim.samplers[size_t(si)];
    const std::vector<double> times = read_doubles(m, s.input);
    const std::vector<double> out = read_doubles(m, s.output);
    const bool cubic = s.interpolation == "CUBICSPLINE";
    const size_t n = times.size();
    auto value = [&](size_t k) {
        const size_t at = cubic ? (3 * k + 1) * width : k * width;
        return std::vector<double>(out.begin() + long(at), out.begin() + long(at + width));
    };
    auto as_quat = [](const std::vector<double>& v) { return dquat(v[3], v[0], v[1], v[2]); };
    auto from_quat = [](dquat q) { return std::vector<double>{q.x, q.y, q.z, q.w}; };
    if (t <= times[0]) return value(0);
    if (t >= times[n - 1]) return value(n - 1);
    size_t k = 0;
    while (!(times[k] <= t && t < times[k + 1])) ++k;
    const double td = times[k + 1] - times[k];
    const double u = (t - times[k]) / td;
    if (s.interpolation == "STEP") return value(k);
    if (!cubic) {
        const std::vector<double> a = value(k), b = value(k + 1);
        if (rotation) return from_quat(ref_slerp(as_quat(a), as_quat(b), u));
        std::vector<double> r(width);
        for (size_t c = 0; c < width; ++c) r[c] = a[c] + (b[c] - a[c]) * u;
        return r;
    }
    // Hermite: (2u^3 - 3u^2 + 1) v_k + td (u^3 - 2u^2 + u) b_k + (-2u^3 + 3u^2) v_k+1
    //          + td (u^3 - u^2) a_k+1.
    std::vector<double> r(width);
    for (size_t c = 0; c < width; ++c) {
        const double vk = out[(3 * k + 1) * width + c];
        const double bk = out[(3 * k + 2) * width + c];
        const double ak1 = out[(3 * (k + 1)) * width + c];
        const double vk1 = out[(3 * (k + 1) + 1) * width + c];
        r[c] = (2 * u * u * u - 3 * u * u + 1) * vk + td * (u * u * u - 2 * u * u + u) * bk +
               (-2 * u * u * u + 3 * u * u) * vk1 + td * (u * u * u - u * u) * ak1;
    }
    if (rotation) return from_quat(glm::normalize(as_quat(r)));
    return r;
}

size_t target_count(const tinygltf::Model& m, int mesh) {
    size_t n = 0;
    for (const auto& p : m.meshes[size_t(mesh)].primitives) n = std::max(n, p.targets.size());
    return n;
}

// World-space positions of every triangle corner at time t of animation `anim_index`.
struct RefCorner {
    int node;
    int mesh;
    size_t prim;
    size_t vertex;
};

struct Reference {
    tinygltf::Model model;
    std::vector<RefCorner> corners;

    bool load(const std::string& path) {
        tinygltf::TinyGLTF loader;
        loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int,
                                 const unsigned char*, int, void*) { return true; },
                              nullptr);
        std::string err, warn;
        const bool binary = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
        const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                               : loader.LoadASCIIFromFile(&model, &err, &warn, path);
        if (!ok) return false;
        // Depth-first preorder from the scene roots, as the importer orders its output.
        const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        std::vector<int> stack(model.scenes[size_t(scene)].nodes.rbegin(),
                               model.scenes[size_t(scene)].nodes.rend());
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            const tinygltf::Node& node = model.nodes[size_t(n)];
            if (node.mesh >= 0) {
                const auto& prims = model.meshes[size_t(node.mesh)].primitives;
                for (size_t p = 0; p < prims.size(); ++p) {
                    EXPECT_TRUE(prims[p].mode == -1 || prims[p].mode == TINYGLTF_MODE_TRIANGLES);
                    if (prims[p].indices >= 0) {
                        for (double i : read_doubles(model, prims[p].indices)) {
                            corners.push_back({n, node.mesh, p, size_t(i)});
                        }
                    } else {
                        const size_t count =
                            model.accessors[size_t(prims[p].attributes.at("POSITION"))].count;
                        for (size_t i = 0; i < count; ++i) corners.push_back({n, node.mesh, p, i});
                    }
                }
            }
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
                stack.push_back(*it);
            }
        }
        return true;
    }

    // Positions of every corner, 3 per corner.
    std::vector<double> evaluate(int anim_index, double t) const {
        const size_t n = model.nodes.size();
        // Local transforms: node TRS (or matrix), then animated TRS overrides.
        std::vector<RefTrs> trs(n);
        std::vector<bool> has_matrix(n, false);
        std::vector<dmat4> matrix(n, dmat4(1.0));
        std::vector<std::vector<double>> weights(n);
        for (size_t i = 0; i < n; ++i) {
            const tinygltf::Node& node = model.nodes[i];
            if (node.matrix.size() == 16) {
                has_matrix[i] = true;
                for (int k = 0; k < 16; ++k) matrix[i][k / 4][k % 4] = node.matrix[size_t(k)];
            }
            if (node.translation.size() == 3)
                trs[i].t = dvec3(node.translation[0], node.translation[1], node.translation[2]);
            if (node.rotation.size() == 4)
                trs[i].r =
                    dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            if (node.scale.size() == 3)
                trs[i].s = dvec3(node.scale[0], node.scale[1], node.scale[2]);
            if (node.mesh >= 0) {
                const size_t nt = target_count(model, node.mesh);
                const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
                weights[i].assign(nt, 0.0);
                if (node.weights.size() == nt) {
                    weights[i] = node.weights;
                } else if (mesh.weights.size() == nt) {
                    weights[i] = mesh.weights;
                }
            }
        }
        if (anim_index >= 0) {
            const tinygltf::Animation& anim = model.animations[size_t(anim_index)];
            for (const tinygltf::AnimationChannel& ch : anim.channels) {
                const size_t i = size_t(ch.target_node);
                if (ch.target_path == "weights") {
                    weights[i] = eval_sampler(model, anim, ch.sampler, t, weights[i].size(), false);
                    continue;
                }
                has_matrix[i] = false;  // §3.11: animated nodes MUST use TRS
                if (ch.target_path == "translation") {
                    const auto v = eval_sampler(model, anim, ch.sampler, t, 3, false);
                    trs[i].t = dvec3(v[0], v[1], v[2]);
                } else if (ch.target_path == "rotation") {
                    const auto v = eval_sampler(model, anim, ch.sampler, t, 4, true);
                    trs[i].r = dquat(v[3], v[0], v[1], v[2]);
                } else if (ch.target_path == "scale") {
                    const auto v = eval_sampler(model, anim, ch.sampler, t, 3, false);
                    trs[i].s = dvec3(v[0], v[1], v[2]);
                }
            }
        }
        // Global transforms, §3.5.3: parent's global * local, from the roots.
        std::vector<dmat4> global(n, dmat4(1.0));
        std::vector<int> parent(n, -1);
        for (size_t i = 0; i < n; ++i) {
            for (int c : model.nodes[i].children) parent[size_t(c)] = int(i);
        }
        std::vector<bool> done(n, false);
        for (size_t i = 0; i < n; ++i) {
            // Walk up to the first computed ancestor, then down.
            std::vector<size_t> chain;
            for (int j = int(i); j >= 0 && !done[size_t(j)]; j = parent[size_t(j)]) {
                chain.push_back(size_t(j));
            }
            for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
                const size_t j = *it;
                const dmat4 local = has_matrix[j] ? matrix[j] : trs_matrix(trs[j]);
                global[j] = parent[j] >= 0 ? global[size_t(parent[j])] * local : local;
                done[j] = true;
            }
        }
        // Joint matrices of each skin, §3.7.3.
        std::vector<std::vector<dmat4>> joint_matrices;
        for (const tinygltf::Skin& skin : model.skins) {
            std::vector<double> ibm;
            if (skin.inverseBindMatrices >= 0) ibm = read_doubles(model, skin.inverseBindMatrices);
            std::vector<dmat4> jm;
            for (size_t j = 0; j < skin.joints.size(); ++j) {
                dmat4 inverse_bind(1.0);
                if (!ibm.empty()) {
                    for (int k = 0; k < 16; ++k)
                        inverse_bind[k / 4][k % 4] = ibm[16 * j + size_t(k)];
                }
                jm.push_back(global[size_t(skin.joints[j])] * inverse_bind);
            }
            joint_matrices.push_back(std::move(jm));
        }
        // Attribute cache per (mesh, primitive).
        std::vector<double> out;
        out.reserve(corners.size() * 3);
        const tinygltf::Primitive* cached = nullptr;
        std::vector<double> pos, joints, wts;
        std::vector<std::vector<double>> deltas;
        for (const RefCorner& c : corners) {
            const tinygltf::Primitive& prim = model.meshes[size_t(c.mesh)].primitives[c.prim];
            if (&prim != cached) {
                cached = &prim;
                pos = read_doubles(model, prim.attributes.at("POSITION"));
                deltas.clear();
                for (const auto& target : prim.targets) {
                    const auto it = target.find("POSITION");
                    deltas.push_back(it == target.end() ? std::vector<double>(pos.size(), 0.0)
                                                        : read_doubles(model, it->second));
                }
                const auto j = prim.attributes.find("JOINTS_0");
                joints = j == prim.attributes.end() ? std::vector<double>()
                                                    : read_doubles(model, j->second);
                const auto w = prim.attributes.find("WEIGHTS_0");
                wts = w == prim.attributes.end() ? std::vector<double>()
                                                 : read_doubles(model, w->second);
            }
            // Morph targets first (§3.7.2.2), then skinning or the node's transform.
            dvec3 p(pos[3 * c.vertex], pos[3 * c.vertex + 1], pos[3 * c.vertex + 2]);
            for (size_t k = 0; k < deltas.size(); ++k) {
                const double w = weights[size_t(c.node)][k];
                p += w * dvec3(deltas[k][3 * c.vertex], deltas[k][3 * c.vertex + 1],
                               deltas[k][3 * c.vertex + 2]);
            }
            const tinygltf::Node& node = model.nodes[size_t(c.node)];
            dvec4 world;
            if (node.skin >= 0 && !joints.empty()) {
                // §3.7.3: the skinned mesh node's own transform is ignored.
                // §3.7.3.3: weights MUST sum to 1. CesiumMan and RiggedFigure ship
                // unnormalised ones (vertex 0 of CesiumMan sums to 0.685); like common
                // viewers (three.js normalizeSkinWeights) and the importer, the reference
                // divides by the sum.
                double sum = 0;
                for (int k = 0; k < 4; ++k) sum += wts[4 * c.vertex + size_t(k)];
                dmat4 skin_matrix(0.0);
                for (int k = 0; k < 4; ++k) {
                    skin_matrix +=
                        wts[4 * c.vertex + size_t(k)] / sum *
                        joint_matrices[size_t(node.skin)][size_t(joints[4 * c.vertex + size_t(k)])];
                }
                world = skin_matrix * dvec4(p, 1.0);
            } else {
                world = global[size_t(c.node)] * dvec4(p, 1.0);
            }
            out.insert(out.end(), {world.x, world.y, world.z});
        }
        return out;
    }
};

// ---------------------------------------------------------------------------------------
// The pipeline under test

struct Pipeline {
    stipple::bake::RawScene scene;
    stipple::bake::RawAnimView view;
    std::vector<stipple::anim::Trs> locals;
    std::vector<glm::mat4> models, palette;
    std::vector<float> morph_weights, morphed_p, morphed_n, out_p, out_n, out_p_scalar,
        out_n_scalar;
    std::vector<uint32_t> cursors;
    stipple::anim::SamplingContext context;
    stipple::Asset asset;  // when loaded through the .stip asset

    // through_asset: bake the scene into a .stip asset (quantised clips) and sample the
    // clips the runtime loader decoded, instead of the importer's float keys.
    bool load(const std::string& path, std::string* error, bool through_asset = false) {
        if (!stipple::test::bake_ok(stipple::bake::import_gltf(path, &scene), error)) return false;
        stipple::bake::make_anim_view(scene, &view);
        if (through_asset) {
            stipple::bake::PointHierarchy points;  // one point: the asset needs a hierarchy
            points.host_triangle = {0};
            points.bary_u = {0.3f};
            points.bary_v = {0.3f};
            points.radius = {1.0f};
            points.neighbour_offsets = {0, 0};
            std::vector<uint8_t> bytes = stipple::bake::encode_asset(scene, points);
            stipple::Status st = stipple::load_asset_memory(bytes.data(), bytes.size(), &asset);
            if (!st.ok()) {
                *error = st.message;
                return false;
            }
            view.clips.assign(asset.clips, asset.clips + asset.clip_count);
        }
        const size_t n = scene.nodes.size(), nv = scene.vertex_count();
        locals.resize(n);
        models.resize(n);
        palette.resize(scene.joint_nodes.size());
        morph_weights.resize(scene.morph_weights.size());
        morphed_p.resize(nv * 3);
        morphed_n.resize(nv * 3);
        out_p.resize(nv * 3);
        out_n.resize(nv * 3);
        out_p_scalar.resize(nv * 3);
        out_n_scalar.resize(nv * 3);
        size_t max_channels = 0;
        for (const auto& c : view.clips)
            max_channels = std::max<size_t>(max_channels, c.channel_count);
        cursors.resize(max_channels);
        context.cursors = stipple::anim::Span<uint32_t>(cursors.data(), cursors.size());
        return true;
    }

    void pose(size_t clip, float t) {
        using namespace stipple::anim;
        SamplingJob sampling;
        sampling.skeleton = &view.skeleton;
        sampling.clip = &view.clips[clip];
        sampling.time = t;
        sampling.context = &context;
        sampling.locals = {locals.data(), locals.size()};
        sampling.morph_weights = {morph_weights.data(), morph_weights.size()};
        sampling.default_morph_weights = {scene.morph_weights.data(), scene.morph_weights.size()};
        ASSERT_TRUE(sampling.run());
        LocalToModelJob l2m;
        l2m.skeleton = &view.skeleton;
        l2m.locals = {locals.data(), locals.size()};
        l2m.models = {models.data(), models.size()};
        ASSERT_TRUE(l2m.run());
        JointMatrixJob jm;
        jm.skeleton = &view.skeleton;
        jm.models = {models.data(), models.size()};
        jm.joint_matrices = {palette.data(), palette.size()};
        ASSERT_TRUE(jm.run());
        const uint32_t nv = uint32_t(scene.vertex_count());
        MorphJob morph;
        morph.morph = &view.morph;
        morph.vertex_count = nv;
        morph.weights = {morph_weights.data(), morph_weights.size()};
        morph.in_positions = {scene.positions.data(), scene.positions.size()};
        morph.in_normals = {scene.normals.data(), scene.normals.size()};
        morph.out_positions = {morphed_p.data(), morphed_p.size()};
        morph.out_normals = {morphed_n.data(), morphed_n.size()};
        ASSERT_TRUE(morph.run());
        SkinningJob skin;
        skin.vertex_count = nv;
        skin.joint_matrices = {palette.data(), palette.size()};
        skin.joints = {scene.joints.data(), scene.joints.size()};
        skin.weights = {scene.weights.data(), scene.weights.size()};
        skin.in_positions = {morphed_p.data(), morphed_p.size()};
        skin.in_normals = {morphed_n.data(), morphed_n.size()};
        skin.out_positions = {out_p.data(), out_p.size()};
        skin.out_normals = {out_n.data(), out_n.size()};
        ASSERT_TRUE(skin.run());
        skin.out_positions = {out_p_scalar.data(), out_p_scalar.size()};
        skin.out_normals = {out_n_scalar.data(), out_n_scalar.size()};
        ASSERT_TRUE(skin.run_scalar());
    }
};

struct Errors {
    double diagonal = 0;
    double max_error = 0;         // SIMD path vs reference
    double max_error_scalar = 0;  // scalar path vs reference
    size_t samples = 0;
};

// Samples every clip at 26 times (both ends and 24 interior times off the key grid).
Errors compare_with_reference(const std::string& path, bool through_asset = false) {
    Errors e;
    Reference ref;
    EXPECT_TRUE(ref.load(path)) << path;
    Pipeline pipe;
    std::string error;
    EXPECT_TRUE(pipe.load(path, &error, through_asset)) << error;
    if (::testing::Test::HasFailure()) return e;
    EXPECT_EQ(pipe.scene.indices.size(), ref.corners.size()) << "corner lists differ";
    EXPECT_EQ(pipe.view.clips.size(), ref.model.animations.size());
    if (::testing::Test::HasFailure()) return e;
    dvec3 lo(1e300), hi(-1e300);
    std::vector<std::pair<size_t, std::vector<double>>> frames;
    for (size_t a = 0; a < ref.model.animations.size(); ++a) {
        const double duration = pipe.view.clips[a].duration;
        for (int i = 0; i < 26; ++i) {
            const double t = i == 0 ? 0.0 : i == 25 ? duration : duration * (i - 0.63) / 24.0;
            const std::vector<double> want = ref.evaluate(int(a), t);
            pipe.pose(a, float(t));
            for (size_t c = 0; c < ref.corners.size(); ++c) {
                const dvec3 w(want[3 * c], want[3 * c + 1], want[3 * c + 2]);
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
                const size_t v = pipe.scene.indices[c];
                const dvec3 got(pipe.out_p[3 * v], pipe.out_p[3 * v + 1], pipe.out_p[3 * v + 2]);
                const dvec3 got_s(pipe.out_p_scalar[3 * v], pipe.out_p_scalar[3 * v + 1],
                                  pipe.out_p_scalar[3 * v + 2]);
                e.max_error = std::max(e.max_error, glm::length(got - w));
                e.max_error_scalar = std::max(e.max_error_scalar, glm::length(got_s - w));
            }
            ++e.samples;
        }
    }
    e.diagonal = glm::length(hi - lo);
    std::printf(
        "[reference%s] %s: %zu samples, %zu corners, bbox diagonal %.4g, max error %.3g "
        "(%.3g of diagonal; scalar path %.3g)\n",
        through_asset ? ", via .stip" : "", path.substr(path.find_last_of('/') + 1).c_str(),
        e.samples, ref.corners.size(), e.diagonal, e.max_error, e.max_error / e.diagonal,
        e.max_error_scalar / e.diagonal);
    return e;
}

void expect_within_bound(const std::string& path, bool through_asset = false) {
    const Errors e = compare_with_reference(path, through_asset);
    ASSERT_GT(e.samples, 0u);
    EXPECT_GT(e.diagonal, 0.0);
    EXPECT_LE(e.max_error, 1e-4 * e.diagonal) << path;
    EXPECT_LE(e.max_error_scalar, 1e-4 * e.diagonal) << path;
}

std::string asset(const char* name) {
    return std::string(STIPPLE_SOURCE_DIR) + "/assets/" + name;
}

TEST(AnimReference, CesiumMan) {
    expect_within_bound(asset("CesiumMan/CesiumMan.glb"));
}

// The same bound holds after the bake quantises the clips (16-bit codes over per-column
// ranges, docs/format.md) and the runtime loader decodes them.
TEST(AnimReference, QuantisedClipsInTheAssetStayWithinTheBound) {
    for (const char* name : {"CesiumMan/CesiumMan.glb", "RiggedFigure/RiggedFigure.glb",
                             "RiggedSimple/RiggedSimple.glb", "SimpleSkin/SimpleSkin.gltf"})
        expect_within_bound(asset(name), true);
}
TEST(AnimReference, RiggedFigure) {
    expect_within_bound(asset("RiggedFigure/RiggedFigure.glb"));
}
TEST(AnimReference, RiggedSimple) {
    expect_within_bound(asset("RiggedSimple/RiggedSimple.glb"));
}
TEST(AnimReference, SimpleSkin) {
    expect_within_bound(asset("SimpleSkin/SimpleSkin.gltf"));
}

// ---------------------------------------------------------------------------------------
// Generated assets

// A glTF under construction: one .bin buffer next to the .gltf, one bufferView per accessor.
struct GltfBuilder {
    nlohmann::json doc;
    std::vector<uint8_t> bin;

    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        doc["accessors"] = nlohmann::json::array();
        doc["bufferViews"] = nlohmann::json::array();
    }
    int add(const void* data, size_t bytes, int component_type, size_t count, const char* type,
            bool normalized = false) {
        while (bin.size() % 4) bin.push_back(0);
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
        const auto* p = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), p, p + bytes);
        nlohmann::json acc = {{"bufferView", doc["bufferViews"].size() - 1},
                              {"componentType", component_type},
                              {"count", count},
                              {"type", type}};
        if (normalized) acc["normalized"] = true;
        doc["accessors"].push_back(acc);
        return int(doc["accessors"].size() - 1);
    }
    int floats(const std::vector<float>& v, const char* type, size_t width) {
        return add(v.data(), v.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT, v.size() / width, type);
    }
    int vec3_with_bounds(const std::vector<float>& v) {
        const int a = floats(v, "VEC3", 3);
        std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
        for (size_t i = 0; i < v.size(); ++i) {
            lo[i % 3] = std::min(lo[i % 3], v[i]);
            hi[i % 3] = std::max(hi[i % 3], v[i]);
        }
        doc["accessors"][size_t(a)]["min"] = lo;
        doc["accessors"][size_t(a)]["max"] = hi;
        return a;
    }
    std::string write(const std::string& name) {
        const std::string bin_name = name + ".bin";  // the .gltf's relative uri
        doc["buffers"] = {{{"uri", bin_name}, {"byteLength", bin.size()}}};
        std::ofstream(stipple::test::scratch_path(bin_name), std::ios::binary)
            .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
        const std::string path = stipple::test::scratch_path(name + ".gltf");
        std::ofstream(path) << doc.dump(1);
        return path;
    }
};

// A vertical bar of `rows` quads (x in {-0.25, 0.25}, y = 0 .. rows * 0.5, z = 0) skinned to
// two joints at y = 0 and y = 1, weights blending over the middle (vertices carry 1 or 2
// influences; one vertex set gives a third, tiny influence to exercise 3-influence blocks).
struct Bar {
    std::vector<float> positions, normals, weights;
    std::vector<uint8_t> joints;
    std::vector<uint16_t> indices;
    explicit Bar(int rows) {
        for (int r = 0; r <= rows; ++r) {
            for (int c = 0; c < 2; ++c) {
                const float y = 0.5f * float(r);
                positions.insert(positions.end(), {c == 0 ? -0.25f : 0.25f, y, 0.0f});
                normals.insert(normals.end(), {0.0f, 0.0f, 1.0f});
                const float w1 = std::min(std::max((y - 0.5f) / 1.0f, 0.0f), 1.0f);
                joints.insert(joints.end(), {0, 1, 0, 0});
                weights.insert(weights.end(), {1.0f - w1, w1, 0.0f, 0.0f});
            }
        }
        for (int r = 0; r < rows; ++r) {
            const uint16_t a = uint16_t(2 * r), b = uint16_t(a + 1), c = uint16_t(a + 2),
                           d = uint16_t(a + 3);
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    }
};

TEST(AnimReference, GeneratedCubicSplineClip) {
    // Two joints (node 1 root joint at the origin, node 2 its child at y = 1), a skinned bar
    // on node 0. Clip "Cubic": CUBICSPLINE translation, rotation and scale on both joints
    // with non-zero tangents, plus a LINEAR and a STEP channel in a second clip.
    GltfBuilder g;
    Bar bar(6);
    const int pos = g.vec3_with_bounds(bar.positions);
    const int nrm = g.floats(bar.normals, "VEC3", 3);
    const int jnt = g.add(bar.joints.data(), bar.joints.size(),
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, bar.joints.size() / 4, "VEC4");
    const int wgt = g.floats(bar.weights, "VEC4", 4);
    const int idx = g.add(bar.indices.data(), bar.indices.size() * 2,
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, bar.indices.size(), "SCALAR");
    const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,  //
                                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    const int ibm_acc = g.floats(ibm, "MAT4", 16);
    const std::vector<float> times = {0.0f, 0.4f, 1.1f, 1.5f};
    const int in = g.floats(times, "SCALAR", 1);
    // (in-tangent, value, out-tangent) per key.
    const std::vector<float> tr = {0,     0,    0, 0,     0,    0,     0.5f, 0.2f,  0,     //
                                   -0.3f, 0.4f, 0, 0.2f,  0.1f, 0.1f,  0.6f, -0.2f, 0.3f,  //
                                   1,     0,    0, -0.1f, 0.3f, 0.0f,  0.2f, 0.2f,  0.2f,  //
                                   0,     0,    0, 0.1f,  0,    -0.2f, 0,    0,     0};
    const float h = std::sqrt(0.5f);
    const std::vector<float> rot = {
        0,    0,    0,    0, 0, 0,           0, 1,           0,    0,     0.8f,  0.1f,  //
        0.1f, 0,    0.5f, 0, 0, 0,           h, h,           0.2f, 0.1f,  -0.4f, 0,     //
        0,    0.3f, 0.2f, 0, h, 0,           0, h,           0,    -0.5f, 0.1f,  0.2f,  //
        0,    0,    0.3f, 0, 0, 0.38268343f, 0, 0.92387953f, 0,    0,     0,     0};
    const std::vector<float> scl = {0,    0,    0,    1,    1,    1,    0.5f, 0,     0,     //
                                    0,    0.3f, 0,    1.2f, 0.9f, 1,    0,    -0.4f, 0.2f,  //
                                    0.1f, 0.1f, 0.1f, 0.8f, 1.1f, 1.3f, 0,    0,     0,     //
                                    0,    0,    0,    1,    1,    1,    0,    0,     0};
    const int out_t = g.floats(tr, "VEC3", 3);
    const int out_r = g.floats(rot, "VEC4", 4);
    const int out_s = g.floats(scl, "VEC3", 3);
    const int lin_out = g.floats({0, 1, 0, 0.3f, 1.2f, 0, -0.2f, 0.8f, 0.1f, 0, 1, 0}, "VEC3", 3);
    const int step_out = g.floats({1, 1, 1, 1.5f, 1, 1, 1, 0.7f, 1, 1, 1, 1}, "VEC3", 3);
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    g.doc["nodes"] = {{{"mesh", 0}, {"skin", 0}},
                      {{"children", {2}}, {"translation", {0.0, 0.0, 0.0}}},
                      {{"translation", {0.0, 1.0, 0.0}}}};
    g.doc["meshes"] = {
        {{"primitives",
          {{{"attributes",
             {{"POSITION", pos}, {"NORMAL", nrm}, {"JOINTS_0", jnt}, {"WEIGHTS_0", wgt}}},
            {"indices", idx}}}}}};
    g.doc["skins"] = {{{"joints", {1, 2}}, {"inverseBindMatrices", ibm_acc}}};
    g.doc["animations"] = {
        {{"name", "Cubic"},
         {"samplers",
          {{{"input", in}, {"output", out_t}, {"interpolation", "CUBICSPLINE"}},
           {{"input", in}, {"output", out_r}, {"interpolation", "CUBICSPLINE"}},
           {{"input", in}, {"output", out_s}, {"interpolation", "CUBICSPLINE"}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
           {{"sampler", 1}, {"target", {{"node", 2}, {"path", "rotation"}}}},
           {{"sampler", 2}, {"target", {{"node", 2}, {"path", "scale"}}}},
           {{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}},
        {{"name", "LinearStep"},
         {"samplers",
          {{{"input", in}, {"output", lin_out}, {"interpolation", "LINEAR"}},
           {{"input", in}, {"output", step_out}, {"interpolation", "STEP"}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "translation"}}}},
           {{"sampler", 1}, {"target", {{"node", 1}, {"path", "scale"}}}}}}}};
    const std::string path = g.write("cubic_bar");
    stipple::bake::RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(stipple::bake::import_gltf(path, &s), &error)) << error;
    ASSERT_EQ(s.clips.size(), 2u);
    EXPECT_EQ(s.clips[0].channels[0].interp, stipple::bake::RawInterp::cubic_spline);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    expect_within_bound(path);
    expect_within_bound(path, true);  // and through the quantised .stip clips
}

TEST(AnimReference, GeneratedMorphTargets) {
    // Node 0: the skinned bar (mesh 0) with 2 morph targets (POSITION + NORMAL deltas),
    // default weights from mesh.weights, animated by a LINEAR weights channel. Node 3: a
    // rigid (unskinned) copy of a small triangle mesh (mesh 1, 3 targets, POSITION only),
    // child of joint node 2, with node.weights overriding the mesh's defaults and a
    // CUBICSPLINE weights channel. Both mesh nodes also move through the skeleton.
    GltfBuilder g;
    Bar bar(4);
    const size_t nv = bar.positions.size() / 3;
    std::vector<float> d0, d1, n0, n1;
    for (size_t v = 0; v < nv; ++v) {
        const float y = bar.positions[3 * v + 1];
        d0.insert(d0.end(), {0.3f * y, 0.0f, 0.0f});
        d1.insert(d1.end(), {0.0f, 0.1f * y * y, 0.2f * (bar.positions[3 * v] > 0 ? 1.0f : -1.0f)});
        n0.insert(n0.end(), {0.2f, 0.0f, 0.0f});
        n1.insert(n1.end(), {0.0f, 0.1f, -0.1f});
    }
    const int pos = g.vec3_with_bounds(bar.positions);
    const int nrm = g.floats(bar.normals, "VEC3", 3);
    const int jnt = g.add(bar.joints.data(), bar.joints.size(),
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, bar.joints.size() / 4, "VEC4");
    const int wgt = g.floats(bar.weights, "VEC4", 4);
    const int idx = g.add(bar.indices.data(), bar.indices.size() * 2,
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, bar.indices.size(), "SCALAR");
    const int t0 = g.vec3_with_bounds(d0), t1 = g.vec3_with_bounds(d1);
    const int tn0 = g.floats(n0, "VEC3", 3), tn1 = g.floats(n1, "VEC3", 3);
    // Mesh 1: one triangle, 3 POSITION targets.
    const int tri = g.vec3_with_bounds({0, 0, 0, 0.3f, 0, 0, 0, 0.3f, 0});
    const int m0 = g.vec3_with_bounds({0, 0, 0.2f, 0, 0, 0, 0, 0, 0});
    const int m1 = g.vec3_with_bounds({0, 0, 0, 0.1f, 0.1f, 0, 0, 0, 0});
    const int m2 = g.vec3_with_bounds({0, 0, 0, 0, 0, 0, -0.1f, 0, 0.3f});
    const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,  //
                                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    const int ibm_acc = g.floats(ibm, "MAT4", 16);
    const int in = g.floats({0.0f, 0.5f, 1.0f, 2.0f}, "SCALAR", 1);
    const int w_lin = g.floats({0, 0, 1, 0.5f, 0.2f, 1, 0.8f, -0.3f}, "SCALAR", 1);
    std::vector<float> w_cubic;  // 4 keys x (in, value, out) x 3 weights
    for (int k = 0; k < 4; ++k) {
        const float base = 0.25f * float(k);
        w_cubic.insert(w_cubic.end(),
                       {0.5f, -0.2f, 0.1f, base, 1 - base, 0.5f * base, -0.4f, 0.3f, 0.2f});
    }
    const int w_cub = g.floats(w_cubic, "SCALAR", 1);
    const int rot_out = g.floats(
        {0, 0, 0, 1, 0, 0, 0.2588190f, 0.9659258f, 0, 0, 0.5f, 0.8660254f, 0, 0, 0, 1}, "VEC4", 4);
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    g.doc["nodes"] = {
        {{"mesh", 0}, {"skin", 0}},
        {{"children", {2}}},
        {{"translation", {0.0, 1.0, 0.0}}, {"children", {3}}},
        {{"mesh", 1}, {"translation", {0.4, 0.2, 0.0}}, {"weights", {0.3, 0.0, 0.6}}}};
    g.doc["meshes"] = {
        {{"primitives",
          {{{"attributes",
             {{"POSITION", pos}, {"NORMAL", nrm}, {"JOINTS_0", jnt}, {"WEIGHTS_0", wgt}}},
            {"indices", idx},
            {"targets",
             {{{"POSITION", t0}, {"NORMAL", tn0}}, {{"POSITION", t1}, {"NORMAL", tn1}}}}}}},
         {"weights", {0.5, 0.25}}},
        {{"primitives",
          {{{"attributes", {{"POSITION", tri}}},
            {"targets", {{{"POSITION", m0}}, {{"POSITION", m1}}, {{"POSITION", m2}}}}}}},
         {"weights", {1.0, 1.0, 1.0}}}};
    g.doc["skins"] = {{{"joints", {1, 2}}, {"inverseBindMatrices", ibm_acc}}};
    g.doc["animations"] = {
        {{"name", "Morph"},
         {"samplers",
          {{{"input", in}, {"output", w_lin}, {"interpolation", "LINEAR"}},
           {{"input", in}, {"output", w_cub}, {"interpolation", "CUBICSPLINE"}},
           {{"input", in}, {"output", rot_out}, {"interpolation", "LINEAR"}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}},
           {{"sampler", 1}, {"target", {{"node", 3}, {"path", "weights"}}}},
           {{"sampler", 2}, {"target", {{"node", 2}, {"path", "rotation"}}}}}}},
        // No weights channel: the defaults (mesh.weights for node 0, node.weights for node 3).
        {{"name", "Defaults"},
         {"samplers", {{{"input", in}, {"output", rot_out}, {"interpolation", "LINEAR"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}};
    const std::string path = g.write("morph");
    stipple::bake::RawScene s;
    std::string error;
    ASSERT_TRUE(stipple::test::bake_ok(stipple::bake::import_gltf(path, &s), &error)) << error;
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    // Slots: node 0 has 2 (defaults from the mesh), node 3 has 3 (defaults from the node).
    EXPECT_EQ(s.morph_weights, (std::vector<float>{0.5f, 0.25f, 0.3f, 0.0f, 0.6f}));
    ASSERT_EQ(s.morph_targets.size(), 5u);
    EXPECT_EQ(s.morph_targets[0].normal_deltas.size(), s.morph_targets[0].position_deltas.size());
    EXPECT_TRUE(s.morph_targets[2].normal_deltas.empty());
    ASSERT_EQ(s.clips.size(), 2u);
    EXPECT_EQ(s.clips[0].channels[0].path, stipple::bake::RawPath::weights);
    EXPECT_EQ(s.clips[0].channels[0].weight_begin, 0u);
    EXPECT_EQ(s.clips[0].channels[0].weight_count, 2u);
    EXPECT_EQ(s.clips[0].channels[1].weight_begin, 2u);
    EXPECT_EQ(s.clips[0].channels[1].values.size(), 4u * 3u * 3u);
    expect_within_bound(path);
    expect_within_bound(path, true);  // and through the quantised .stip clips
}

}  // namespace
