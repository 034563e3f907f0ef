// make-stretch-tube: writes the "stretch tube" test asset, a skinned closed tube whose upper part
// is scaled 2x along its axis by an animation. Non-uniform joint scale stretches the surface far
// more than any of the rigged characters do, so it exercises what happens to stipple density when
// the area of host faces changes under skinning.
//
// The geometry (glTF 2.0 conventions: +Y up, counter-clockwise front faces, outward normals):
//   - side: radius 0.25 around +Y from y = 0 to y = 2, `segments_around` x `segments_along` quads;
//   - caps: flat triangle fans at y = 0 and y = 2 around a centre vertex, with their own copies of
//     the rim vertices so that they carry the cap normal.
// The rig: "lower" at the origin, "upper" its child at (0, 0.5, 0). A vertex is bound to lower
// below y = 0.45, to upper above y = 0.55, and blended linearly in between.
// Animations: "stretch" scales upper by (1,1,1) -> (1,2,1) -> (1,1,1) at t = 0, 1, 2 s (so the
// top reaches y = 3.5 at t = 1); "rest" holds scale (1,1,1) so a player can show the bind pose;
// "sweep" scales upper along Y linearly from 0.5 to 2.5 over t = 0..2 s (scale = 0.5 + t), for
// measuring tone across the whole range of stretch (docs/measure.md).

#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "tools/cli_options.h"
#include "tools/gltf_build.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kRadius = 0.25f;
constexpr float kLength = 2.0f;
constexpr float kUpperJointY = 0.5f;
constexpr float kBlendBegin = 0.45f;  // at or below: weight 1 on "lower"
constexpr float kBlendEnd = 0.55f;    // at or above: weight 1 on "upper"
constexpr int kDefaultSegmentsAround = 48;
constexpr int kDefaultSegmentsAlong = 64;
constexpr int kMaxSegments = 4096;

using stipple::tools::gltf_build::add_values;
using stipple::tools::gltf_build::kArrayBuffer;
using stipple::tools::gltf_build::kElementArrayBuffer;

struct Options {
    std::string out_path;
    int segments_around = kDefaultSegmentsAround;
    int segments_along = kDefaultSegmentsAlong;
};

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    uint8_t joints[4];
    float weights[4];
};

struct TubeMesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // triangles
};

std::string usage() {
    char text[800];
    std::snprintf(
        text, sizeof(text),
        "usage: make-stretch-tube OUT.gltf [--segments-around N] [--segments-along M]\n"
        "  Writes a skinned closed tube (radius 0.25, y from 0 to 2) with joints \"lower\"\n"
        "  and \"upper\" and animations \"stretch\" (upper scaled 1 -> 2 -> 1 along Y over\n"
        "  2 s), \"rest\" and \"sweep\" (upper scaled 0.5 -> 2.5 along Y over 2 s), as glTF\n"
        "  with an embedded buffer.\n"
        "  --segments-around N   quads around the tube, 3..%d (default %d)\n"
        "  --segments-along M    quads along the tube, 1..%d (default %d)\n"
        "  -h, --help            this text\n",
        kMaxSegments, kDefaultSegmentsAround, kMaxSegments, kDefaultSegmentsAlong);
    return text;
}

// Bad options end the tool with a one-line error and exit status 1.
Options parse_options(int argc, char** argv) {
    Options options;
    const std::string text = usage();
    stipple::cli::Parser p("make-stretch-tube", text.c_str());
    p.positional("output path", &options.out_path)
        .integer("--segments-around", 3, kMaxSegments, &options.segments_around)
        .integer("--segments-along", 1, kMaxSegments, &options.segments_along);
    p.parse(argc, argv);
    if (options.out_path.empty()) p.fail("no output path (see --help)");
    return options;
}

// Rigid below kBlendBegin, rigid above kBlendEnd, linear in between.
void set_skin_weights(Vertex* v) {
    const float y = v->position.y;
    float upper = 0.0f;
    if (y >= kBlendEnd) {
        upper = 1.0f;
    } else if (y > kBlendBegin) {
        upper = (y - kBlendBegin) / (kBlendEnd - kBlendBegin);
    }
    v->joints[0] = 0;
    v->joints[1] = 1;
    v->joints[2] = 0;
    v->joints[3] = 0;
    v->weights[0] = 1.0f - upper;
    v->weights[1] = upper;
    v->weights[2] = 0.0f;
    v->weights[3] = 0.0f;
}

