// Renders one frame of each asset named on the command line with the installed package;
// prints each one's dark pixel count.
#include <platform/headless_context.h>
#include <runtime/stipple.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

// One frame of one asset; the dark pixel count, or -1 on an error (printed).
long dark_pixels(const char* path, const stipple_player_desc& desc, size_t pixels) {
    stipple_asset* asset = nullptr;
    stipple_player* player = nullptr;
    if (stipple_asset_load_file(path, &asset) != STIPPLE_OK ||
        stipple_player_create(asset, &desc, &player) != STIPPLE_OK) {
        std::fprintf(stderr, "%s: %s\n", path, stipple_last_error());
        stipple_asset_destroy(asset);
        return -1;
    }
    std::vector<uint8_t> rgba(pixels * 4);
    stipple_player_draw(player, 0, 0.0f);
    stipple_player_read_rgba(player, rgba.data());
    long dark = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) dark += rgba[i] < 128;
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    return dark;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    stipple::platform::HeadlessContext context;
    const stipple::platform::ContextStatus created =
        stipple::platform::create_headless_context({}, &context);
    if (!created.ok()) {
        std::fprintf(stderr, "%s\n", created.message.c_str());
        return 1;
    }
    stipple_player_desc desc = {};
    desc.get_proc_address = stipple::platform::proc_loader(context);
    stipple_player_desc resolved;  // the zero description's defaults: the image size
    if (stipple_player_desc_resolve(&desc, &resolved) != STIPPLE_OK) {
        std::fprintf(stderr, "%s\n", stipple_last_error());
        return 1;
    }
    int failures = 0;
    for (int i = 1; i < argc; ++i) {
        const long dark =
            dark_pixels(argv[i], desc, size_t(resolved.width) * size_t(resolved.height));
        std::printf("%s: %ld\n", argv[i], dark);
        failures += dark <= 100;
    }
    stipple::platform::destroy_headless_context(&context);
    return failures == 0 ? 0 : 1;
}
