// The zone surface (render/ZoneSurface.h, shaders/surface_zones.glsl) on the
// GL: golden images of the default scene with automatic zones and with the
// sample zone map and bands; the --debug-view zones frame against the zone map
// rasterised from the same camera; and, on a flat terrain with one solid
// colour per tile, how many tiles a fragment mixes and with what weight.
//
// SIERRA_UPDATE_GOLDEN=1 rewrites the references in tests/golden/.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/ZoneSurface.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/Terrain.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Palette.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>

using namespace sierra;

namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 360;

using scene::assetPath;
using test::testOutputPath;

// Depth of the frame just drawn into the pbuffer (no multisampling), rows top-down.
std::vector<float> readDepth(int width, int height) {
    std::vector<float> raw(size_t(width) * height), out(raw.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, raw.data());
    for (int y = 0; y < height; ++y)
        std::copy_n(&raw[size_t(height - 1 - y) * width], width, &out[size_t(y) * width]);
    return out;
}

// World position under pixel (x, y) (top-down rows) from its depth.
glm::vec3 unproject(const glm::mat4& inverseViewProjection, int x, int y, float depth, int width,
                    int height) {
    glm::vec4 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f,
                  1.0f - (float(y) + 0.5f) / float(height) * 2.0f, depth * 2.0f - 1.0f, 1.0f);
    glm::vec4 w = inverseViewProjection * ndc;
    return glm::vec3(w) / w.w;
}

class ZoneFrames : public test::GlTest {
  protected:
    void SetUp() override {
        createContext(kWidth, kHeight);
        std::filesystem::create_directories(SIERRA_TEST_OUTPUT_DIR);
    }

    // The default scene (the terrain sierra-render draws with no arguments).
    void useDefaultScene() {
        field_ = scene::loadTerrain({});
        seaLevel_ = scene::heightQuantile(field_, 0.3);
        terrain_.emplace(
            render::TerrainRenderer::create({.field = &field_, .seaLevel = seaLevel_}));
    }

    void useField(terrain::Heightfield field) {
        field_ = std::move(field);
        seaLevel_ = std::numeric_limits<float>::quiet_NaN();
        terrain_.emplace(render::TerrainRenderer::create({.field = &field_}));
    }

    render::ZoneSurfaceInfo setZones(render::ZoneSurfaceDesc desc) {
        if (desc.palette.empty()) desc.palette = assetPath("palettes/default.json");
        desc.autoZones.seaLevel = seaLevel_;
        render::ZoneSurfaceInfo info;
        terrain_->setSurface(render::makeZoneSurface(terrain_->terrain(), field_, desc, &info));
        return info;
    }

    gpu::Image renderFrame(const render::Camera& camera, int samples,
                           const render::Lighting& lighting = {}) {
        target_.emplace(
            render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = samples}));
        target_->begin(render::TerrainRenderer::clearColour(lighting));
        terrain_->draw(camera, kWidth, kHeight,
                       {.lod = render::Lod::Sbt, .tau = 1.0f, .lighting = lighting});
        return target_->read();
    }

    render::Camera defaultCamera() const {
        return render::defaultCamera(terrain_->bounds(), float(kWidth) / float(kHeight));
    }

    // Close to the coast of the default scene, as README's near picture.
    render::Camera nearCamera() const {
        return render::framedCamera(terrain_->bounds(), {.target = {640.0f, -10.0f, 640.0f},
                                                         .azimuthDeg = 200.0f,
                                                         .elevationDeg = 25.0f,
                                                         .aspect = float(kWidth) / float(kHeight),
                                                         .distance = 120.0f});
    }

    void checkAgainstGolden(const gpu::Image& image, const std::string& name) {
        test::expectMatchesGolden(image, name);
    }

    // Zone-map pixel position of a world point: the inverse of the shader's
    // zoneMapPosition (map pixel centres on the real samples).
    glm::vec2 mapPosition(const glm::vec3& world, int mapWidth, int mapHeight) const {
        const glm::vec3 extent = terrain_->bounds().max;
        return {world.x / extent.x * float(mapWidth - 1) + 0.5f,
                world.z / extent.z * float(mapHeight - 1) + 0.5f};
    }

    terrain::Heightfield field_;
    float seaLevel_ = 0.0f;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
};

// ---------------------------------------------------------------- goldens

