#!/usr/bin/env python3
"""Reference values for tests/unit/terrain_sun_test.cpp: the NOAA Solar
Calculator's spreadsheet equations transcribed cell by cell, with the Julian
day from Python's datetime (not the engine's date arithmetic) and the azimuth
from atan2 of the horizontal components (not the spreadsheet's arccos and its
branches). Run offline: python3 terrain_sun_reference.py"""
import datetime
import math


def sun(when, lat, lon):
    epoch = datetime.datetime(2000, 1, 1, 12, tzinfo=datetime.timezone.utc)
    jd = 2451545.0 + (when - epoch).total_seconds() / 86400.0
    t = (jd - 2451545.0) / 36525.0
    rad, deg = math.radians, math.degrees
    l0 = (280.46646 + t * (36000.76983 + t * 0.0003032)) % 360.0
    m = 357.52911 + t * (35999.05029 - 0.0001537 * t)
    e = 0.016708634 - t * (0.000042037 + 0.0000001267 * t)
    c = (math.sin(rad(m)) * (1.914602 - t * (0.004817 + 0.000014 * t))
         + math.sin(rad(2 * m)) * (0.019993 - 0.000101 * t) + math.sin(rad(3 * m)) * 0.000289)
    true_long = l0 + c
    app_long = true_long - 0.00569 - 0.00478 * math.sin(rad(125.04 - 1934.136 * t))
    mean_obliq = 23 + (26 + ((21.448 - t * (46.815 + t * (0.00059 - t * 0.001813)))) / 60) / 60
    obliq = mean_obliq + 0.00256 * math.cos(rad(125.04 - 1934.136 * t))
    decl = deg(math.asin(math.sin(rad(obliq)) * math.sin(rad(app_long))))
    y = math.tan(rad(obliq / 2)) ** 2
    eot = 4 * deg(y * math.sin(2 * rad(l0)) - 2 * e * math.sin(rad(m))
                  + 4 * e * y * math.sin(rad(m)) * math.cos(2 * rad(l0))
                  - 0.5 * y * y * math.sin(4 * rad(l0)) - 1.25 * e * e * math.sin(2 * rad(m)))
    midnight = when.replace(hour=0, minute=0, second=0, microsecond=0)
    minutes = (when - midnight).total_seconds() / 60.0
    tst = (minutes + eot + 4 * lon) % 1440
    ha = tst / 4 + 180 if tst / 4 < 0 else tst / 4 - 180
    zen = deg(math.acos(math.sin(rad(lat)) * math.sin(rad(decl))
                        + math.cos(rad(lat)) * math.cos(rad(decl)) * math.cos(rad(ha))))
    el = 90 - zen
    if el > 85:
        r = 0
    elif el > 5:
        te = math.tan(rad(el))
        r = 58.1 / te - 0.07 / te ** 3 + 0.000086 / te ** 5
    elif el > -0.575:
        r = 1735 + el * (-518.2 + el * (103.4 + el * (-12.79 + el * 0.711)))
    else:
        r = -20.772 / math.tan(rad(el))
    # Azimuth from the local east and north components of the sun's direction.
    east = -math.cos(rad(decl)) * math.sin(rad(ha))
    north = (math.cos(rad(lat)) * math.sin(rad(decl))
             - math.sin(rad(lat)) * math.cos(rad(decl)) * math.cos(rad(ha)))
    az = deg(math.atan2(east, north)) % 360
    return dict(azimuth=az, altitude=el + r / 3600, geometric=el, declination=decl, eot=eot,
                hour_angle=ha)


CASES = [
    ("Boulder, Colorado", "2026-06-21T17:30:00+00:00", 40.0150, -105.2705),
    ("Sydney", "2026-12-21T02:00:00+00:00", -33.8688, 151.2093),
    ("Tromso, low winter sun", "2026-01-15T11:00:00+00:00", 69.6492, 18.9553),
]

if __name__ == "__main__":
    for name, text, lat, lon in CASES:
        s = sun(datetime.datetime.fromisoformat(text), lat, lon)
        print(f"{name}: {text} lat {lat} lon {lon}")
        print("  " + ", ".join(f"{k} {v:.6f}" for k, v in s.items()))
