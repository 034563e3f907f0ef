// glTF 2.0 materials, §3.9: the parts of the surface (one per material, or per primitive
// without one), their base colour (§3.9.2 baseColorFactor, baseColorTexture), alpha mode
// (§3.9.6: BLEND parts are transparent, thesis §7.4) and the images they sample (§3.8),
// decoded by stb_image within the bake's input caps.
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>

#include "bake/gltf_file_access.h"
#include "bake/gltf_parts.h"

namespace stipple::bake::gltf {

namespace {

bool listed(const std::vector<std::string>& names, const std::string& name) {
    return !name.empty() && std::find(names.begin(), names.end(), name) != names.end();
}

const tinygltf::Material* material_of(const Model& model, const tinygltf::Primitive& prim) {
    if (prim.material < 0 || size_t(prim.material) >= model.materials.size()) return nullptr;
    return &model.materials[size_t(prim.material)];
}

// The scene texture of glTF texture `index` (decoded image and sampler wrap modes), made the
// first time; -1 when it has no decoded image (not asked for, refused, or another format).
int scene_texture(const Model& model, int index, PartTable* table, RawScene* scene) {
    if (index < 0 || size_t(index) >= model.textures.size()) return -1;
    table->texture_of.resize(model.textures.size(), -2);  // -2: not looked at yet
    int& slot = table->texture_of[size_t(index)];
    if (slot != -2) return slot;
    slot = -1;
    const tinygltf::Texture& texture = model.textures[size_t(index)];
    if (texture.source < 0 || size_t(texture.source) >= model.images.size()) return slot;
    const tinygltf::Image& image = model.images[size_t(texture.source)];
    if (image.image.empty() || image.component != 4 || image.width <= 0 || image.height <= 0 ||
        image.image.size() != size_t(image.width) * size_t(image.height) * 4)
        return slot;
    RawTexture t;
    t.width = uint32_t(image.width);
    t.height = uint32_t(image.height);
    t.rgba = image.image;
    if (texture.sampler >= 0 && size_t(texture.sampler) < model.samplers.size()) {
        t.wrap_s = model.samplers[size_t(texture.sampler)].wrapS;
        t.wrap_t = model.samplers[size_t(texture.sampler)].wrapT;
    }
    slot = int(scene->textures.size());
    scene->textures.push_back(std::move(t));
    return slot;
}

// A new part for `material` (nullptr: the default material, white and opaque).
RawPart make_part(const Model& model, const tinygltf::Material* material,
                  const ImportOptions& options, PartTable* table, RawScene* scene) {
    RawPart part;
    if (!material) return part;
    part.material_name = material->name;
    const std::vector<double>& factor = material->pbrMetallicRoughness.baseColorFactor;
    for (size_t c = 0; c < 4 && c < factor.size(); ++c)
        part.colour[c] = std::isfinite(factor[c]) ? float(std::clamp(factor[c], 0.0, 1.0)) : 1.0f;
    part.blend = material->alphaMode == "BLEND";
    part.transparent = part.blend || listed(options.transparent, material->name);
    if (options.looks)
        part.texture = scene_texture(model, material->pbrMetallicRoughness.baseColorTexture.index,
                                     table, scene);
    return part;
}

}  // namespace

int base_colour_texcoord(const Model& model, const tinygltf::Primitive& prim) {
    const tinygltf::Material* m = material_of(model, prim);
    if (!m || m->pbrMetallicRoughness.baseColorTexture.index < 0) return -1;
    return std::max(0, m->pbrMetallicRoughness.baseColorTexture.texCoord);
}

BakeError primitive_part(const Model& model, size_t mesh_index, size_t prim_index,
                         const ImportOptions& options, PartTable* table, RawScene* scene,
                         uint16_t* part) {
    const tinygltf::Mesh& mesh = model.meshes[mesh_index];
    const tinygltf::Primitive& prim = mesh.primitives[prim_index];
    const tinygltf::Material* material = material_of(model, prim);
    const bool named = listed(options.transparent, mesh.name);
    // A material is one part, split off for a mesh that --transparent names.
    const std::array<int, 3> key =
        material ? std::array<int, 3>{prim.material, named ? int(mesh_index) : -1, -1}
                 : std::array<int, 3>{-1, int(mesh_index), int(prim_index)};
    auto it = std::find(table->keys.begin(), table->keys.end(), key);
    size_t index = size_t(it - table->keys.begin());
    if (it == table->keys.end()) {
        if (table->keys.size() >= limits::kMaxParts)
            return bake_error(BakeErrorCode::unsupported,
                              "more than " + str(size_t(limits::kMaxParts)) +
                                  " parts (materials, and primitives without one)");
        table->keys.push_back(key);
        scene->parts.push_back(make_part(model, material, options, table, scene));
        if (named) scene->parts.back().transparent = true;
    }
    RawPart& p = scene->parts[index];
    if (!mesh.name.empty() && !listed(p.mesh_names, mesh.name)) p.mesh_names.push_back(mesh.name);
    *part = uint16_t(index);
    return BakeError();
}

bool load_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
    ImageDecoding* d = static_cast<ImageDecoding*>(user);
    if (!d || !d->decode) return true;
    const std::string label = "image " + str(index) + ": ";
    int w = 0, h = 0, components = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &components)) {
        d->warnings->push_back(label + "not a PNG or JPEG image; its materials get no texture");
        return true;
    }
    const uint64_t need = uint64_t(w) * uint64_t(h) * 4;
    if (w <= 0 || h <= 0 || uint64_t(w) > kMaxTextureSide || uint64_t(h) > kMaxTextureSide ||
        d->bytes + need > kMaxTextureBytes) {
        d->warnings->push_back(label + str(w) + " x " + str(h) + " pixels, over the limit (" +
                               str(size_t(kMaxTextureSide)) + " a side, " +
                               str(size_t(kMaxTextureBytes >> 20)) +
                               " MiB decoded in all); its materials get no texture");
        return true;
    }
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &components, 4);
    if (!pixels) {
        d->warnings->push_back(label + "cannot be decoded (" + stbi_failure_reason() +
                               "); its materials get no texture");
        return true;
    }
    image->image.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    d->bytes += need;
    return true;
}

}  // namespace stipple::bake::gltf
