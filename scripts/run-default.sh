#!/usr/bin/env bash
# Sets everything up, then renders the built-in default scene (a generated
# 1025x1025 fractal terrain): out/frame.png and the debug snapshot out/debug.png.
# Extra arguments go to sierra-render (see --help).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
exec "${BUILD_DIR:-$root/build}/apps/sierra-render" "$@"
