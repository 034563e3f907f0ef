// Particle settings through the player (docs/particles.md): stipple-play --particle-fades turns
// on visibility fades (FrameConfig::particle_fades, runtime/particle_visibility.h), so strokes
// the body hides fade instead of popping; --particle-budget sizes the particle tree and is
// range-checked.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/particle_style.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

// The strokes of strokes_NNNN.csv that show (visible = 1): id -> alpha.
std::map<uint32_t, float> seen_strokes(const std::string& path) {
    std::map<uint32_t, float> seen;
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);  // id,x,y,angle,size,width,alpha,visible
    while (std::getline(f, line)) {
        std::vector<std::string> c;
        std::stringstream ss(line);
        for (std::string field; std::getline(ss, field, ',');) c.push_back(field);
        if (c.size() == 8 && c[7] == "1") seen[uint32_t(std::stoul(c[0]))] = std::stof(c[6]);
    }
    return seen;
}

struct Pops {
    size_t in = 0, out = 0, strokes = 0;
};

// Two seconds of the walk at 30 fps (320x240, painterly-long) through the player: strokes seen
// (after the depth test) that appear or vanish above a third of the style's opacity, as
// ParticleFrames.HiddenStrokesFadeWithVisibilityFades counts them. The first six frames
// settle the fades.
Pops walk_pops(const std::string& options) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    std::string log;
    EXPECT_EQ(run(play_checked() + " '" + asset + "' --out '" + dir.path() +
                      "' --style painterly-long --size 320x240 --fps 30 --frames 67"
                      " --strokes-out --no-png --no-apng " +
                      options,
                  &log),
              0)
        << log;
    const float third = find_particle_style("painterly-long")->opacity / 3.0f + 1e-3f;
    Pops p;
    std::map<uint32_t, float> last;
    for (int f = 6; f < 67; ++f) {
        char name[32];
        std::snprintf(name, sizeof(name), "strokes_%04d.csv", f);
        const std::map<uint32_t, float> now = seen_strokes(dir.file(name));
        if (f > 6) {
            for (const auto& [id, alpha] : now) p.in += !last.count(id) && alpha > third;
            for (const auto& [id, alpha] : last) p.out += !now.count(id) && alpha > third;
            p.strokes += now.size();
        }
        last = now;
    }
    std::printf("%s: popped in %zu, out %zu of %zu strokes seen\n",
                options.empty() ? "default" : options.c_str(), p.in, p.out, p.strokes);
    return p;
}

TEST(ParticlePlayer, ParticleFadesRemoveThePopsAfterTheDepthTest) {
    const Pops tested = walk_pops("");
    const Pops faded = walk_pops("--particle-fades");
    EXPECT_GT(tested.in + tested.out, 100u);
    EXPECT_GT(faded.strokes, 10000u);
    EXPECT_EQ(faded.in, 0u);
    EXPECT_EQ(faded.out, 0u);
}

TEST(ParticlePlayer, ParticleOptionsAreChecked) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    std::string log;
    EXPECT_NE(run(bin("stipple-play") + " '" + asset + "' --out '" + dir.path() +
                      "' --particle-fades --frames 1",
                  &log),
              0);
    EXPECT_NE(log.find("--particle-fades needs a particle style"), std::string::npos) << log;
    EXPECT_NE(run(bin("stipple-play") + " '" + asset + "' --out '" + dir.path() +
                      "' --style ink --particle-budget 99999999 --frames 1",
                  &log),
              0);
    EXPECT_NE(log.find("--particle-budget"), std::string::npos) << log;
    // The bake alone (a budget below its points) still draws.
    EXPECT_EQ(run(play_checked() + " '" + asset + "' --out '" + dir.path() +
                      "' --style ink --particle-budget 0 --frames 1 --no-apng",
                  &log),
              0)
        << log;
}

}  // namespace