TEST_F(ZoneFrames, AutoZonesMatchReference) {
    useDefaultScene();
    render::ZoneSurfaceInfo info = setZones({.map = "auto"});
    EXPECT_GT(info.borderEdges, 100u);
    checkAgainstGolden(renderFrame(defaultCamera(), 4), "zones_auto.png");
}

TEST_F(ZoneFrames, SampleMapWithBandsMatchesReferenceNear) {
    useDefaultScene();
    render::ZoneSurfaceInfo info =
        setZones({.map = assetPath("zones/default_zones.png"), .band = 4.0f});
    EXPECT_EQ(info.band, 4.0f);
    checkAgainstGolden(renderFrame(nearCamera(), 4), "zones_map_bands_near.png");
}

// DrawOptions::plainSurface (sierra-bench frames --surface-costs): the
// renderer with zones draws the colour ramp it was created with, pixel for
// pixel the frame of a renderer that never had zones, and the zones again
// without it.
TEST_F(ZoneFrames, PlainSurfaceDrawsTheRampBesideTheZones) {
    useDefaultScene();
    const gpu::Image ramp = renderFrame(defaultCamera(), 0);
    setZones({.map = "auto"});
    const gpu::Image zones = renderFrame(defaultCamera(), 0);
    target_->begin(render::TerrainRenderer::clearColour({}));
    terrain_->draw(defaultCamera(), kWidth, kHeight,
                   {.lod = render::Lod::Sbt, .tau = 1.0f, .plainSurface = true});
    const gpu::Image plain = target_->read();
    const gpu::Image zonesAgain = renderFrame(defaultCamera(), 0);
    EXPECT_TRUE(std::isinf(render::compareImages(plain, ramp).psnr));
    EXPECT_TRUE(std::isinf(render::compareImages(zonesAgain, zones).psnr));
    EXPECT_GT(render::compareImages(plain, zones).differingShare, 0.2);
}

// ------------------------------------------------- debug view against the map

// Flat colours, no shading: ambient 1 lights every face fully and no fog, so
// each terrain pixel holds its zone's palette colour exactly.
render::Lighting flatLighting() {
    render::Lighting l;
    l.ambient = 1.0f;
    l.fogDensity = 0.0f;
    return l;
}

// The palette zone whose colour is the pixel's, or -1 (sky, or a colour of no zone).
int zoneOfColour(const uint8_t* p, const zones::Palette& palette) {
    for (size_t k = 0; k < palette.surfaces.size(); ++k) {
        const zones::Colour c = palette.surfaces[k].colour;
        if (std::abs(int(p[0]) - int((c >> 16) & 255)) <= 2 &&
            std::abs(int(p[1]) - int((c >> 8) & 255)) <= 2 &&
            std::abs(int(p[2]) - int(c & 255)) <= 2)
            return int(k);
    }
    return -1;
}

struct Agreement {
    size_t terrainPixels = 0, agreeing = 0;
    std::set<int> zonesSeen;
    double share() const { return terrainPixels ? double(agreeing) / double(terrainPixels) : 0.0; }
};

// Every pixel the terrain covers: its world position from the depth buffer,
// the zone map's pixel there against the zone the debug view drew. A Figure 1
// borderline pixel belongs to no zone: there any zone of its 3x3 neighbourhood agrees.
Agreement compareWithMap(const gpu::Image& frame, const std::vector<float>& depth,
                         const glm::mat4& inverseVp, const zones::ZoneMap& map,
                         const zones::Palette& palette,
                         const std::function<glm::vec2(glm::vec3)>& toMap,
                         gpu::Image* disagreement) {
    Agreement a;
    *disagreement = frame;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const size_t p = size_t(y) * frame.width + x;
            if (depth[p] >= 1.0f) continue;  // sky
            ++a.terrainPixels;
            const glm::vec2 m =
                toMap(unproject(inverseVp, x, y, depth[p], frame.width, frame.height));
            const int i = std::clamp(int(std::floor(m.x)), 0, map.width - 1);
            const int j = std::clamp(int(std::floor(m.y)), 0, map.height - 1);
            const int drawn = zoneOfColour(&frame.rgba[p * 4], palette);
            a.zonesSeen.insert(drawn);
            bool ok = map.at(i, j) == drawn;
            if (map.at(i, j) == zones::kBorderlinePixel)
                for (int dj = -1; dj <= 1 && !ok; ++dj)
                    for (int di = -1; di <= 1 && !ok; ++di) {
                        const int ii = std::clamp(i + di, 0, map.width - 1),
                                  jj = std::clamp(j + dj, 0, map.height - 1);
                        ok = map.at(ii, jj) == drawn;
                    }
            a.agreeing += ok;
            if (!ok) {
                uint8_t* q = &disagreement->rgba[p * 4];
                q[0] = 255, q[1] = 0, q[2] = 255;
            }
        }
    return a;
}

