#include "MapSchemes.h"

#include "AppMain.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sierra::apps::map {
namespace {

struct Named {
    const char* name;
    Kind kind;
};

constexpr Named kLighting[] = {{"shadow", Kind::Shadow},
                               {"sky-view", Kind::SkyView},
                               {"openness-positive", Kind::OpennessPositive},
                               {"openness-negative", Kind::OpennessNegative},
                               {"relief", Kind::Relief}};

constexpr const char* kHeightNames[] = {"plasma", "atlas", "hypsometric"};
constexpr const char* kDemNames[] = {"hillshade",
                                     "slope",
                                     "aspect",
                                     "tri",
                                     "tpi",
                                     "roughness",
                                     "curvature-profile",
                                     "curvature-plan",
                                     "curvature-tangential",
                                     "curvature-mean",
                                     "curvature-gaussian",
                                     "curvature-min",
                                     "curvature-max"};

using terrain::ColourRamp;
using terrain::ColourStop;
using terrain::Rgb;

ColourRamp grey(float black, float white) {
    if (black == white) white = black + 1.0f;
    if (black < white)
        return ColourRamp({{black, {0, 0, 0}}, {white, {255, 255, 255}}}, black, white);
    return ColourRamp({{white, {255, 255, 255}}, {black, {0, 0, 0}}}, white, black);
}

// A diverging ramp symmetric about 0: concave (negative) blue, convex red.
// Its ends at the `share` quantile of the magnitudes.
ColourRamp diverging(std::span<const float> values, double share = 0.98) {
    std::vector<float> magnitude;
    magnitude.reserve(values.size());
    for (float v : values) magnitude.push_back(std::abs(v));
    float m = terrain::finiteQuantile(magnitude, share);
    if (!(m > 0.0f)) m = 1.0f;
    return ColourRamp({{-m, {40, 80, 170}},
                       {-0.5f * m, {130, 170, 220}},
                       {0.0f, {245, 245, 240}},
                       {0.5f * m, {230, 150, 110}},
                       {m, {170, 40, 30}}},
                      -m, m, {.noData = Rgb{0, 0, 0}});
}

}  // namespace

std::string schemeNames() {
    std::string s;
    auto add = [&](const char* n) { s += (s.empty() ? "" : ", ") + std::string(n); };
    for (const char* n : kHeightNames) add(n);
    for (const char* n : kDemNames) add(n);
    for (const Named& n : kLighting) add(n.name);
    return s;
}

Scheme parseScheme(const std::string& name) {
    Scheme s{.name = name};
    if (terrain::parseMapScheme(name, &s.height)) {
        s.kind = Kind::Height;
        return s;
    }
    if (terrain::parseDemField(name, &s.dem)) {
        s.kind = Kind::Dem;
        return s;
    }
    for (const Named& n : kLighting)
        if (name == n.name) {
            s.kind = n.kind;
            return s;
        }
    throw UsageError(
        msg("map: --scheme: unknown scheme '", name, "'; expected one of ", schemeNames()));
}

bool hasValues(const Scheme& scheme) {
    return scheme.kind != Kind::Height && scheme.kind != Kind::Relief;
}

bool hasColourBar(const Scheme& scheme) {
    switch (scheme.kind) {
        case Kind::Height:
        case Kind::SkyView:
        case Kind::OpennessPositive:
        case Kind::OpennessNegative:
            return true;
        case Kind::Dem:
            return scheme.dem != terrain::DemField::Hillshade &&
                   scheme.dem != terrain::DemField::Aspect;
        default:
            return false;
    }
}

