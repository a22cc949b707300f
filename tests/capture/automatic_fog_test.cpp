// render::automaticFog: the haze over the terrain's bounding sphere reaches
// the same share of the sky colour at its far edge from any distance.
#include <sierra/render/FrameUniforms.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace sierra::render;

namespace {

TEST(AutomaticFog, FarEdgeFixedWhateverTheDistance) {
    const float radius = 300.0f;
    for (float distance : {500.0f, 2000.0f, 20000.0f}) {
        SCOPED_TRACE(distance);
        FogRange f = automaticFog(distance, radius);
        EXPECT_FLOAT_EQ(f.start, distance - radius);
        auto fogAt = [&](float d) {
            return 1.0f - std::exp(-f.density * std::max(d - f.start, 0.0f));
        };
        EXPECT_FLOAT_EQ(fogAt(distance - radius), 0.0f);
        EXPECT_NEAR(fogAt(distance + radius), kAutoFogFarEdge, 1e-5f);
        EXPECT_LT(fogAt(distance), kAutoFogFarEdge);
    }
    // Seven extents away (the far camera of the 403-sample DEM): the terrain is no more fogged
    // than from near by.
    EXPECT_FLOAT_EQ(automaticFog(20000.0f, radius).density, automaticFog(500.0f, radius).density);
    // Inside the sphere the haze starts at the eye and reaches the same share at the far edge.
    FogRange inside = automaticFog(100.0f, radius);
    EXPECT_EQ(inside.start, 0.0f);
    EXPECT_NEAR(1.0f - std::exp(-inside.density * 400.0f), kAutoFogFarEdge, 1e-5f);
    EXPECT_EQ(automaticFog(100.0f, 0.0f).density, 0.0f);
}

}  // namespace