void checkDebugViewAgainstMap(const gpu::Image& frame, const std::vector<float>& depth,
                              const render::Camera& camera, const zones::ZoneMap& map,
                              const zones::Palette& palette,
                              const std::function<glm::vec2(glm::vec3)>& toMap,
                              const std::string& name) {
    gpu::Image marked;
    const glm::mat4 inverseVp = glm::inverse(camera.viewProjection(float(kWidth) / float(kHeight)));
    Agreement a = compareWithMap(frame, depth, inverseVp, map, palette, toMap, &marked);
    render::writePng(testOutputPath(name), marked);
    std::printf("%s: %zu terrain pixels, %.3f%% agree with the zone map, %zu colours seen\n",
                name.c_str(), a.terrainPixels, 100.0 * a.share(), a.zonesSeen.size());
    EXPECT_GT(a.terrainPixels, size_t(kWidth * kHeight / 8))
        << "the terrain covers too little of the frame";
    EXPECT_GE(a.zonesSeen.size(), 4u) << "too few zones in view to tell a wrong mapping";
    EXPECT_GE(a.share(), 0.99) << "disagreeing pixels are magenta in " << testOutputPath(name);
}

TEST_F(ZoneFrames, DebugViewZonesAgreesWithAutoZoneMap) {
    useDefaultScene();
    setZones({.map = "auto", .debugView = render::ZoneDebugView::Zones});
    const zones::Palette palette = zones::loadPalette(assetPath("palettes/default.json"));
    zones::AutoZoneDesc autoDesc;
    autoDesc.seaLevel = seaLevel_;
    const zones::ZoneMap map =
        zones::autoZones(field_, palette, autoDesc);  // the default field needs no padding
    const render::Camera camera = defaultCamera();
    const gpu::Image frame = renderFrame(camera, 0, flatLighting());
    const std::vector<float> depth = readDepth(kWidth, kHeight);
    render::writePng(testOutputPath("zones_debug_auto.png"), frame);
    checkDebugViewAgainstMap(
        frame, depth, camera, map, palette,
        [&](glm::vec3 w) { return mapPosition(w, map.width, map.height); },
        "zones_debug_auto_disagreement.png");
}

TEST_F(ZoneFrames, DebugViewZonesAgreesWithSampleMapNear) {
    useDefaultScene();
    setZones({.map = assetPath("zones/default_zones.png"),
              .band = 4.0f,
              .debugView = render::ZoneDebugView::Zones});
    const zones::Palette palette = zones::loadPalette(assetPath("palettes/default.json"));
    const zones::ZoneMap map = zones::loadZoneMap(assetPath("zones/default_zones.png"), palette);
    const render::Camera camera = nearCamera();
    const gpu::Image frame = renderFrame(camera, 0, flatLighting());
    const std::vector<float> depth = readDepth(kWidth, kHeight);
    render::writePng(testOutputPath("zones_debug_map_near.png"), frame);
    checkDebugViewAgainstMap(
        frame, depth, camera, map, palette,
        [&](glm::vec3 w) { return mapPosition(w, map.width, map.height); },
        "zones_debug_map_disagreement.png");
}

// ------------------------------------------- one tile away from borders, two in a band

// A flat 65^2 terrain zoned by a 64x64 map of three zones meeting at a T
// junction (left half: zone 0; right half: zone 1 above, zone 2 below), each
// zone's tile one solid primary colour (red, green, blue). Seen from straight
// above with flat light, a pixel's channels are the tiles' weights.
class ZoneSampling : public ZoneFrames {
  protected:
    static constexpr int kMap = 64;

