// glTF 2.0 importer: tinygltf parses the JSON/GLB container, everything after that (accessor
// decoding, hierarchy, skin, clips) is validated by the parts named in bake/gltf_parts.h,
// because tinygltf checks little beyond the JSON schema. Section numbers refer to the glTF
// 2.0 specification, https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html
//
// Malformed geometry, hierarchy or skin data fails the whole import with one line naming the
// problem; a malformed animation channel only drops that channel (with a warning), so one bad
// track does not cost the whole asset.
#include <algorithm>
#include <cassert>
#include <cstring>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "bake/gltf_file_access.h"
#include "bake/gltf_parts.h"
#include "bake/input_file.h"
#include "bake/scene_import.h"

namespace stipple::bake {

namespace {

using gltf::Model;

// First non-empty line of a (possibly multi-line) message, trimmed, with bytes that are not
// printable ASCII (tinygltf quotes raw input bytes) replaced by '?'.
std::string first_line(const std::string& text) {
    size_t begin = 0;
    while (begin < text.size()) {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(begin, end - begin);
        const size_t a = line.find_first_not_of(" \t\r");
        if (a != std::string::npos) {
            const size_t b = line.find_last_not_of(" \t\r");
            line = line.substr(a, b - a + 1);
            for (char& c : line) {
                if (c < 0x20 || c > 0x7e) c = '?';
            }
            return line;
        }
        begin = end + 1;
    }
    return std::string();
}

// Without looks, images are irrelevant to the bake: accept them without decoding.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
    return true;
}

// The JSON text tinygltf will parse: the whole .gltf, or a GLB's first chunk (§4.4.3
// "Chunks": 12-byte header, then chunk length, type, data). A GLB too short for a chunk
// yields nothing here; tinygltf reports it.
std::pair<const unsigned char*, size_t> json_text(const std::vector<unsigned char>& file,
                                                  bool binary) {
    if (!binary) return {file.data(), file.size()};
    if (file.size() < 20) return {file.data(), 0};
    uint32_t length = 0;
    std::memcpy(&length, file.data() + 12, 4);
    return {file.data() + 20, std::min<size_t>(length, file.size() - 20)};
}

// Reads the model file itself (a regular file under kMaxModelFileBytes), then lets
// tinygltf parse it with file callbacks that confine buffer URIs to its folder.
BakeError load_model(const std::string& path, bool looks, Model* model,
                     std::vector<std::string>* warnings) {
    std::vector<unsigned char> file;
    const BakeError read = read_input_file(path, kMaxModelFileBytes, &file);
    if (!read.ok()) return read;
    if (file.empty()) return malformed_input("not a valid glTF file: the file is empty");
    // GLB starts with the magic "glTF" (§4.4.2 "Header"); anything else is tried as JSON.
    const bool binary = file.size() >= 4 && std::memcmp(file.data(), "glTF", 4) == 0;
    const auto json = json_text(file, binary);
    const BakeError uris = gltf::check_data_uris(json.first, json.second);
    if (!uris.ok()) return uris;
    gltf::FileAccess access(path);
    tinygltf::TinyGLTF loader;
    gltf::ImageDecoding decoding;
    decoding.decode = looks;
    decoding.warnings = warnings;
    if (looks)
        loader.SetImageLoader(&gltf::load_image, &decoding);
    else
        loader.SetImageLoader(&skip_image, nullptr);
    loader.SetFsCallbacks(access.callbacks());
    std::string terr;
    std::string twarn;
    const unsigned size = unsigned(file.size());  // < kMaxModelFileBytes
    const bool ok = binary ? loader.LoadBinaryFromMemory(model, &terr, &twarn, file.data(), size,
                                                         access.base_dir())
                           : loader.LoadASCIIFromString(model, &terr, &twarn,
                                                        reinterpret_cast<const char*>(file.data()),
                                                        size, access.base_dir());
    size_t begin = 0;
    while (begin < twarn.size()) {
        size_t end = twarn.find('\n', begin);
        if (end == std::string::npos) end = twarn.size();
        const std::string line = first_line(twarn.substr(begin, end - begin));
        if (!line.empty()) warnings->push_back("glTF loader: " + line);
        begin = end + 1;
    }
    if (ok) return BakeError();
    const std::string refused = access.refusal_in(terr);
    if (!refused.empty()) return bake_error(BakeErrorCode::unsupported, refused);
    std::string why = first_line(terr);
    if (why.empty()) why = "unknown error";
    // tinygltf may quote a whole data URI; keep the log line readable.
    if (why.size() > 200) why = why.substr(0, 200) + "...";
    return malformed_input("not a valid glTF file: " + why);
}

bool contains(const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

// §3.12: "If a required extension is not supported by the client, the client must fail
// loading the asset." Material and texture extensions do not change geometry, so they count
// as understood; any other required extension (compressed geometry included) fails.
BakeError check_extensions(const Model& model, std::vector<std::string>* warnings) {
    for (const std::string& ext : model.extensionsRequired) {
        if (ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression") {
            return bake_error(
                BakeErrorCode::unsupported,
                "required extension " + ext + " is unsupported (compressed geometry)");
        }
        const bool harmless =
            ext == "KHR_mesh_quantization" || ext.rfind("KHR_materials_", 0) == 0 ||
            ext.rfind("KHR_texture_", 0) == 0 || ext.rfind("EXT_texture_", 0) == 0;
        if (!harmless) {
            return bake_error(BakeErrorCode::unsupported,
                              "required extension " + ext + " is not supported");
        }
    }
    if (contains(model.extensionsUsed, "EXT_mesh_gpu_instancing")) {
        warnings->push_back("EXT_mesh_gpu_instancing is unsupported; instanced meshes appear once");
    }
    return BakeError();
}

// An animated scene keeps its joints, clips and morph targets; a static one was baked into
// world space and keeps none. No double-sided material: nothing to record.
void finish_scene(bool animated, gltf::SkinTable* skin, gltf::MorphWeightTable* morph,
                  std::vector<RawClip>* clips, RawScene* scene) {
    if (std::find(scene->double_sided.begin(), scene->double_sided.end(), 1) ==
        scene->double_sided.end())
        scene->double_sided.clear();
    // Texture coordinates only matter where a part samples a texture, colours where one is
    // not white.
    if (std::none_of(scene->parts.begin(), scene->parts.end(),
                     [](const RawPart& p) { return p.texture >= 0; }))
        scene->uvs.clear();
    if (std::all_of(scene->colours.begin(), scene->colours.end(),
                    [](float c) { return c == 1.0f; }))
        scene->colours.clear();
    if (!animated) return;
    scene->joint_nodes = std::move(skin->joint_nodes);
    scene->inverse_bind = std::move(skin->inverse_bind);
    scene->clips = std::move(*clips);
    if (!scene->morph_targets.empty()) {
        scene->morph_weights = std::move(morph->weights);
        scene->morph_weight_nodes = std::move(morph->slot_nodes);
        return;
    }
    // No target survived: weights channels would animate nothing.
    for (RawClip& clip : scene->clips) {
        clip.channels.erase(
            std::remove_if(clip.channels.begin(), clip.channels.end(),
                           [](const RawChannel& c) { return c.path == RawPath::weights; }),
            clip.channels.end());
    }
}

// The import proper, part by part: nodes, skin, morph weight slots, clips, meshes.
BakeError import_model(const Model& model, const ImportOptions& options, RawScene* scene) {
    BakeError error = check_extensions(model, &scene->warnings);
    gltf::NodeTable nodes;
    if (error.ok()) error = gltf::read_nodes(model, scene, &nodes);
    gltf::SkinTable skin;
    if (error.ok()) error = gltf::read_skin(model, nodes, &scene->warnings, &skin);
    if (!error.ok()) return error;
    gltf::MorphWeightTable morph = gltf::assign_morph_slots(model, nodes, &scene->warnings);
    std::vector<RawClip> clips = gltf::read_clips(model, nodes, morph.slots, &scene->warnings);
    const bool animated = skin.present || !clips.empty();
    error = gltf::merge_meshes(model, nodes, morph, animated, options, &skin, scene);
    if (!error.ok()) return error;
    if (scene->indices.empty()) return malformed_input("no triangle primitives found");
    finish_scene(animated, &skin, &morph, &clips, scene);
    return BakeError();
}

}  // namespace

BakeError import_gltf(const std::string& path, RawScene* out, const ImportOptions& options) {
    assert(out != nullptr);
    RawScene scene;
    BakeError error;
    try {
        Model model;
        error = load_model(path, options.looks, &model, &scene.warnings);
        if (error.ok()) error = import_model(model, options, &scene);
    } catch (const std::bad_alloc&) {
        error = bake_error(BakeErrorCode::out_of_memory, "out of memory");
    } catch (const std::exception& e) {
        error = bake_error(BakeErrorCode::internal,
                           std::string("glTF loader failed: ") + first_line(e.what()));
    } catch (...) {
        error = bake_error(BakeErrorCode::internal, "glTF loader failed");
    }
    if (!error.ok()) {
        *out = RawScene();
        if (error.message.empty()) error.message = "import failed";
        return prefixed(path + ": ", std::move(error));
    }
    *out = std::move(scene);
    return BakeError();
}

}  // namespace stipple::bake