FieldRamp fieldRamp(const Scheme& scheme, const terrain::DemFieldDesc& desc,
                    std::span<const float> values, bool metres) {
    using terrain::DemField;
    const std::string length = metres ? "m" : "";
    switch (scheme.kind) {
        case Kind::Shadow:
            return {grey(0.0f, 1.0f), ""};
        case Kind::SkyView: {
            const float lo = std::min(terrain::finiteQuantile(values, 0.01), 0.99f);
            return {grey(lo, 1.0f), ""};
        }
        case Kind::OpennessPositive:
            return {
                grey(terrain::finiteQuantile(values, 0.01), terrain::finiteQuantile(values, 0.99)),
                "deg"};
        case Kind::OpennessNegative:  // high in valleys: drawn dark there, as positive openness is
            return {
                grey(terrain::finiteQuantile(values, 0.99), terrain::finiteQuantile(values, 0.01)),
                "deg"};
        default:
            break;
    }
    SIERRA_CHECK(scheme.kind == Kind::Dem, "scheme ", scheme.name, " has no scalar field");
    switch (scheme.dem) {
        case DemField::Hillshade:
            return {grey(0.0f, 255.0f), ""};
        case DemField::Slope:  // white flat to black vertical (percent: black at 45 degrees)
            return desc.slopeUnits == terrain::SlopeUnits::Percent
                       ? FieldRamp{grey(100.0f, 0.0f), "%"}
                       : FieldRamp{grey(90.0f, 0.0f), "deg"};
        case DemField::Aspect: {
            // A colour wheel, north red, east yellow, south teal, west purple;
            // flat ground (no aspect) mid grey.
            std::vector<ColourStop> wheel = {
                {0.0f, {214, 69, 65}},    {45.0f, {235, 140, 50}},  {90.0f, {240, 215, 80}},
                {135.0f, {140, 200, 90}}, {180.0f, {70, 180, 170}}, {225.0f, {70, 130, 210}},
                {270.0f, {120, 90, 190}}, {315.0f, {190, 80, 160}}, {360.0f, {214, 69, 65}}};
            return {ColourRamp(std::move(wheel), 0.0f, 360.0f, {.noData = Rgb{128, 128, 128}}),
                    "deg"};
        }
        case DemField::Tri:
        case DemField::Roughness: {
            float hi = terrain::finiteQuantile(values, 0.99);
            if (!(hi > 0.0f)) hi = 1.0f;
            return {ColourRamp({{0.0f, {255, 250, 230}},
                                {0.33f * hi, {230, 180, 100}},
                                {0.67f * hi, {160, 80, 40}},
                                {hi, {60, 20, 10}}},
                               0.0f, hi),
                    length};
        }
        case DemField::Tpi:
            return {diverging(values), length};
        case DemField::CurvaturePlan:  // 1/G^1.5 spikes on near-flat ground: a tighter range
            return {diverging(values, 0.9), metres ? "1/m" : ""};
        case DemField::CurvatureGaussian:
            return {diverging(values), metres ? "1/m^2" : ""};
        default:
            return {diverging(values), metres ? "1/m" : ""};
    }
}

terrain::ColourRamp reliefTints(float lo, float hi, float sea) {
    const float span = hi - lo;
    const bool water = std::isfinite(sea) && sea > lo && sea < hi;
    const float land = water ? sea : lo;
    const float relief = hi - land;
    std::vector<ColourStop> stops;
    if (water) {
        stops.push_back({lo, {150, 185, 215}});
        stops.push_back({sea, {190, 215, 232}});
    }
    for (const auto& [t, c] : std::initializer_list<std::pair<float, Rgb>>{{0.0f, {166, 196, 140}},
                                                                           {0.25f, {196, 210, 152}},
                                                                           {0.5f, {226, 222, 170}},
                                                                           {0.75f, {236, 224, 190}},
                                                                           {1.0f, {250, 247, 240}}})
        stops.push_back({land + t * relief, c});
    if (water) stops[2].height = std::nextafter(sea, hi);  // the shore: a hard edge
    return ColourRamp(std::move(stops), lo, span > 0.0f ? hi : lo + 1.0f);
}

}  // namespace sierra::apps::map
