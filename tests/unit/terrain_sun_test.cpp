// The sun's position (terrain/SunPosition.h) against values the NOAA Solar
// Calculator's equations give, computed offline by an independent
// transcription (tests/unit/terrain_sun_reference.py: Python's own date
// arithmetic, the azimuth by atan2), and against facts known without them:
// solar noon at Greenwich near 12:07 UTC on the March equinox with the sun
// 90 - latitude high, the June solstice's declination of 23.44 degrees.
// ISO 8601 times with zones, and the malformed ones refused.

#include <sierra/core/Error.h>
#include <sierra/terrain/SunPosition.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sierra::terrain {
namespace {

constexpr double kTolerance = 0.01;  // degrees

struct Reference {
    const char* time;
    double latitude, longitude;
    double azimuth, altitude, declination, equationOfTime;  // degrees; minutes
};

// python3 tests/unit/terrain_sun_reference.py
constexpr Reference kReferences[] = {
    {"2026-06-21T17:30:00Z", 40.0150, -105.2705, 123.261057, 64.353650, 23.437630, -1.874096},
    {"2026-12-21T02:00:00Z", -33.8688, 151.2093, 351.234790, 79.458864, -23.435427, 2.129353},
    // The sun just below the horizon, lifted by refraction (the band below -0.575 degrees).
    {"2026-01-15T11:00:00Z", 69.6492, 18.9553, 181.499899, -0.280455, -21.075524, -9.391920},
};

TEST(SunPosition, MatchesTheReferenceAtThreePlaces) {
    for (const Reference& r : kReferences) {
        SCOPED_TRACE(r.time);
        SunPosition s = sunPosition(parseUtcTime(r.time), r.latitude, r.longitude);
        EXPECT_NEAR(s.azimuth, r.azimuth, kTolerance);
        EXPECT_NEAR(s.altitude, r.altitude, kTolerance);
        EXPECT_NEAR(s.declination, r.declination, kTolerance);
        EXPECT_NEAR(s.equationOfTime, r.equationOfTime, 0.01);
    }
}

TEST(SunPosition, SolarNoonAtGreenwichOnTheEquinox) {
    // 2026's March equinox is on 20 March; the equation of time is then about
    // -7.5 minutes, so the sun crosses the meridian near 12:07:30 UTC.
    const double latitude = 51.4769, longitude = -0.0005;
    const double start = parseUtcTime("2026-03-20T11:30:00Z");
    // Solar noon: the hour angle's zero crossing, to the second. The highest
    // sun comes a few seconds later (the declination rises through the day).
    double noon = start, highest = -90.0;
    for (int second = 0; second <= 3600; ++second) {
        SunPosition s = sunPosition(start + second, latitude, longitude);
        if (std::abs(s.hourAngle) < std::abs(sunPosition(noon, latitude, longitude).hourAngle))
            noon = start + second;
        highest = std::max(highest, s.altitude);
    }
    EXPECT_GE(noon, parseUtcTime("2026-03-20T12:06:00Z"));
    EXPECT_LE(noon, parseUtcTime("2026-03-20T12:09:00Z"));
    EXPECT_NEAR(highest, 90.0 - latitude, 0.5);
    SunPosition atNoon = sunPosition(noon, latitude, longitude);
    EXPECT_NEAR(atNoon.azimuth, 180.0, 0.01);
    EXPECT_NEAR(atNoon.hourAngle, 0.0, 0.005);  // a second is 0.0042 degrees
    EXPECT_NEAR(atNoon.altitude, highest, 0.001);
    EXPECT_NEAR(atNoon.declination, 0.0, 0.5);
}

TEST(SunPosition, JuneSolsticeDeclination) {
    // 2026's June solstice: 21 June, 08:24 UTC; the obliquity is 23.436 degrees.
    SunPosition s = sunPosition(parseUtcTime("2026-06-21T08:24:00Z"), 0.0, 0.0);
    EXPECT_NEAR(s.declination, 23.44, 0.01);
    // A day either side the declination is lower.
    EXPECT_LT(sunPosition(parseUtcTime("2026-06-20T08:24:00Z"), 0.0, 0.0).declination,
              s.declination);
    EXPECT_LT(sunPosition(parseUtcTime("2026-06-22T08:24:00Z"), 0.0, 0.0).declination,
              s.declination);
}

TEST(SunPosition, MorningEastAfternoonWest) {
    const double day = parseUtcTime("2026-09-01T00:00:00Z");
    // Zurich: 47.37 N, 8.54 E; local solar noon near 11:25 UTC.
    SunPosition morning = sunPosition(day + 7 * 3600, 47.37, 8.54);
    SunPosition evening = sunPosition(day + 16 * 3600, 47.37, 8.54);
    EXPECT_GT(morning.azimuth, 45.0);
    EXPECT_LT(morning.azimuth, 135.0);
    EXPECT_GT(evening.azimuth, 225.0);
    EXPECT_LT(evening.azimuth, 315.0);
    EXPECT_LT(sunPosition(day, 47.37, 8.54).altitude, 0.0);  // midnight
}

TEST(SunPosition, RefusesPlacesOutsideTheGlobe) {
    EXPECT_THROW(sunPosition(0.0, 91.0, 0.0), Error);
    EXPECT_THROW(sunPosition(0.0, 0.0, -181.0), Error);
    EXPECT_THROW(sunPosition(NAN, 0.0, 0.0), Error);
}

TEST(UtcTime, ZonesAndFractions) {
    const double utc = parseUtcTime("2026-06-21T17:30:00Z");
    EXPECT_DOUBLE_EQ(utc, 1782063000.0);  // date -u -d 2026-06-21T17:30:00Z +%s
    EXPECT_DOUBLE_EQ(parseUtcTime("2026-06-21T19:30:00+02:00"), utc);
    EXPECT_DOUBLE_EQ(parseUtcTime("2026-06-21T12:00:00-05:30"), utc);
    EXPECT_DOUBLE_EQ(parseUtcTime("2026-06-21T23:30:00+06:00"), utc);
    EXPECT_DOUBLE_EQ(parseUtcTime("2026-06-21T19:30+0200"), utc);
    EXPECT_DOUBLE_EQ(parseUtcTime("2026-06-21 17:30:00.5Z"), utc + 0.5);
    EXPECT_DOUBLE_EQ(parseUtcTime("1970-01-01T00:00:00Z"), 0.0);
    EXPECT_DOUBLE_EQ(parseUtcTime("2024-02-29T00:00:00Z"), 1709164800.0);
    EXPECT_EQ(formatUtcTime(utc), "2026-06-21T17:30:00Z");
    EXPECT_EQ(formatUtcTime(-1.0), "1969-12-31T23:59:59Z");
}

TEST(UtcTime, RefusesMalformedTimes) {
    for (const char* bad :
         {"", "2026-06-21", "2026-06-21T17:30:00", "2026-13-01T00:00Z", "2026-02-29T00:00Z",
          "2026-06-21T24:00Z", "2026-06-21T17:61Z", "2026-06-21T17:30:00+25:00",
          "2026-06-21T17:30:00Zjunk", "noon", "2026/06/21T17:30Z", "2026-06-21T17:30:00."}) {
        SCOPED_TRACE(bad);
        try {
            parseUtcTime(bad, "--sun-time");
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--sun-time"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace sierra::terrain