TubeMesh build_tube(int around, int along) {
    TubeMesh mesh;
    const auto ring_point = [&](int i, float y, glm::vec3* position, glm::vec3* normal) {
        // x = r sin(theta), z = r cos(theta): increasing i then walks counter-clockwise when seen
        // from outside, which the index order below relies on.
        const double theta = 2.0 * kPi * i / around;
        const float s = static_cast<float>(std::sin(theta));
        const float c = static_cast<float>(std::cos(theta));
        *position = glm::vec3(kRadius * s, y, kRadius * c);
        *normal = glm::vec3(s, 0.0f, c);
    };
    const auto add_vertex = [&](const glm::vec3& position, const glm::vec3& normal) {
        Vertex v{};
        v.position = position;
        v.normal = normal;
        set_skin_weights(&v);
        mesh.vertices.push_back(v);
        return static_cast<uint32_t>(mesh.vertices.size() - 1);
    };

    // Side: rings k = 0..along, no seam duplicate (the asset has no texture coordinates).
    for (int k = 0; k <= along; ++k) {
        const float y = kLength * static_cast<float>(k) / static_cast<float>(along);
        for (int i = 0; i < around; ++i) {
            glm::vec3 p, n;
            ring_point(i, y, &p, &n);
            add_vertex(p, n);
        }
    }
    const auto side = [&](int k, int i) { return static_cast<uint32_t>(k * around + i % around); };
    for (int k = 0; k < along; ++k) {
        for (int i = 0; i < around; ++i) {
            const uint32_t a = side(k, i), b = side(k, i + 1);
            const uint32_t c = side(k + 1, i + 1), d = side(k + 1, i);
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
    }

    // Caps: a centre vertex and a copy of the rim carrying the cap normal.
    for (int top = 0; top < 2; ++top) {
        const float y = top ? kLength : 0.0f;
        const glm::vec3 cap_normal(0.0f, top ? 1.0f : -1.0f, 0.0f);
        const uint32_t centre = add_vertex(glm::vec3(0.0f, y, 0.0f), cap_normal);
        for (int i = 0; i < around; ++i) {
            glm::vec3 p, n;
            ring_point(i, y, &p, &n);
            add_vertex(p, cap_normal);
        }
        for (int i = 0; i < around; ++i) {
            const uint32_t r0 = centre + 1 + static_cast<uint32_t>(i);
            const uint32_t r1 = centre + 1 + static_cast<uint32_t>((i + 1) % around);
            if (top) {
                mesh.indices.insert(mesh.indices.end(), {centre, r0, r1});
            } else {
                mesh.indices.insert(mesh.indices.end(), {centre, r1, r0});
            }
        }
    }
    return mesh;
}

// Every triangle's geometric normal must agree with its vertices' normals, i.e. it is
// counter-clockwise seen from outside (glTF 2.0 spec, "Meshes").
bool winding_is_outward(const TubeMesh& mesh) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vertex& a = mesh.vertices[mesh.indices[t]];
        const Vertex& b = mesh.vertices[mesh.indices[t + 1]];
        const Vertex& c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(face, a.normal + b.normal + c.normal) <= 0.0f) return false;
    }
    return true;
}

// Adds an animation of one sampler that drives `node`'s scale through `scales` at `times`.
void add_scale_animation(tinygltf::Model* model, const char* name, int node,
                         const std::vector<float>& times, const std::vector<glm::vec3>& scales) {
    std::vector<float> values;
    for (const glm::vec3& s : scales) values.insert(values.end(), {s.x, s.y, s.z});
    // Sampler inputs must carry min and max (glTF 2.0 spec, "Animations": input accessors must have
    // min and max).
    const int input =
        add_values(model, times, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                   times.size(), {times.front()}, {times.back()});
    const int output = add_values(model, values, 0, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                  TINYGLTF_TYPE_VEC3, scales.size());
    tinygltf::AnimationSampler sampler;
    sampler.input = input;
    sampler.output = output;
    sampler.interpolation = "LINEAR";
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = node;
    channel.target_path = "scale";
    tinygltf::Animation animation;
    animation.name = name;
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    model->animations.push_back(animation);
}

