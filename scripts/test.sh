#!/usr/bin/env bash
# Sets everything up, then runs the whole test suite through CTest: unit tests
# (no GL), GL tests on an EGL context (llvmpipe here), shader validation and the
# apps end to end. Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build_dir="${BUILD_DIR:-$root/build}"
exec ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