    void SetUp() override {
        ZoneFrames::SetUp();
        // Nearly flat: a small tilt gives the terrain a height range.
        terrain::Heightfield flat(65, 65);
        for (int j = 0; j < 65; ++j)
            for (int i = 0; i < 65; ++i) flat.at(i, j) = 0.01f * float(i + j);
        flat.setSpacing(1.0f, 1.0f);
        flat.setVerticalScale(1.0f);
        useField(std::move(flat));
        dir_ = testOutputPath("zone_sampling");
        std::filesystem::create_directories(dir_);
        const char* names[3] = {"red", "green", "blue"};
        for (int k = 0; k < 3; ++k) {
            gpu::Image tile{.width = 16, .height = 16};
            tile.rgba.assign(16 * 16 * 4, 0);
            for (size_t p = 0; p < tile.rgba.size(); p += 4) {
                tile.rgba[p + size_t(k)] = 255;
                tile.rgba[p + 3] = 255;
            }
            render::writePng(dir_ + "/" + names[k] + ".png", tile);
        }
        std::ofstream(dir_ + "/palette.json") << R"({"zones": [
                {"name": "red",   "colour": "#c00000", "tile": "red.png",   "heightBlend": 0},
                {"name": "green", "colour": "#00c000", "tile": "green.png", "heightBlend": 0},
                {"name": "blue",  "colour": "#0000c0", "tile": "blue.png",  "heightBlend": 0}]})";
        gpu::Image map{.width = kMap, .height = kMap};
        map.rgba.assign(size_t(kMap) * kMap * 4, 255);
        for (int j = 0; j < kMap; ++j)
            for (int i = 0; i < kMap; ++i) {
                const int zone = i < kMap / 2 ? 0 : j < kMap / 2 ? 1 : 2;
                uint8_t* p = &map.rgba[(size_t(j) * kMap + i) * 4];
                p[0] = zone == 0 ? 0xc0 : 0, p[1] = zone == 1 ? 0xc0 : 0,
                p[2] = zone == 2 ? 0xc0 : 0;
            }
        render::writePng(dir_ + "/map.png", map);
        palette_ = zones::loadPalette(dir_ + "/palette.json");
        lines_ = zones::buildBorderlines(zones::loadZoneMap(dir_ + "/map.png", palette_), palette_,
                                         {.epsilon = 0.5, .bandWidth = 0.0});
    }

    // Straight down onto the terrain's centre, orthographic, the whole map in view.
    render::Camera topCamera() const { return test::topDownCamera({32.0f, 0.0f, 32.0f}, 70.0f); }

    std::string dir_;
    zones::Palette palette_;
    zones::Borderlines lines_;
};

// The shader's blend weight of the pair's second zone, computed on the CPU from
// the same field: bilinear signed distance where the four texels around the
// point share the pair (else nullopt: near a junction the pair changes).
struct Expected {
    int zone, low, high;
    float distance;  // zone-map pixels
};
std::optional<Expected> expectedAt(const zones::BorderField& f, glm::vec2 m) {
    const float s = float(f.texelsPerPixel);
    const glm::vec2 p = m * s - 0.5f;
    const int i0 = int(std::floor(p.x)), j0 = int(std::floor(p.y));
    if (i0 < 0 || j0 < 0 || i0 + 1 >= f.width || j0 + 1 >= f.height) return std::nullopt;
    auto at = [&](int i, int j) { return size_t(j) * f.width + i; };
    const size_t n = at(std::clamp(int(std::floor(m.x * s)), 0, f.width - 1),
                        std::clamp(int(std::floor(m.y * s)), 0, f.height - 1));
    Expected e{f.zone[n], f.lowZone[n], f.highZone[n], 0.0f};
    const glm::vec2 t = p - glm::vec2(float(i0), float(j0));
    float d[4];
    for (int k = 0; k < 4; ++k) {
        const size_t q = at(i0 + (k & 1), j0 + (k >> 1));
        if (f.lowZone[q] != e.low || f.highZone[q] != e.high) return std::nullopt;
        d[k] = f.signedDistance[q];
    }
    e.distance = glm::mix(glm::mix(d[0], d[1], t.x), glm::mix(d[2], d[3], t.x), t.y) / s;
    return e;
}

