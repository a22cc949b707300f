#!/bin/sh
# The Figure 2 style curvature images of docs/curvature.md and the README:
# for each method (two-normal, three-normal, three-normal with reinforcement
# distance 2, three-vertex, edge-angle) the largest of the 4 directional
# curvatures per vertex as intensity, clamped at 1 (sierra-gen curvature
# --png), on the valley DEM of the README's DEM images (403x344 samples), taken
# as a unitless grid (spacing 1, relief 20% of the extent) rather than as the
# metres its georeferencing gives: its curvature then reaches 1 at scale 1.
# Usage: scripts/curvature_images.sh [BUILD_DIR] [SCALE]   (defaults: build, 1)
set -e
build=${1:-build}
scale=${2:-1}
dem=/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz  # Debian: python3-matplotlib-data
out=docs/images
tmp=${TMPDIR:-/tmp}/sierra-curvature
mkdir -p "$out" "$tmp"
run() {  # NAME METHOD [OPTIONS]
  name=$1
  shift
  "$build/apps/sierra-gen" curvature --heightmap "$dem" --height-units none --spacing 1 \
    --method "$@" --scale "$scale" \
    --out "$tmp/$name.npy" --png "$out/curvature_$name.png"
}
run a_two_normal two-normal
run b_three_normal three-normal
run c_three_normal_d2 three-normal --distance 2
run d_three_vertex three-vertex
run e_edge_angle edge-angle
