#pragma once
// The sun's position in the sky from a place and a time (no GL): the NOAA
// Solar Calculator's equations (after Meeus, "Astronomical Algorithms",
// 1991), accurate to about 0.01 degree for years 1800..2200 away from the
// horizon, with the calculator's correction for atmospheric refraction.

#include <string>

namespace sierra::terrain {

// Seconds since 1970-01-01T00:00:00Z (UTC, leap seconds ignored) of an ISO 8601
// date and time: YYYY-MM-DDTHH:MM[:SS[.fff]] followed by Z or an offset
// +hh:mm / -hh:mm (also +hhmm, +hh) from UTC; a space may stand for the T.
// Throws sierra::Error naming `what` (an option or key) for anything else,
// a time without a zone included (it would be ambiguous).
double parseUtcTime(const std::string& text, const std::string& what = "time");

// The same instant written back as YYYY-MM-DDTHH:MM:SSZ (whole seconds, rounded).
std::string formatUtcTime(double unixSeconds);

struct SunPosition {
    double azimuth = 0.0;   // compass bearing of the sun, degrees clockwise from north, 0..360
    double altitude = 0.0;  // degrees above the horizon, refraction included
    double geometricAltitude = 0.0;  // degrees above the horizon, without refraction
    double declination = 0.0;        // degrees
    double equationOfTime = 0.0;     // minutes, true solar time minus mean solar time
    double hourAngle = 0.0;          // degrees, 0 at local solar noon, negative before
};

// The sun seen from `latitude` (degrees north, -90..90) and `longitude`
// (degrees east, -180..360) at `unixSeconds` (parseUtcTime). Throws
// sierra::Error for a place outside those ranges or a non-finite time.
SunPosition sunPosition(double unixSeconds, double latitude, double longitude);

}  // namespace sierra::terrain
