#include "MapOptions.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <cmath>
#include <functional>
#include <initializer_list>

namespace sierra::apps::map {
namespace {

bool isDem(const Scheme& s, std::initializer_list<terrain::DemField> fields) {
    if (s.kind != Kind::Dem) return false;
    for (terrain::DemField f : fields)
        if (s.dem == f) return true;
    return false;
}

// Which schemes each scheme option applies to, in words for the message.
struct Applies {
    const char* option;
    const char* where;
    std::function<bool(const Scheme&, const MapOptions&)> test;
};

void checkOptionsApply(const CLI::App& cmd, const Scheme& s, const MapOptions& o) {
    using terrain::DemField;
    auto hillshade = [](const Scheme& x) {
        return isDem(x, {DemField::Hillshade}) || x.kind == Kind::Relief;
    };
    auto horizons = [](const Scheme& x) {
        return x.kind == Kind::SkyView || x.kind == Kind::OpennessPositive ||
               x.kind == Kind::OpennessNegative || x.kind == Kind::Relief;
    };
    const Applies table[] = {
        {"--cpt", "height schemes and relief",
         [](const Scheme& x, const MapOptions&) {
             return x.kind == Kind::Height || x.kind == Kind::Relief;
         }},
        {"--colour-bar", "height schemes and the scalar schemes but hillshade and aspect",
         [](const Scheme& x, const MapOptions&) { return map::hasColourBar(x); }},
        {"--legend", "height schemes and the scalar schemes but hillshade and aspect",
         [](const Scheme& x, const MapOptions&) { return map::hasColourBar(x); }},
        {"--values", "the scalar schemes (all but the height schemes and relief)",
         [](const Scheme& x, const MapOptions&) { return map::hasValues(x); }},
        {"--algorithm", "hillshade, slope, aspect, the curvatures and relief",
         [&](const Scheme& x, const MapOptions&) {
             return hillshade(x) || isDem(x, {DemField::Slope, DemField::Aspect}) ||
                    (x.kind == Kind::Dem && terrain::isCurvature(x.dem));
         }},
        {"--z-factor", "hillshade and relief",
         [&](const Scheme& x, const MapOptions&) { return hillshade(x); }},
        {"--multidirectional", "hillshade and relief",
         [&](const Scheme& x, const MapOptions&) { return hillshade(x); }},
        {"--combined", "hillshade and relief",
         [&](const Scheme& x, const MapOptions&) { return hillshade(x); }},
        {"--igor", "hillshade and relief",
         [&](const Scheme& x, const MapOptions&) { return hillshade(x); }},
        {"--azimuth", "hillshade (but --multidirectional), shadow and relief",
         [&](const Scheme& x, const MapOptions& m) {
             return (hillshade(x) && !m.multidirectional) || x.kind == Kind::Shadow;
         }},
        {"--altitude", "hillshade (but --igor), shadow and relief",
         [&](const Scheme& x, const MapOptions& m) {
             return (hillshade(x) && !m.igor) || x.kind == Kind::Shadow;
         }},
        {"--slope-units", "slope",
         [](const Scheme& x, const MapOptions&) { return isDem(x, {DemField::Slope}); }},
        {"--trigonometric", "aspect",
         [](const Scheme& x, const MapOptions&) { return isDem(x, {DemField::Aspect}); }},
        {"--zero-for-flat", "aspect",
         [](const Scheme& x, const MapOptions&) { return isDem(x, {DemField::Aspect}); }},
        {"--tri", "tri",
         [](const Scheme& x, const MapOptions&) { return isDem(x, {DemField::Tri}); }},
        {"--compute-edges", "the 3x3 schemes (hillshade to curvature-max) and relief",
         [](const Scheme& x, const MapOptions&) {
             return x.kind == Kind::Dem || x.kind == Kind::Relief;
         }},
        {"--sun-size", "shadow",
         [](const Scheme& x, const MapOptions&) { return x.kind == Kind::Shadow; }},
        {"--horizon-radius", "shadow, sky-view, the opennesses and relief",
         [&](const Scheme& x, const MapOptions&) { return horizons(x) || x.kind == Kind::Shadow; }},
        {"--directions", "sky-view, the opennesses and relief",
         [&](const Scheme& x, const MapOptions&) { return horizons(x); }},
    };
    for (const Applies& a : table)
        if (cmd.count(a.option) > 0 && !a.test(s, o))
            throw UsageError(msg("map: ", a.option, " does not apply to --scheme ", s.name,
                                 " (it applies to ", a.where, ")"));
    if (int(o.multidirectional) + int(o.combined) + int(o.igor) > 1)
        throw UsageError("map: only one of --multidirectional, --combined and --igor");
}

}  // namespace

terrain::DemFieldDesc demFieldDesc(const Scheme& s, const MapOptions& o) {
    terrain::DemFieldDesc d{.field = s.kind == Kind::Dem ? s.dem : terrain::DemField::Hillshade,
                            .computeEdges = o.computeEdges};
    const bool curvature = terrain::isCurvature(d.field);
    if (o.algorithm.empty())
        d.stencil = curvature ? terrain::Stencil::EvansYoung : terrain::Stencil::Horn;
    else if (o.algorithm == "horn" && !curvature)
        d.stencil = terrain::Stencil::Horn;
    else if (o.algorithm == "zevenbergen")
        d.stencil = terrain::Stencil::ZevenbergenThorne;
    else if (o.algorithm == "evans-young")
        d.stencil = terrain::Stencil::EvansYoung;
    else
        throw UsageError(msg("map: --algorithm must be ",
                             curvature
                                 ? "evans-young or zevenbergen (a curvature needs a quadratic)"
                                 : "horn, zevenbergen or evans-young",
                             ", got '", o.algorithm, "'"));
    if (o.slopeUnits == "percent")
        d.slopeUnits = terrain::SlopeUnits::Percent;
    else if (o.slopeUnits != "degrees")
        throw UsageError(
            msg("map: --slope-units must be degrees or percent, got '", o.slopeUnits, "'"));
    if (o.tri == "wilson")
        d.tri = terrain::TriFormula::Wilson;
    else if (o.tri != "riley")
        throw UsageError(msg("map: --tri must be riley or wilson, got '", o.tri, "'"));
    d.trigonometric = o.trigonometric;
    d.zeroForFlat = o.zeroForFlat;
    d.azimuth = o.azimuth;
    d.altitude = o.altitude;
    d.zFactor = o.zFactor;
    d.shade = o.multidirectional ? terrain::ShadeStyle::Multidirectional
              : o.combined       ? terrain::ShadeStyle::Combined
              : o.igor           ? terrain::ShadeStyle::Igor
                                 : terrain::ShadeStyle::Oblique;
    return d;
}

namespace {

void checkValues(const MapOptions& o) {
    if (!std::isfinite(o.azimuth) || !(o.altitude >= 0.0f && o.altitude <= 90.0f))
        throw UsageError(msg("map: --altitude must be 0..90 degrees and --azimuth finite, got ",
                             o.altitude, " and ", o.azimuth));
    if (!(std::isfinite(o.zFactor) && o.zFactor > 0.0f))
        throw UsageError(msg("map: --z-factor must be > 0, got ", o.zFactor));
    if (!(std::isfinite(o.sunSize) && o.sunSize > 0.0f && o.sunSize < 90.0f))
        throw UsageError(
            msg("map: --sun-size must be a diameter in degrees > 0 and < 90, got ", o.sunSize));
    if (!(std::isfinite(o.horizonRadius) && o.horizonRadius >= 0.0f))
        throw UsageError(
            msg("map: --horizon-radius must be >= 0 world units (0 = the whole grid), got ",
                o.horizonRadius));
    if (o.directions < 1 || o.directions > 1024)
        throw UsageError(msg("map: --directions must be 1..1024, got ", o.directions));
    if (o.out.empty() && o.values.empty())
        throw UsageError("map: nothing to write: give --out FILE.png, --values FILE.npy or both");
    if (!o.out.empty() && lowerExtension(o.out) != ".png")
        throw UsageError(
            msg("map: --out must name a .png file (maps are written as PNG), got '", o.out, "'"));
    if (!o.values.empty() && lowerExtension(o.values) != ".npy")
        throw UsageError(msg("map: --values must name a .npy file, got '", o.values, "'"));
}

}  // namespace

void checkMapOptions(const CLI::App& cmd, const Scheme& s, const MapOptions& o) {
    checkOptionsApply(cmd, s, o);
    checkValues(o);
}

void addMapOptions(CLI::App& c, MapOptions& o) {
    CLI::App* cmd = &c;
    cmd->add_option("--scheme", o.scheme, msg("Map scheme: ", map::schemeNames()))
        ->capture_default_str();
    cmd->add_option("--cpt", o.cpt,
                    "GMT .cpt colour table for the heights (absolute stored heights); height "
                    "schemes and relief");
    cmd->add_flag("--colour-bar", o.colourBar,
                  "Add a legend with ticks and numbers in the map's units");
    cmd->add_option("--out", o.out, "Output PNG");
    cmd->add_option("--values", o.values,
                    "Output .npy: the scheme's float32 field (rows as the input's), NaN where "
                    "gdaldem writes no data");
    cmd->add_option("--algorithm", o.algorithm,
                    "Derivatives: horn (default), zevenbergen or evans-young; curvatures: "
                    "evans-young (default) or zevenbergen");
    cmd->add_option("--z-factor", o.zFactor, "Hillshade: vertical exaggeration of the heights")
        ->capture_default_str();
    cmd->add_flag("--multidirectional", o.multidirectional,
                  "Hillshade: four lights from 225, 270, 315, 360 degrees, weighted by aspect");
    cmd->add_flag("--combined", o.combined, "Hillshade: oblique shade darkened by slope");
    cmd->add_flag("--igor", o.igor, "Hillshade: dark only on steep slopes facing away");
    cmd->add_option("--azimuth,--sun-azimuth", o.azimuth, "Sun, degrees clockwise from north (up)")
        ->capture_default_str();
    cmd->add_option("--altitude,--sun-altitude", o.altitude,
                    "Sun, degrees above the horizon, 0..90")
        ->capture_default_str();
    cmd->add_option("--slope-units", o.slopeUnits, "Slope: degrees or percent")
        ->capture_default_str();
    cmd->add_flag("--trigonometric", o.trigonometric,
                  "Aspect: counter-clockwise from east instead of clockwise from north");
    cmd->add_flag("--zero-for-flat", o.zeroForFlat, "Aspect: 0 on flat ground instead of NaN");
    cmd->add_option("--tri", o.tri, "TRI: riley (root of summed squares) or wilson (mean abs)")
        ->capture_default_str();
    cmd->add_flag("--compute-edges", o.computeEdges,
                  "3x3 schemes: values on the border and next to no data (extrapolated), "
                  "not NaN");
    cmd->add_option("--sun-size", o.sunSize, "Shadow: the sun's angular diameter in degrees")
        ->capture_default_str();
    cmd->add_option("--horizon-radius", o.horizonRadius,
                    "Horizon search radius, world units (0 = the whole grid)")
        ->capture_default_str();
    cmd->add_option("--directions", o.directions, "Horizon azimuths for sky-view and openness")
        ->capture_default_str();
}

}  // namespace sierra::apps::map
