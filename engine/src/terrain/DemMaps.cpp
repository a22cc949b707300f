#include <sierra/terrain/DemMaps.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sierra::terrain {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The 3x3 window of (i, j) in stored heights, with gdaldem's rules at the
// edges and next to no data (DemMaps.h). False where the sample gets no value.
bool window(const Heightfield& f, int i, int j, bool computeEdges, double w[9]) {
    const int width = f.width(), height = f.height();
    if (!f.valid(i, j)) return false;
    const bool inside = i > 0 && j > 0 && i < width - 1 && j < height - 1;
    if (!inside && !computeEdges) return false;
    // Samples with no data, and values extrapolated from them, are NaN here.
    auto get = [&](int x, int y) { return f.valid(x, y) ? double(f.at(x, y)) : std::nan(""); };
    auto extrapolate = [](double a, double b) { return 2.0 * a - b; };  // NaN in, NaN out
    if (inside) {
        for (int k = 0; k < 9; ++k) w[k] = get(i + k % 3 - 1, j + k / 3 - 1);
    } else if (j == 0 || j == height - 1) {
        // First or last row: the missing row extrapolated across the rows; the
        // columns clamp at the corners.
        const int cols[3] = {std::max(i - 1, 0), i, std::min(i + 1, width - 1)};
        const int near = j == 0 ? 1 : j - 1;  // the row inside the grid
        for (int n = 0; n < 3; ++n) {
            const double here = get(cols[n], j), in = get(cols[n], near);
            const double out = extrapolate(here, in);
            w[n] = j == 0 ? out : in;
            w[3 + n] = here;
            w[6 + n] = j == 0 ? in : out;
        }
    } else {
        // First or last column of an inner row: extrapolated across the columns.
        const int near = i == 0 ? 1 : i - 1;
        for (int r = 0; r < 3; ++r) {
            const double here = get(i, j + r - 1), in = get(near, j + r - 1);
            const double out = extrapolate(here, in);
            w[3 * r] = i == 0 ? out : in;
            w[3 * r + 1] = here;
            w[3 * r + 2] = i == 0 ? in : out;
        }
    }
    for (int k = 0; k < 9; ++k)
        if (std::isnan(w[k])) {
            if (!computeEdges) return false;
            w[k] = w[4];
        }
    return true;
}

// First derivatives, east (p) and north (q), of world heights.
struct Gradient {
    double p, q;
};

Gradient gradient(const double w[9], Stencil stencil, double hx, double hy) {
    switch (stencil) {
        case Stencil::Horn:
            return {((w[2] + 2 * w[5] + w[8]) - (w[0] + 2 * w[3] + w[6])) / (8 * hx),
                    ((w[0] + 2 * w[1] + w[2]) - (w[6] + 2 * w[7] + w[8])) / (8 * hy)};
        case Stencil::ZevenbergenThorne:
            return {(w[5] - w[3]) / (2 * hx), (w[1] - w[7]) / (2 * hy)};
        case Stencil::EvansYoung:
            break;
    }
    return {((w[2] + w[5] + w[8]) - (w[0] + w[3] + w[6])) / (6 * hx),
            ((w[0] + w[1] + w[2]) - (w[6] + w[7] + w[8])) / (6 * hy)};
}

// Second derivatives of the quadratic z = r x^2/2 + s x y + t y^2/2 + p x + q y + c.
struct Second {
    double r, s, t;
};

Second second(const double w[9], Stencil stencil, double hx, double hy) {
    const double s = (w[2] + w[6] - w[0] - w[8]) / (4 * hx * hy);
    if (stencil == Stencil::ZevenbergenThorne)
        return {(w[3] - 2 * w[4] + w[5]) / (hx * hx), s, (w[1] - 2 * w[4] + w[7]) / (hy * hy)};
    return {(w[0] + w[2] + w[3] + w[5] + w[6] + w[8] - 2 * (w[1] + w[4] + w[7])) / (3 * hx * hx), s,
            (w[0] + w[1] + w[2] + w[6] + w[7] + w[8] - 2 * (w[3] + w[4] + w[5])) / (3 * hy * hy)};
}

