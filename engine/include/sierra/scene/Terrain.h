#pragma once
// Where a scene's terrain comes from, and loading it: read or generate the
// heightfield, pad it to (2^n+1)^2, pick spacing and vertical scale. Shared by
// every app so each program reads terrain the same way. No GL.

#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace sierra::scene {

// Sea level of the water plane, in stored height units (the file's own
// numbers, before the vertical scale).
struct SeaLevel {
    enum class Mode {
        Auto,   // chosen by the renderer from the data (today: the 30% height quantile)
        None,   // no water
        Value,  // `value` below
    };
    Mode mode = Mode::Auto;
    float value = 0.0f;  // stored height units; used only when mode == Value
    bool operator==(const SeaLevel&) const = default;
};

// What the stored heights measure.
enum class HeightUnits {
    Auto,    // metres for SRTM (.hgt) and GeoTIFF, unitless for everything else
    Metres,  // heights are metres: vertical scale 1 against the (metric) spacing
    None,    // unitless: automatic relief of 20% of the horizontal extent
};

// Which channel of a colour image is the height. Grey images need none.
enum class Channel {
    Grey,       // absent: grey (or grey+alpha) images only; colour images are rejected
    Luminance,  // Rec. 709 luminance of RGB
    Red,
    Green,
    Blue,
};

struct TerrainSource {
    std::string heightmap;       // file to load; empty = generate
    int generateSize = 1025;     // samples per side of a generated terrain, 2^n + 1
    uint64_t seed = 1;           // seed of the generator
    float roughness = 1.0f;      // amplitude factor of every random offset of the generator, > 0
    std::optional<float> hurst;  // per-level amplitude factor 2^-H of the generator;
                                 // absent = the generator's default scaling
    int rawWidth = 0;            // samples per row of a .r16/.r32 file; 0 = guess a square
    int rawHeight = 0;           // rows of a .r16/.r32 file; give both or neither
    float spacing = 0.0f;        // world units between samples; 0 = the file's (1 for images)
    float verticalScale = 0.0f;  // stored height -> world height; 0 = automatic (see loadTerrain)
    SeaLevel seaLevel;           // default: automatic
    HeightUnits heightUnits = HeightUnits::Auto;
    Channel channel = Channel::Grey;
    bool operator==(const TerrainSource&) const = default;
};

// Names used by the command line and the JSON form; parse* throw sierra::Error
// naming `what` (an option or key) and the accepted names.
const char* toString(SeaLevel::Mode mode);  // "auto" "none" "value"
const char* toString(HeightUnits units);    // "auto" "m" "none"
const char* toString(Channel channel);      // "grey" "luminance" "r" "g" "b"
HeightUnits parseHeightUnits(const std::string& text, const std::string& what);  // also "metres"
Channel parseChannel(const std::string& text, const std::string& what);

// Parses "WIDTHxHEIGHT" of a frame (each 1..16384); throws sierra::Error naming `option`.
std::pair<int, int> parseFrameSize(const std::string& text, const std::string& option = "--size");

// Parses "WIDTHxHEIGHT" of a raw heightmap (each 1..65537, the loaders' limit);
// throws sierra::Error naming `option`.
std::pair<int, int> parseRawSize(const std::string& text, const std::string& option = "--raw-size");

// How loadTerrain shapes the grid.
enum class Padding {
    PowerOfTwoPlusOne,  // the SBT's (2^n+1)^2 grid: edge-clamped, the padding masked (the default)
    None,               // the samples as read, any width x height (the TIN meshes exactly these)
};

// The terrain ready for the SBT (or, with Padding::None, as read). Automatic spacing is the
// loader's (1 for image and array formats; SRTM: 90 m for 1201 wide tiles, 30 m for 3601; GeoTIFF:
// the pixel size of a projected system). Automatic vertical scale is 1 for metric heights
// (metricHeights) and otherwise makes the relief 20% of the horizontal
// extent. `description`, when given, receives one line saying what was loaded and the choices made.
// Throws sierra::Error for bad input, and for a `hurst` or `channel` that this build's terrain
// module cannot honour yet.
// Spacing, vertical scale and description do not depend on `padding`.
// `maxPaddedSide` is the largest (2^n+1) grid side the caller can take (a
// renderer: its GL's texture limit, see render::TerrainGpu::maxGridSide); a
// file or a generator size that pads past it is refused before its samples
// are allocated.
terrain::Heightfield loadTerrain(const TerrainSource& source, std::string* description = nullptr,
                                 Padding padding = Padding::PowerOfTwoPlusOne,
                                 int maxPaddedSide = terrain::kDefaultMaxPaddedSide);

// The same for a grid from elsewhere (an array an embedding program hands
// over): loadTerrain's padding, spacing and vertical scale, with the automatic
// choices of a loaded heightmap (no water unless asked). `source.heightmap`
// names the grid in messages and the description; `field` carries its own
// spacing and no-data mask. Throws sierra::Error for a grid under 2x2 or one
// that pads past `maxPaddedSide`.
terrain::Heightfield prepareTerrain(terrain::Heightfield field, const TerrainSource& source,
                                    std::string* description = nullptr,
                                    Padding padding = Padding::PowerOfTwoPlusOne,
                                    int maxPaddedSide = terrain::kDefaultMaxPaddedSide);

// True when the heights of `field`, loaded from `source`, are metres: height
// units `m`, or automatic with an SRTM (.hgt) or GeoTIFF file, or with a file
// whose georeferencing says metres (terrain::Heightfield::metres: an .npz
// with geographic bounds).
bool metricHeights(const TerrainSource& source, const terrain::Heightfield& field);

// The height below which `share` (0..1) of the valid samples lie.
float heightQuantile(const terrain::Heightfield& field, double share);

// The sea level to draw, in stored height units, or NaN for no water. A value
// is taken as given; automatic water appears only on generated terrain (the
// height below which 30% of the samples lie, a coast on any fractal) and on
// metric data that reaches below 0 (topobathymetry: sea level 0); a loaded
// unitless heightmap, or land above 0 m, gets none.
float resolveSeaLevel(const TerrainSource& source, const terrain::Heightfield& field);

}  // namespace sierra::scene
