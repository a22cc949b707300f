#!/bin/sh
# Renders the 22 overlay presets (Figures 3 and 4) on one generated terrain
# into docs/presets/NAME.png (480x270), the images of docs/presets.md.
# Usage: scripts/render_presets.sh [BUILD_DIR]   (default: build)
set -e
build=${1:-build}
mkdir -p docs/presets
for p in fig3a fig3b fig3c fig3d fig3e fig3f fig3g fig3h fig3i fig3j fig3k fig3l fig3m fig3n \
         fig4a fig4b fig4c fig4d fig4e fig4f fig4g fig4h; do
  "$build/apps/sierra-render" --generate 257 --seed 4 --vertical-scale 150 --sea-level none --elevation 40 \
    --preset "$p" --size 480x270 --out "docs/presets/$p.png" --no-debug 2>&1 | grep overlays | sed "s/^/$p: /"
done
"$build/apps/sierra-render" --generate 257 --seed 4 --vertical-scale 150 --sea-level none --elevation 40 \
  --size 480x270 --out docs/presets/shaded.png --no-debug >/dev/null 2>&1
"$build/apps/sierra-render" --generate 257 --seed 4 --vertical-scale 150 --sea-level none --elevation 40 \
  --style shaded,contours --size 480x270 --out docs/presets/contours.png --no-debug >/dev/null 2>&1
