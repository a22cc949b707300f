#include <sierra/terrain/SunPosition.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace sierra::terrain {

namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

double sinDeg(double d) {
    return std::sin(d * kDegrees);
}
double cosDeg(double d) {
    return std::cos(d * kDegrees);
}
double tanDeg(double d) {
    return std::tan(d * kDegrees);
}

// Days from 1970-01-01 to the proleptic Gregorian date (H. Hinnant's
// days_from_civil).
long long daysFromCivil(long long y, unsigned m, unsigned d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = unsigned(y - era * 400);
    const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + (long long)(doe)-719468;
}

bool leapYear(int y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

// Reads exactly `digits` decimal digits at text[pos], advancing pos.
bool digitsAt(const std::string& text, size_t& pos, int digits, int& value) {
    if (pos + size_t(digits) > text.size()) return false;
    value = 0;
    for (int k = 0; k < digits; ++k) {
        const char c = text[pos + size_t(k)];
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
        value = value * 10 + (c - '0');
    }
    pos += size_t(digits);
    return true;
}

}  // namespace

double parseUtcTime(const std::string& text, const std::string& what) {
    auto fail = [&](const char* why) {
        return Error(msg(what, " '", text, "': ", why,
                         "; expected an ISO 8601 time with its zone, e.g. 2026-06-21T17:30:00Z or "
                         "2026-06-21T19:30:00+02:00"));
    };
    size_t p = 0;
    int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
    double fraction = 0.0;
    if (!digitsAt(text, p, 4, year) || p >= text.size() || text[p++] != '-' ||
        !digitsAt(text, p, 2, month) || p >= text.size() || text[p++] != '-' ||
        !digitsAt(text, p, 2, day))
        throw fail("no date YYYY-MM-DD");
    if (p >= text.size() || (text[p] != 'T' && text[p] != 't' && text[p] != ' '))
        throw fail("no time after the date");
    ++p;
    if (!digitsAt(text, p, 2, hour) || p >= text.size() || text[p++] != ':' ||
        !digitsAt(text, p, 2, minute))
        throw fail("no time HH:MM");
    if (p < text.size() && text[p] == ':') {
        ++p;
        if (!digitsAt(text, p, 2, second)) throw fail("no seconds after HH:MM:");
        if (p < text.size() && (text[p] == '.' || text[p] == ',')) {
            ++p;
            double scale = 0.1;
            const size_t start = p;
            while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) {
                fraction += scale * (text[p] - '0');
                scale *= 0.1;
                ++p;
            }
            if (p == start) throw fail("no digits after the decimal point");
        }
    }
    int offsetMinutes = 0;
    if (p >= text.size()) throw fail("no time zone (Z or +hh:mm)");
    if (text[p] == 'Z' || text[p] == 'z') {
        ++p;
    } else if (text[p] == '+' || text[p] == '-') {
        const int sign = text[p] == '-' ? -1 : 1;
        ++p;
        int oh = 0, om = 0;
        if (!digitsAt(text, p, 2, oh)) throw fail("a zone offset needs hours, +hh:mm");
        if (p < text.size() && text[p] == ':') ++p;
        if (p < text.size() && !digitsAt(text, p, 2, om)) throw fail("bad zone offset minutes");
        if (oh > 18 || om > 59) throw fail("zone offset out of range (at most +-18:00)");
        offsetMinutes = sign * (oh * 60 + om);
    } else {
        throw fail("no time zone (Z or +hh:mm)");
    }
    if (p != text.size()) throw fail("unexpected characters after the time");
    static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (month < 1 || month > 12) throw fail("month out of range 01..12");
    const int monthDays = kDays[month - 1] + (month == 2 && leapYear(year) ? 1 : 0);
    if (day < 1 || day > monthDays) throw fail("day out of range for the month");
    if (hour > 23 || minute > 59 || second > 60) throw fail("time of day out of range");
    const long long days = daysFromCivil(year, unsigned(month), unsigned(day));
    return double(days) * 86400.0 + hour * 3600.0 + minute * 60.0 + second + fraction -
           offsetMinutes * 60.0;
}

std::string formatUtcTime(double unixSeconds) {
    const long long total = std::llround(unixSeconds);
    long long days = total / 86400, rest = total % 86400;
    if (rest < 0) {
        rest += 86400;
        --days;
    }
    // H. Hinnant's civil_from_days.
    days += 719468;
    const long long era = (days >= 0 ? days : days - 146096) / 146097;
    const unsigned doe = unsigned(days - era * 146097);
    const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const unsigned mp = (5 * doy + 2) / 153;
    const unsigned d = doy - (153 * mp + 2) / 5 + 1;
    const unsigned m = mp < 10 ? mp + 3 : mp - 9;
    const long long y = (long long)(yoe) + era * 400 + (m <= 2);
    char text[64];
    std::snprintf(text, sizeof text, "%04lld-%02u-%02uT%02lld:%02lld:%02lldZ", y, m, d, rest / 3600,
                  rest / 60 % 60, rest % 60);
    return text;
}

