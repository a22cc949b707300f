#pragma once
// Scalar fields of a DEM from the 3x3 neighbourhood of each sample (no GL):
// slope, aspect, hillshade in four styles, terrain ruggedness (TRI), the
// topographic position index (TPI), roughness and the seven named curvatures
// of the local quadratic. The formulas, edge rules and no-data rules are those
// of gdaldem, so the numbers agree with it on the same raster; docs/maps.md
// gives them all.
//
// Geometry: the heightfield's row 0 is north and its columns run west to east
// (a north-up GeoTIFF's order); x is east, y north. Derivatives are in world
// units: stored heights times field.verticalScale(), distances
// field.spacingX() (east) and spacingZ() (north).
//
// The window of sample (i, j), w[0..8], row by row from the north-west:
//   w0 w1 w2      (row j - 1, north)
//   w3 w4 w5      (row j)
//   w6 w7 w8      (row j + 1, south)
// A sample gets NaN (where gdaldem writes its no-data value) when it has no
// data itself, or when its window reaches past the grid or into no data and
// computeEdges is off: the 1-sample border is NaN. With computeEdges, a window
// row or column past the grid is extrapolated linearly from the two nearest
// (2 a - b; on the first and last rows across the rows, with the columns
// clamped at the corners; on the first and last columns across the columns),
// and every window sample that is no data, or extrapolated from no data,
// takes the centre's height.

#include <sierra/terrain/Heightfield.h>

#include <string>
#include <vector>

namespace sierra::terrain {

// The stencil of the derivatives.
//   Horn (1981, "Hill shading and the reflectance map"): the gradient weighted
//     1-2-1 across the window (gdaldem's default); no second derivatives.
//   ZevenbergenThorne (1987, "Quantitative analysis of land surface
//     topography"): central differences of the four axis neighbours; a
//     quadratic through the nine samples for the curvatures.
//   EvansYoung (Evans 1979; Young 1978): the least-squares quadratic over the
//     nine samples, the curvatures' default; its gradient is the unweighted
//     Prewitt form.
enum class Stencil { Horn, ZevenbergenThorne, EvansYoung };

enum class DemField {
    Slope,      // degrees 0..90 (or percent: 100 * |gradient|)
    Aspect,     // compass degrees 0..360 the slope faces (downhill), 0 = north, 90 = east
    Hillshade,  // 1..255 (gdaldem's byte scale before rounding), 0 reserved for no data
    Tri,        // terrain ruggedness index, world height units
    Tpi,        // topographic position index: centre minus the mean of the 8, world height units
    Roughness,  // largest minus smallest of the 9, world height units
    // Curvatures, 1 / world units. Sign: Florinsky's ("Digital Terrain Analysis
    // in Soil Science and Geology", 2016): positive = convex (hilltops, ridges,
    // the shoulder of a slope), negative = concave (hollows, valleys, the foot
    // of a slope). With p, q the first and r, s, t the second derivatives of
    // the quadratic (x east, y north), G = p^2 + q^2, W = 1 + G:
    CurvatureProfile,     // -(p^2 r + 2pqs + q^2 t) / (G W^1.5): along the steepest slope
    CurvaturePlan,        // -(q^2 r - 2pqs + p^2 t) / G^1.5: of the contour line
    CurvatureTangential,  // -(q^2 r - 2pqs + p^2 t) / (G W^0.5): plan times the sine of the slope
    CurvatureMean,        // -((1 + q^2) r - 2pqs + (1 + p^2) t) / (2 W^1.5)
    CurvatureGaussian,    // (r t - s^2) / W^2 (the same under either sign convention)
    CurvatureMinimal,     // H - sqrt(H^2 - K), H the mean and K the Gaussian curvature
    CurvatureMaximal,     // H + sqrt(H^2 - K)
};

enum class SlopeUnits { Degrees, Percent };

// Hillshade styles (gdaldem's -combined, -multidirectional, -igor).
//   Oblique: 1 + 254 cos(angle between the normal and the sun), 1 when unlit.
//   Combined: 1 + 254 (1 - angle * slope / (pi/2)^2), angles in radians: the
//     oblique shade darkened by steepness.
//   Multidirectional: Mark's four lights from 225, 270, 315 and 360 degrees
//     (USGS Open-File Report 92-422, 1992), each lit shade max(0, cos)
//     weighted by cos^2 of the angle between its azimuth and the gradient's
//     (equal weights on flat ground). The azimuth is unused.
//   Igor: 255 (1 - slope/90 * |aspect - azimuth| / 180), degrees (Maperitive's
//     relief shading): dark only on steep slopes facing away. The altitude is
//     unused.
enum class ShadeStyle { Oblique, Combined, Multidirectional, Igor };

enum class TriFormula {
    Riley,   // sqrt(sum of the squared differences to the 8) (Riley, DeGloria and Elliot 1999)
    Wilson,  // mean absolute difference to the 8 (Wilson et al. 2007)
};

struct DemFieldDesc {
    DemField field = DemField::Slope;
    // Horn by default; the curvatures take ZevenbergenThorne or EvansYoung
    // (Horn has no second derivatives) and default to EvansYoung.
    Stencil stencil = Stencil::Horn;
    bool computeEdges = false;
    SlopeUnits slopeUnits = SlopeUnits::Degrees;
    // Aspect: trigonometric gives the counter-clockwise angle from east (0 =
    // east, 90 = north); zeroForFlat gives 0 instead of NaN where the gradient
    // is exactly zero.
    bool trigonometric = false;
    bool zeroForFlat = false;
    // Hillshade: the sun's compass azimuth (degrees clockwise from north,
    // default 315) and altitude above the horizon (0..90, default 45), and a
    // vertical exaggeration of the heights (default 1, > 0).
    float azimuth = 315.0f;
    float altitude = 45.0f;
    float zFactor = 1.0f;
    ShadeStyle shade = ShadeStyle::Oblique;
    TriFormula tri = TriFormula::Riley;
};

// The field per sample, row-major like the heightfield (index j * width + i),
// NaN where gdaldem writes no data (and for a flat aspect unless zeroForFlat).
// Throws sierra::Error for an empty field, a curvature with the Horn stencil,
// a non-finite or out-of-range sun, or a z factor that is not > 0.
std::vector<float> demField(const Heightfield& field, const DemFieldDesc& desc);

// Names as the map command spells them: "slope", "aspect", "hillshade", "tri",
// "tpi", "roughness", "curvature-profile", "curvature-plan",
// "curvature-tangential", "curvature-mean", "curvature-gaussian",
// "curvature-min", "curvature-max". False for any other name.
bool parseDemField(const std::string& name, DemField* out);
bool isCurvature(DemField field);

}  // namespace sierra::terrain
