#pragma once
// Relief lighting fields of a heightfield (no GL): horizon angles in D
// azimuths, the sun's visibility (soft cast shadows), the sky-view factor, the
// cosine-weighted sky light the terrain pass uses as its ambient term, and
// openness. All in world units (the heightfield's spacing and vertical scale).
//
// Azimuths are compass bearings in degrees, clockwise from north; north is
// -z (row 0 of the grid), east +x. Fields are row-major like the heightfield
// (index j * width + i). No-data samples neither cast nor receive: their
// values are NaN and they are skipped as occluders; so is the padding
// (HorizonOptions::validWidth / validHeight).
//
// Horizons are found by a sweep per azimuth along digital lines that tile the
// grid (docs/relief.md): the occluder of a sample is the point of its line's
// profile where the tangent from it touches the profile's upper hull, the
// profile's abscissa being the projection onto the azimuth; the elevation is
// then taken at that point's true horizontal distance. Grid-aligned azimuths
// (the axes, and the diagonals on a square grid) are exact for the surface as
// drawn at full resolution. O(samples) per azimuth without a radius.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <vector>

namespace sierra::analysis {

struct HorizonOptions {
    // Azimuths: `directions` evenly spaced bearings starting at `firstAzimuth`
    // (degrees clockwise from north). Default 16, from north.
    int directions = 16;
    float firstAzimuth = 0.0f;
    // Search radius in world units, measured along the azimuth; 0 (the
    // default) searches the whole grid.
    float radius = 0.0f;
    // Columns and rows of real data (the rest is padding, which never casts);
    // 0 = the whole grid.
    int validWidth = 0;
    int validHeight = 0;
    // Worker threads (0 = sierra::defaultThreadCount()); the result does not
    // depend on it.
    int threads = 0;
};

// Horizon elevation angles in radians: angle[d * samples + j * width + i] is
// the elevation of the horizon seen from sample (i, j) towards azimuth d
// (>= -pi/2; negative where everything in that direction lies below the
// sample; -pi/2 at the grid's edge looking out). NaN at no-data samples.
struct Horizons {
    int width = 0;
    int height = 0;
    int directions = 0;
    float firstAzimuth = 0.0f;  // degrees
    std::vector<float> angle;
    float at(int d, int i, int j) const {
        return angle[size_t(d) * size_t(width) * size_t(height) + size_t(j) * size_t(width) +
                     size_t(i)];
    }
    float azimuthDegrees(int d) const {
        return firstAzimuth + 360.0f * float(d) / float(directions);
    }
};

// Throws sierra::Error for an empty field, directions outside 1..1024, a
// non-finite firstAzimuth, a negative or non-finite radius, valid sizes
// outside 0..width / 0..height, or negative threads.
Horizons computeHorizons(const terrain::Heightfield& field, const HorizonOptions& options);

// The sun as a disc: bearing and altitude of its centre in degrees, and its
// angular diameter (default 0.53, the sun seen from the Earth; > 0).
struct SunDisc {
    float azimuth = 315.0f;
    float altitude = 45.0f;
    float diameter = 0.53f;
};

// Fraction 0..1 of the sun's disc above the horizon in the sun's azimuth, per
// sample (NaN at no-data and in the padding): the area of the disc above a
// horizontal line at the horizon's elevation (a circular segment), so the
// disc's vertical extent gives the penumbra. One sweep, in the sun's azimuth
// only (options.directions and firstAzimuth are not used). A sun at or below
// the horizontal is taken as it is (a summit whose horizon is below 0 still
// sees part of it), except that a sun with altitude < -diameter / 2, its whole
// disc below the horizontal, gives 0 at every sample with data.
// Throws sierra::Error for a diameter outside (0, 180) or non-finite, a
// non-finite azimuth, an altitude outside [-90, 90], and bad options as
// computeHorizons.
std::vector<float> sunVisibility(const terrain::Heightfield& field, const SunDisc& sun,
                                 const HorizonOptions& options = {});

// Sky-view factor (Zaksek, Ostir and Kokalj, "Sky-View Factor as a Relief
// Visualization Technique", 2011): SVF = 1 - (1/D) sum_i sin(max(gamma_i, 0)).
std::vector<float> skyViewFactor(const Horizons& horizons);

// The ambient term of the terrain pass: the cosine-weighted fraction of a
// uniform sky that a sample's surface (its normal from the heightfield)
// sees past its horizons; 1 on a flat plane. Normals are central differences
// in world units (NormalMethod::Edge), as the terrain shader's. Per azimuth
// the sky from max(horizon, the tangent plane) to the zenith counts, weighted
// by n . w; the sum is normalised by pi and capped at 1. The closed form is in
// docs/relief.md. Throws sierra::Error when the horizons do not belong to the
// field.
std::vector<float> skyLight(const terrain::Heightfield& field, const Horizons& horizons);

// The same two fields straight from the heightfield, one azimuth's horizons
// at a time: one field of angles is kept instead of D (1 GiB for 16 azimuths
// at 4097^2, whose fresh pages alone cost the kernel about 1 s of CPU to
// map). Equal, bit for bit, to skyViewFactor(computeHorizons(field,
// options)) and skyLight(field, computeHorizons(field, options)); the same
// errors as computeHorizons, naming skyViewFactor or skyLight.
std::vector<float> skyViewFactor(const terrain::Heightfield& field, const HorizonOptions& options);
std::vector<float> skyLight(const terrain::Heightfield& field, const HorizonOptions& options);

// Openness (Yokoyama, Shirasawa and Pike, "Visualizing Topography by
// Openness", 2002), in degrees: positive is the mean zenith angle of the
// horizon over the D azimuths (90 - elevation), negative the mean nadir angle
// of the terrain seen from below (the positive openness of the inverted
// surface). Both use options.radius as Yokoyama's L. Azimuths in which
// nothing lies within reach (the grid's edge looking out) are left out of the
// mean; NaN where none is left, at no-data and in the padding.
std::vector<float> opennessPositive(const terrain::Heightfield& field,
                                    const HorizonOptions& options = {});
std::vector<float> opennessNegative(const terrain::Heightfield& field,
                                    const HorizonOptions& options = {});

}  // namespace sierra::analysis