// The tube's one primitive: vertex attributes (one tightly packed view each) and indices.
tinygltf::Primitive add_tube_primitive(tinygltf::Model* model_out, const TubeMesh& mesh) {
    tinygltf::Model& model = *model_out;
    // Vertex attributes, one tightly packed view each.
    std::vector<float> positions, normals, weights;
    std::vector<uint8_t> joints;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vertex& v : mesh.vertices) {
        positions.insert(positions.end(), {v.position.x, v.position.y, v.position.z});
        normals.insert(normals.end(), {v.normal.x, v.normal.y, v.normal.z});
        joints.insert(joints.end(), v.joints, v.joints + 4);
        weights.insert(weights.end(), v.weights, v.weights + 4);
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    const size_t n = mesh.vertices.size();
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    // POSITION must carry min and max (glTF 2.0 spec, "Meshes").
    primitive.attributes["POSITION"] =
        add_values(&model, positions, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_FLOAT,
                   TINYGLTF_TYPE_VEC3, n, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    primitive.attributes["NORMAL"] = add_values(
        &model, normals, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    primitive.attributes["JOINTS_0"] = add_values(
        &model, joints, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, n);
    primitive.attributes["WEIGHTS_0"] = add_values(
        &model, weights, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n);
    if (n <= 65535) {
        std::vector<uint16_t> indices(mesh.indices.begin(), mesh.indices.end());
        primitive.indices =
            add_values(&model, indices, kElementArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                       TINYGLTF_TYPE_SCALAR, indices.size());
    } else {
        primitive.indices = add_values(&model, mesh.indices, kElementArrayBuffer,
                                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                       mesh.indices.size());
    }
    return primitive;
}

// Nodes 0 "lower" (joint root), 1 "upper" (its child), 2 the skinned mesh, and the skin.
void add_rig(tinygltf::Model* model_out) {
    tinygltf::Model& model = *model_out;
    tinygltf::Node lower;
    lower.name = "lower";
    lower.children = {1};
    tinygltf::Node upper;
    upper.name = "upper";
    upper.translation = {0.0, kUpperJointY, 0.0};
    tinygltf::Node tube;
    tube.name = "tube";
    tube.mesh = 0;
    tube.skin = 0;
    model.nodes = {lower, upper, tube};

    // Inverse bind matrices: the inverse of each joint's world matrix in the bind pose
    // (glTF 2.0 spec, "Skins"), column-major like glm and glTF.
    const glm::mat4 lower_world(1.0f);
    const glm::mat4 upper_world =
        lower_world * glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kUpperJointY, 0.0f));
    std::vector<float> inverse_binds;
    for (const glm::mat4& world : {lower_world, upper_world}) {
        const glm::mat4 inverse = glm::inverse(world);
        inverse_binds.insert(inverse_binds.end(), glm::value_ptr(inverse),
                             glm::value_ptr(inverse) + 16);
    }
    tinygltf::Skin skin;
    skin.name = "tube_rig";
    skin.joints = {0, 1};
    skin.skeleton = 0;
    skin.inverseBindMatrices =
        add_values(&model, inverse_binds, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, 2);
    model.skins.push_back(skin);
}

tinygltf::Model build_model(const TubeMesh& mesh) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "stipple tools/make_stretch_tube.cpp";
    model.buffers.resize(1);
    tinygltf::Mesh gltf_mesh;
    gltf_mesh.name = "tube";
    gltf_mesh.primitives.push_back(add_tube_primitive(&model, mesh));
    model.meshes.push_back(gltf_mesh);
    add_rig(&model);

    add_scale_animation(&model, "stretch", 1, {0.0f, 1.0f, 2.0f},
                        {glm::vec3(1.0f), glm::vec3(1.0f, 2.0f, 1.0f), glm::vec3(1.0f)});
    add_scale_animation(&model, "rest", 1, {0.0f}, {glm::vec3(1.0f)});
    add_scale_animation(&model, "sweep", 1, {0.0f, 2.0f},
                        {glm::vec3(1.0f, 0.5f, 1.0f), glm::vec3(1.0f, 2.5f, 1.0f)});

    tinygltf::Scene scene;
    scene.name = "stretch_tube";
    scene.nodes = {0, 2};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    return model;
}

// Reloads what was written and checks the parts a player depends on, so a writer or loader
// mismatch fails here rather than in a test far away.
bool reload_matches(const std::string& path, const tinygltf::Model& written, std::string* why) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    if (!loader.LoadASCIIFromFile(&model, &err, &warn, path)) {
        *why = "tinygltf cannot load it: " + err;
        return false;
    }
    if (model.meshes.size() != 1 || model.skins.size() != 1 || model.skins[0].joints.size() != 2 ||
        model.nodes.size() != written.nodes.size() || model.animations.size() != 3 ||
        model.animations[0].name != "stretch" || model.animations[1].name != "rest" ||
        model.animations[2].name != "sweep") {
        *why = "the reloaded scene differs in structure";
        return false;
    }
    if (model.buffers.size() != 1 || model.buffers[0].data != written.buffers[0].data) {
        *why = "the reloaded buffer differs";
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse_options(argc, argv);

    const TubeMesh mesh = build_tube(options.segments_around, options.segments_along);
    if (!winding_is_outward(mesh)) {
        std::fprintf(stderr, "make-stretch-tube: internal error: a triangle faces inward\n");
        return 1;
    }
    const tinygltf::Model model = build_model(mesh);

    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, options.out_path, /*embedImages=*/true,
                                     /*embedBuffers=*/true, /*prettyPrint=*/true,
                                     /*writeBinary=*/false)) {
        std::fprintf(stderr, "make-stretch-tube: cannot write '%s'\n", options.out_path.c_str());
        return 1;
    }
    std::string why;
    if (!reload_matches(options.out_path, model, &why)) {
        std::fprintf(stderr, "make-stretch-tube: '%s' does not reload: %s\n",
                     options.out_path.c_str(), why.c_str());
        return 1;
    }
    std::printf("make-stretch-tube: wrote %s (%zu vertices, %zu triangles)\n",
                options.out_path.c_str(), mesh.vertices.size(), mesh.indices.size() / 3);
    return 0;
}