// Compass bearing in degrees [0, 360) of the downhill direction.
double downhillBearing(Gradient g) {
    double a = std::atan2(-g.p, -g.q) / kDegrees;
    if (a < 0.0) a += 360.0;
    if (a >= 360.0) a -= 360.0;
    return a + 0.0;  // no -0
}

// Cosine of the angle between the unit normal and a light at (azimuth,
// altitude) in radians.
double lambert(Gradient g, double azimuth, double altitude) {
    const double along = g.p * std::sin(azimuth) + g.q * std::cos(azimuth);
    return (std::sin(altitude) - std::cos(altitude) * along) /
           std::sqrt(1.0 + g.p * g.p + g.q * g.q);
}

double shade(Gradient g, const DemFieldDesc& d) {
    const double az = d.azimuth * kDegrees, alt = d.altitude * kDegrees;
    const double g2 = g.p * g.p + g.q * g.q;
    double v = 0.0;
    switch (d.shade) {
        case ShadeStyle::Oblique:
            v = lambert(g, az, alt);
            break;
        case ShadeStyle::Combined: {
            const double angle = std::acos(std::clamp(lambert(g, az, alt), -1.0, 1.0));
            const double quarter = std::numbers::pi / 2;
            v = 1.0 - angle * std::atan(std::sqrt(g2)) / (quarter * quarter);
            break;
        }
        case ShadeStyle::Multidirectional: {
            double sum = 0.0, weights = 0.0;
            for (double lightAz : {225.0, 270.0, 315.0, 360.0}) {
                const double a = lightAz * kDegrees;
                const double along = g.p * std::sin(a) + g.q * std::cos(a);
                const double weight = g2 > 0.0 ? along * along / g2 : 0.5;
                sum += weight * std::max(0.0, lambert(g, a, alt));
                weights += weight;
            }
            v = sum / weights;
            break;
        }
        case ShadeStyle::Igor: {
            const double slope = std::atan(std::sqrt(g2)) / kDegrees;
            double diff = std::abs(downhillBearing(g) - d.azimuth);
            diff = std::fmod(diff, 360.0);
            if (diff > 180.0) diff = 360.0 - diff;
            return 255.0 * (1.0 - slope / 90.0 * diff / 180.0);
        }
    }
    return v <= 0.0 ? 1.0 : 1.0 + 254.0 * v;
}

double curvature(DemField field, Gradient g, Second c) {
    const double p = g.p, q = g.q, r = c.r, s = c.s, t = c.t;
    const double gg = p * p + q * q, ww = 1.0 + gg;
    // Florinsky's signs: the minus makes a hilltop (r, t < 0) positive.
    const double mean =
        -((1 + q * q) * r - 2 * p * q * s + (1 + p * p) * t) / (2 * std::pow(ww, 1.5));
    const double gauss = (r * t - s * s) / (ww * ww);
    const double spread = std::sqrt(std::max(0.0, mean * mean - gauss));
    const double contour = -(q * q * r - 2 * p * q * s + p * p * t);
    switch (field) {
        case DemField::CurvatureProfile:
            return gg > 0.0 ? -(p * p * r + 2 * p * q * s + q * q * t) / (gg * std::pow(ww, 1.5))
                            : 0.0;
        case DemField::CurvaturePlan:
            return gg > 0.0 ? contour / std::pow(gg, 1.5) : 0.0;
        case DemField::CurvatureTangential:
            return gg > 0.0 ? contour / (gg * std::sqrt(ww)) : 0.0;
        case DemField::CurvatureMean:
            return mean;
        case DemField::CurvatureGaussian:
            return gauss;
        case DemField::CurvatureMinimal:
            return mean - spread;
        default:
            return mean + spread;
    }
}

