// Where water is drawn by default: generated terrain, metric data below 0 m,
// or when asked; never on a loaded unitless heightmap.

#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Padding.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sierra;

namespace {

terrain::Heightfield ramp(float lo, float hi) {
    terrain::Heightfield f(11, 11);
    for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i) f.at(i, j) = lo + (hi - lo) * float(j * 11 + i) / 120.0f;
    return f;
}

TEST(SceneSeaLevel, GeneratedTerrainHasThirtyPercentBelowTheSea) {
    terrain::Heightfield f = ramp(0.0f, 120.0f);
    scene::TerrainSource generated;  // no heightmap: generated
    float sea = scene::resolveSeaLevel(generated, f);
    EXPECT_FLOAT_EQ(sea, scene::heightQuantile(f, 0.3));
    EXPECT_NEAR(sea, 36.0f, 1.0f);
}

TEST(SceneSeaLevel, LoadedHeightmapsGetWaterOnlyBelowZeroMetres) {
    scene::TerrainSource png{.heightmap = "valley.png"};
    EXPECT_TRUE(std::isnan(scene::resolveSeaLevel(png, ramp(-50.0f, 100.0f))))
        << "unitless: no water";
    scene::TerrainSource metric{.heightmap = "valley.png",
                                .heightUnits = scene::HeightUnits::Metres};
    EXPECT_TRUE(std::isnan(scene::resolveSeaLevel(metric, ramp(236.0f, 1076.0f))))
        << "land above 0 m: no water";
    EXPECT_EQ(scene::resolveSeaLevel(metric, ramp(-1437.0f, 2205.0f)), 0.0f)
        << "topobathymetry: sea at 0 m";
    scene::TerrainSource srtm{.heightmap = "N36W084.hgt"};
    EXPECT_TRUE(scene::metricHeights(srtm, ramp(-10.0f, 300.0f)));
    EXPECT_EQ(scene::resolveSeaLevel(srtm, ramp(-10.0f, 300.0f)), 0.0f);
}

// A file whose georeferencing says metres (an .npz with geographic bounds)
// counts as metric under automatic units, through padding; explicit units
// still win.
TEST(SceneSeaLevel, GeoreferencedMetresAreMetric) {
    terrain::Heightfield dem = ramp(-20.0f, 400.0f);
    scene::TerrainSource npz{.heightmap = "dem.npz"};
    EXPECT_FALSE(scene::metricHeights(npz, dem)) << "an .npz without georeferencing";
    dem.setMetres(true);
    EXPECT_TRUE(scene::metricHeights(npz, dem));
    EXPECT_TRUE(scene::metricHeights(npz, terrain::padToPowerOfTwoPlusOne(dem)));
    EXPECT_EQ(scene::resolveSeaLevel(npz, dem), 0.0f) << "metric data below 0 m: sea at 0";
    npz.heightUnits = scene::HeightUnits::None;
    EXPECT_FALSE(scene::metricHeights(npz, dem));
}

TEST(SceneSeaLevel, AskedForOrTurnedOff) {
    terrain::Heightfield f = ramp(0.0f, 120.0f);
    scene::TerrainSource given{.seaLevel = {.mode = scene::SeaLevel::Mode::Value, .value = 7.5f}};
    EXPECT_EQ(scene::resolveSeaLevel(given, f), 7.5f);
    scene::TerrainSource none{.seaLevel = {.mode = scene::SeaLevel::Mode::None}};
    EXPECT_TRUE(std::isnan(scene::resolveSeaLevel(none, f)));
    scene::TerrainSource unitless{.heightmap = "x.hgt", .heightUnits = scene::HeightUnits::None};
    EXPECT_FALSE(scene::metricHeights(unitless, f)) << "explicit units win over the extension";
}

}  // namespace