float smoothStep(float a, float b, float x) {
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

TEST_F(ZoneSampling, OneTileAwayFromBordersTwoBlendedByDistanceInABand) {
    const float band = 6.0f;  // zone-map pixels
    render::ZoneSurfaceInfo info = setZones({.map = dir_ + "/map.png",
                                             .palette = dir_ + "/palette.json",
                                             .band = band,
                                             .heightBlend = false});
    const zones::BorderField field =
        zones::buildBorderField(lines_, {.texelsPerPixel = info.texelsPerPixel});
    const render::Camera camera = topCamera();
    const gpu::Image frame = renderFrame(camera, 0, flatLighting());
    const std::vector<float> depth = readDepth(kWidth, kHeight);
    render::writePng(testOutputPath("zone_sampling.png"), frame);
    const glm::mat4 inverseVp = glm::inverse(camera.viewProjection(float(kWidth) / float(kHeight)));

    size_t far = 0, farPure = 0, banded = 0, bandTwoAtMost = 0, formulaChecked = 0, formulaOk = 0;
    size_t mixedFar = 0;
    float worstWeightError = 0.0f;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t p = size_t(y) * kWidth + x;
            if (depth[p] >= 1.0f) continue;
            const glm::vec2 m =
                mapPosition(unproject(inverseVp, x, y, depth[p], kWidth, kHeight), kMap, kMap);
            const uint8_t* c = &frame.rgba[p * 4];
            int present = 0;
            for (int ch = 0; ch < 3; ++ch) present += c[ch] > 3;
            // The distance to the true borders (x = 32 between zone 0 and the
            // others, y = 32 right of it), in map pixels.
            const float toBorder =
                std::min(std::abs(m.x - 32.0f), m.x > 32.0f ? std::abs(m.y - 32.0f) : 1e9f);
            if (m.x < 1.5f || m.y < 1.5f || m.x > kMap - 1.5f || m.y > kMap - 1.5f)
                continue;  // the frame's margin
            if (toBorder > 0.5f * band + 1.5f) {
                ++far;
                const bool pure = present == 1 && std::max({c[0], c[1], c[2]}) >= 252;
                farPure += pure;
                mixedFar += !pure;
                continue;
            }
            if (toBorder >= 0.5f * band - 0.5f) continue;  // the band's edge: either count is right
            ++banded;
            bandTwoAtMost += present <= 2;
            std::optional<Expected> e = expectedAt(field, m);
            if (!e || e->low == e->high) continue;
            ++formulaChecked;
            const float weight = smoothStep(-0.5f * band, 0.5f * band, e->distance);
            const float lowShare = float(c[e->low]) / 255.0f,
                        highShare = float(c[e->high]) / 255.0f;
            const int other = 3 - e->low - e->high;
            const float error =
                std::max(std::abs(highShare - weight), std::abs(lowShare - (1.0f - weight)));
            worstWeightError = std::max(worstWeightError, error);
            formulaOk += error <= 0.03f && c[other] <= 3;
        }
    std::printf(
        "far from borders: %zu of %zu pixels one tile; in bands: %zu of %zu at most two tiles; "
        "blend weight within 0.03 of smoothstep(-W/2, W/2, d): %zu of %zu (worst %.3f)\n",
        farPure, far, bandTwoAtMost, banded, formulaOk, formulaChecked, worstWeightError);
    ASSERT_GT(far, size_t(50000));
    ASSERT_GT(banded, size_t(5000));
    ASSERT_GT(formulaChecked, banded / 2);
    EXPECT_EQ(mixedFar, 0u) << "pixels away from every band mix tiles (see "
                            << testOutputPath("zone_sampling.png") << ")";
    EXPECT_EQ(bandTwoAtMost, banded) << "band pixels mix more than two tiles";
    EXPECT_GE(double(formulaOk), 0.995 * double(formulaChecked))
        << "worst weight error " << worstWeightError;
}

// Height blending and tile variation move the weight inside a band but never
// bring in a third tile, nor a second one away from the band.
TEST_F(ZoneSampling, HeightBlendKeepsAtMostTwoTiles) {
    setZones({.map = dir_ + "/map.png",
              .palette = dir_ + "/palette.json",
              .band = 6.0f,
              .heightBlend = true,
              .variation = true});
    const render::Camera camera = topCamera();
    const gpu::Image frame = renderFrame(camera, 0, flatLighting());
    const std::vector<float> depth = readDepth(kWidth, kHeight);
    size_t terrain = 0, three = 0, mixed = 0;
    for (size_t p = 0; p < depth.size(); ++p) {
        if (depth[p] >= 1.0f) continue;
        ++terrain;
        int present = 0;
        for (int ch = 0; ch < 3; ++ch) present += frame.rgba[p * 4 + ch] > 3;
        three += present == 3;
        mixed += present == 2;
    }
    EXPECT_GT(terrain, size_t(100000));
    EXPECT_EQ(three, 0u);
    EXPECT_GT(mixed, size_t(2000)) << "no band was drawn";
}

}  // namespace
