#!/usr/bin/env bash
# Renders docs/layers_jacksboro.png: matplotlib's Jacksboro DEM (Debian's
# python-matplotlib-data) as a GeoTIFF, draped with gdaldem's colour relief
# and hillshade, its 100 m contours from gdal_contour as a vector layer, a
# label at a longitude and latitude, and map furniture. Needs a built
# build/ (scripts/setup.sh), gdal-bin and python3-gdal.
#   scripts/layers_demo.sh [OUT.png]   (default docs/layers_jacksboro.png)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/docs/layers_jacksboro.png}")"
render="${BUILD_DIR:-$root/build}/apps/sierra-render"
dem=/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz
for tool in gdaldem gdal_contour; do
  command -v "$tool" >/dev/null || { echo "layers_demo: $tool is missing (apt-get install gdal-bin)" >&2; exit 1; }
done
[[ -x "$render" ]] || { echo "layers_demo: no $render (run scripts/setup.sh)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
/usr/bin/python3 - "$dem" <<'PY'
import sys
import numpy as np
from osgeo import gdal, osr
d = np.load(sys.argv[1])
z = d["elevation"].astype(np.float32)
ds = gdal.GetDriverByName("GTiff").Create("dem.tif", z.shape[1], z.shape[0], 1, gdal.GDT_Float32)
# Row 0 is the north edge (ymin holds the larger latitude in this file).
ds.SetGeoTransform((float(d["xmin"]), float(d["dx"]), 0.0, float(d["ymin"]), 0.0, -float(d["dy"])))
srs = osr.SpatialReference()
srs.ImportFromEPSG(4326)
ds.SetProjection(srs.ExportToWkt())
ds.GetRasterBand(1).WriteArray(z)
PY
printf '200 40 90 40\n400 110 150 70\n600 180 170 100\n800 200 160 120\n1000 240 240 240\n' >ramp.txt
# The same colours as a GMT table, so the legend shows the drape's ramp.
awk 'NR > 1 { print z, c, $1, $2 "/" $3 "/" $4 } { z = $1; c = $2 "/" $3 "/" $4 }' ramp.txt >ramp.cpt
gdaldem color-relief dem.tif ramp.txt colour.tif -q
gdaldem hillshade dem.tif shade.tif -s 111120 -q
gdal_contour -a elev -i 100 dem.tif contours.geojson -q
"$render" --heightmap dem.tif --vertical-scale 3 --azimuth 200 --elevation 35 \
  --drape colour.tif --drape shade.tif:0.6:multiply \
  --vector 'contours.geojson:colour=#5a3a1a,width=1,fill=0' \
  --label 'Jellico@84.127W,36.588N' --scale-bar --north-arrow --legend \
  --title 'Jacksboro fault, Tennessee' --cpt ramp.cpt --size 960x540 --no-debug --out "$out"
echo "layers_demo: wrote $out"
