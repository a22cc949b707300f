#pragma once
// The schemes of `sierra-gen map`: their names, which options each takes, and
// the colour ramp each scalar field is drawn through.

#include <sierra/terrain/ColourRamp.h>
#include <sierra/terrain/DemMaps.h>
#include <sierra/terrain/Maps.h>

#include <span>
#include <string>

namespace sierra::apps::map {

enum class Kind {
    Height,            // plasma, atlas, hypsometric (and a --cpt table): colours of the heights
    Dem,               // a 3x3 field of terrain/DemMaps.h
    Shadow,            // the sun's visible fraction (analysis/Relief.h)
    SkyView,           // the sky-view factor
    OpennessPositive,  // degrees
    OpennessNegative,  // degrees
    Relief,            // tints x hillshade x sky-view
};

struct Scheme {
    std::string name;
    Kind kind = Kind::Height;
    terrain::MapScheme height = terrain::MapScheme::Hypsometric;
    terrain::DemField dem = terrain::DemField::Slope;
};

// Every scheme name, comma-separated, for --help and messages.
std::string schemeNames();

// Throws UsageError "map: --scheme: unknown scheme 'NAME'; expected ..." for
// a name that is none of them.
Scheme parseScheme(const std::string& name);

// Whether the scheme has a scalar field (--values) and one that a colour bar
// can label.
bool hasValues(const Scheme& scheme);
bool hasColourBar(const Scheme& scheme);

// The ramp a scalar scheme's field is drawn through, from its values
// (robust ranges: quantiles of the finite values), and the units the colour
// bar labels it in ("m" for a metric terrain's heights and curvatures).
struct FieldRamp {
    terrain::ColourRamp ramp;
    std::string units;
};
FieldRamp fieldRamp(const Scheme& scheme, const terrain::DemFieldDesc& desc,
                    std::span<const float> values, bool metres);

// The relief scheme's height tints over lo..hi (stored heights): light,
// desaturated colours that lighten with height, green lowlands through pale
// yellow to near white, as on Swiss topographic maps; water blue below `sea`
// (NaN = no water).
terrain::ColourRamp reliefTints(float lo, float hi, float sea);

}  // namespace sierra::apps::map