double value(const double w[9], const DemFieldDesc& d, double hx, double hy) {
    const Stencil stencil = d.stencil;
    switch (d.field) {
        case DemField::Slope: {
            const Gradient g = gradient(w, stencil, hx, hy);
            const double rise = std::hypot(g.p, g.q);
            return d.slopeUnits == SlopeUnits::Percent ? 100.0 * rise : std::atan(rise) / kDegrees;
        }
        case DemField::Aspect: {
            const Gradient g = gradient(w, stencil, hx, hy);
            if (g.p == 0.0 && g.q == 0.0) return d.zeroForFlat ? 0.0 : std::nan("");
            const double a = downhillBearing(g);
            if (!d.trigonometric) return a;
            const double trig = std::fmod(450.0 - a, 360.0);
            return trig + 0.0;
        }
        case DemField::Hillshade: {
            Gradient g = gradient(w, stencil, hx, hy);
            g.p *= d.zFactor, g.q *= d.zFactor;
            return shade(g, d);
        }
        case DemField::Tri: {
            double sum = 0.0;
            for (int k = 0; k < 9; ++k) {
                const double e = w[k] - w[4];
                sum += d.tri == TriFormula::Riley ? e * e : std::abs(e);
            }
            return d.tri == TriFormula::Riley ? std::sqrt(sum) : sum / 8.0;
        }
        case DemField::Tpi: {
            double sum = 0.0;
            for (int k = 0; k < 9; ++k)
                if (k != 4) sum += w[k];
            return w[4] - sum / 8.0;
        }
        case DemField::Roughness: {
            const auto [lo, hi] = std::minmax_element(w, w + 9);
            return *hi - *lo;
        }
        default:
            return curvature(d.field, gradient(w, stencil, hx, hy), second(w, stencil, hx, hy));
    }
}

}  // namespace

bool isCurvature(DemField field) {
    return field >= DemField::CurvatureProfile;
}

std::vector<float> demField(const Heightfield& field, const DemFieldDesc& desc) {
    SIERRA_CHECK(!field.empty(), "cannot compute a DEM field of an empty heightfield");
    SIERRA_CHECK(!isCurvature(desc.field) || desc.stencil != Stencil::Horn,
                 "curvatures need a quadratic: the Evans-Young or Zevenbergen-Thorne stencil, "
                 "not Horn's gradient");
    if (desc.field == DemField::Hillshade) {
        SIERRA_CHECK(std::isfinite(desc.azimuth) && desc.altitude >= 0.0f && desc.altitude <= 90.0f,
                     "sun azimuth ", desc.azimuth, " and altitude ", desc.altitude,
                     " degrees: need a finite azimuth and an altitude in 0..90");
        SIERRA_CHECK(std::isfinite(desc.zFactor) && desc.zFactor > 0.0f, "z factor ", desc.zFactor,
                     ": must be > 0");
    }
    const double vs = field.verticalScale();
    const double hx = field.spacingX(), hy = field.spacingZ();
    std::vector<float> out(size_t(field.sampleCount()), kNaN);
    double w[9];
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            if (!window(field, i, j, desc.computeEdges, w)) continue;
            for (double& v : w) v *= vs;
            out[size_t(j) * size_t(field.width()) + size_t(i)] = float(value(w, desc, hx, hy));
        }
    return out;
}

bool parseDemField(const std::string& name, DemField* out) {
    static const std::pair<const char*, DemField> kNames[] = {
        {"slope", DemField::Slope},
        {"aspect", DemField::Aspect},
        {"hillshade", DemField::Hillshade},
        {"tri", DemField::Tri},
        {"tpi", DemField::Tpi},
        {"roughness", DemField::Roughness},
        {"curvature-profile", DemField::CurvatureProfile},
        {"curvature-plan", DemField::CurvaturePlan},
        {"curvature-tangential", DemField::CurvatureTangential},
        {"curvature-mean", DemField::CurvatureMean},
        {"curvature-gaussian", DemField::CurvatureGaussian},
        {"curvature-min", DemField::CurvatureMinimal},
        {"curvature-max", DemField::CurvatureMaximal},
    };
    for (const auto& [n, f] : kNames)
        if (name == n) {
            if (out) *out = f;
            return true;
        }
    return false;
}

}  // namespace sierra::terrain