SunPosition sunPosition(double unixSeconds, double latitude, double longitude) {
    SIERRA_CHECK(std::isfinite(unixSeconds), "the sun's position needs a finite time");
    SIERRA_CHECK(std::isfinite(latitude) && std::abs(latitude) <= 90.0,
                 "latitude must be -90..90 degrees, got ", latitude);
    SIERRA_CHECK(std::isfinite(longitude) && longitude >= -180.0 && longitude <= 360.0,
                 "longitude must be -180..360 degrees, got ", longitude);
    // The NOAA spreadsheet's columns, in its order and names.
    const double julianDay = unixSeconds / 86400.0 + 2440587.5;
    const double t = (julianDay - 2451545.0) / 36525.0;  // Julian century
    const double meanLongitude =
        std::fmod(280.46646 + t * (36000.76983 + t * 0.0003032), 360.0);  // degrees
    const double meanAnomaly = 357.52911 + t * (35999.05029 - 0.0001537 * t);
    const double eccentricity = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
    const double centre = sinDeg(meanAnomaly) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                          sinDeg(2.0 * meanAnomaly) * (0.019993 - 0.000101 * t) +
                          sinDeg(3.0 * meanAnomaly) * 0.000289;
    const double trueLongitude = meanLongitude + centre;
    const double omega = 125.04 - 1934.136 * t;
    const double apparentLongitude = trueLongitude - 0.00569 - 0.00478 * sinDeg(omega);
    const double meanObliquity =
        23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
    const double obliquity = meanObliquity + 0.00256 * cosDeg(omega);
    const double declination = std::asin(sinDeg(obliquity) * sinDeg(apparentLongitude)) / kDegrees;
    const double y = tanDeg(obliquity / 2.0) * tanDeg(obliquity / 2.0);
    const double l0 = meanLongitude * kDegrees, m = meanAnomaly * kDegrees;
    const double equationOfTime =
        4.0 / kDegrees *
        (y * std::sin(2.0 * l0) - 2.0 * eccentricity * std::sin(m) +
         4.0 * eccentricity * y * std::sin(m) * std::cos(2.0 * l0) -
         0.5 * y * y * std::sin(4.0 * l0) - 1.25 * eccentricity * eccentricity * std::sin(2.0 * m));
    // Minutes past UTC midnight; the spreadsheet's time zone is 0 here.
    double dayMinutes = std::fmod(unixSeconds / 60.0, 1440.0);
    if (dayMinutes < 0.0) dayMinutes += 1440.0;
    double trueSolarTime = std::fmod(dayMinutes + equationOfTime + 4.0 * longitude, 1440.0);
    if (trueSolarTime < 0.0) trueSolarTime += 1440.0;
    const double hourAngle =
        trueSolarTime / 4.0 < 0.0 ? trueSolarTime / 4.0 + 180.0 : trueSolarTime / 4.0 - 180.0;
    const double cosZenith =
        std::clamp(sinDeg(latitude) * sinDeg(declination) +
                       cosDeg(latitude) * cosDeg(declination) * cosDeg(hourAngle),
                   -1.0, 1.0);
    const double zenith = std::acos(cosZenith) / kDegrees;
    const double elevation = 90.0 - zenith;
    // Atmospheric refraction in arc seconds, by the calculator's bands.
    double refraction = 0.0;
    if (elevation <= 85.0) {
        const double te = tanDeg(elevation);
        if (elevation > 5.0)
            refraction = 58.1 / te - 0.07 / (te * te * te) + 0.000086 / std::pow(te, 5.0);
        else if (elevation > -0.575)
            refraction =
                1735.0 +
                elevation *
                    (-518.2 + elevation * (103.4 + elevation * (-12.79 + elevation * 0.711)));
        else
            refraction = -20.772 / te;
    }
    // Azimuth: undefined at the zenith and the poles' axis; the spreadsheet's
    // arccos argument is clamped so those give a finite bearing.
    const double sinZenith = std::sin(zenith * kDegrees);
    const double denominator = cosDeg(latitude) * sinZenith;
    double azimuth = 180.0;
    if (std::abs(denominator) > 1e-12) {
        const double a =
            std::acos(std::clamp((sinDeg(latitude) * cosZenith - sinDeg(declination)) / denominator,
                                 -1.0, 1.0)) /
            kDegrees;
        azimuth = hourAngle > 0.0 ? std::fmod(a + 180.0, 360.0) : std::fmod(540.0 - a, 360.0);
    }
    return {.azimuth = azimuth,
            .altitude = elevation + refraction / 3600.0,
            .geometricAltitude = elevation,
            .declination = declination,
            .equationOfTime = equationOfTime,
            .hourAngle = hourAngle};
}

}  // namespace sierra::terrain
