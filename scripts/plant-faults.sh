#!/usr/bin/env bash
# Plants known faults in the code one at a time and checks that the tests meant
# to catch each one fail: the suite is shown to catch what it claims. For every
# fault it edits one line (sed on a line that occurs once), rebuilds the
# targets that line reaches, runs the named CTest tests, requires every one of
# them to fail, and restores the file. A fault that no named test catches, or
# a line that is no longer there, fails the script.
#
#   scripts/plant-faults.sh [FAULT...]     (default: every fault; list: -l)
#
# BUILD_DIR (default build/) must be a configured build of this tree (scripts/
# setup.sh makes one); it is rebuilt from the restored sources at the end. The
# files a fault edits must have no uncommitted changes (the script restores
# them with git checkout). docs/testing.md has the table of faults and tests.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"

# name|file|line (literal text, found on exactly one line)|its replacement|build targets|tests
faults=(
  "morph-sign-gpu|shaders/morph.glsl|return texel.g + w * (texel.r - texel.g);|return texel.g - w * (texel.r - texel.g);|sierra_gl_tests|Golden.SbtFrameMatchesReferenceAndFullGrid DisplayGolden.ColourByLevel"
  "morph-sign-cpu|engine/include/sierra/sbt/Morph.h|return base + w * (height - base);|return base - w * (height - base);|sierra_unit_tests|SbtMorph.WeightIsZeroAtActivationOneAtTheBudget SbtMorph.DrawnVerticesStayWithinTauAndMorphsEndAtTheBudget"
  "cull-skips-left-plane|engine/src/sbt/Refiner.cpp|rootMask = kView && view->cull ? kAllPlanes : 0;|rootMask = kView && view->cull ? (kAllPlanes & ~1u) : 0;|sierra_unit_tests sierra_sbt_scalar_tests|SbtCulledSubtrees.MatchBruteForceOnBothPathsForAnyThreadsAndChunkLevel SbtViewOrder.SameTrianglesInTheSameOrderAsTheReference scalar.SbtCulledSubtrees.MatchBruteForceOnBothPathsForAnyThreadsAndChunkLevel"
  "palette-swaps-zones-0-1|engine/src/zones/Palette.cpp|if (surfaces[k].colour == colour) return int(k);|if (surfaces[k].colour == colour) return int(k < 2 ? 1 - k : k);|sierra_unit_tests|ZonesIo.PaletteReadsFieldsAndResolvesTiles ZonesIo.ZoneMapRoundTripsThroughPng"
  "parity-fixed-leaf-level|engine/src/sbt/ExactWalk.h|                    append(q, l & 1);|                    append(q, (l + 1) & 1);|sierra_unit_tests|SbtFixed.MeshesMatchBruteForceAndConform SbtFixed.FullGridStripLengthIsExact"
  "parity-keyed-depth-2|engine/src/sbt/KeyedWalk.h|constexpr int parity = int(kOdd) ^ (depth & 1), childParity = parity ^ 1;|constexpr int parity = int(kOdd) ^ (depth & 1) ^ (depth == 2), childParity = parity ^ 1;|sierra_unit_tests sierra_sbt_scalar_tests|SbtView.FastPathEmitsTheBaselineStrip SbtViewOrder.SameTrianglesInTheSameOrderAsTheReference scalar.SbtView.FastPathEmitsTheBaselineStrip"
  "parallel-never-forks|engine/src/core/Parallel.cpp|        while ((unit = claim(nullptr)) >= 0) {|        for (woken = true; (unit = claim(nullptr)) >= 0;) {|sierra_unit_tests|CoreParallel.LongCallsShareTheWork"
  "frames-range-drops-last|apps/sierra-render/main.cpp|const int last = s.path.range ? s.path.range->last : frameCount - 1;|const int last = s.path.range ? s.path.range->last - 1 : frameCount - 1;|sierra-render|apps.render_scene"
)

# The sed expression that replaces literal text $1 with literal text $2.
sed_replace() {
  local old new
  old="$(printf '%s' "$1" | sed 's/[][\\.*^$/]/\\&/g')"
  new="$(printf '%s' "$2" | sed 's/[\\&/]/\\&/g')"
  printf 's/%s/%s/' "$old" "$new"
}

if [[ "${1:-}" == "-l" ]]; then
  for f in "${faults[@]}"; do IFS='|' read -r name file _ _ _ tests <<<"$f"; echo "$name: $file -> $tests"; done
  exit 0
fi
[[ -f "$build/CMakeCache.txt" ]] || { echo "plant-faults: no configured build in $build (run scripts/setup.sh)" >&2; exit 1; }

wanted=("$@")
planted=""
restore() {
  if [[ -n "$planted" ]]; then
    git checkout -- "$planted"
    planted=""
  fi
}
trap restore EXIT INT TERM

failures=0
touched=()
for f in "${faults[@]}"; do
  IFS='|' read -r name file line replacement targets tests <<<"$f"
  if ((${#wanted[@]})) && [[ ! " ${wanted[*]} " == *" $name "* ]]; then continue; fi
  if ! git diff --quiet -- "$file"; then
    echo "plant-faults: $file has uncommitted changes; commit or stash them first" >&2
    exit 1
  fi
  before="$(grep -cF -- "$line" "$file" || true)"
  if [[ "$before" -ne 1 ]]; then
    echo "plant-faults: $name: the line to change is not in $file exactly once (found $before)" >&2
    failures=$((failures + 1))
    continue
  fi
  planted="$file"
  sed -i "$(sed_replace "$line" "$replacement")" "$file"
  if git diff --quiet -- "$file"; then
    echo "plant-faults: $name: sed changed nothing in $file" >&2
    restore
    failures=$((failures + 1))
    continue
  fi
  echo "plant-faults: $name: planted in $file"
  git --no-pager diff --unified=0 -- "$file" | grep '^[-+][^-+]' || true
  touched+=("$targets")
  # shellcheck disable=SC2086  # targets is a list
  cmake --build "$build" -j "$jobs" --target $targets >"$build/plant-faults-$name.build.log" 2>&1 || {
    echo "plant-faults: $name: the build failed (log $build/plant-faults-$name.build.log)" >&2
    restore
    failures=$((failures + 1))
    continue
  }
  regex="^($(echo "$tests" | tr ' ' '\n' | sed 's/[.]/\\./g' | paste -sd'|'))\$"
  log="$build/plant-faults-$name.test.log"
  ctest --test-dir "$build" -R "$regex" --output-on-failure >"$log" 2>&1 || true
  caught=() missed=()
  for t in $tests; do
    # ctest lists each test that did not pass as "N - NAME (why)".
    if grep -Eq "^[[:space:]]*[0-9]+ - $(echo "$t" | sed 's/[.]/\\./g') \(" "$log"; then
      caught+=("$t")
    elif ! grep -Eq "Test +#[0-9]+: $(echo "$t" | sed 's/[.]/\\./g') " "$log"; then
      missed+=("$t (not run: no such test?)")
    else
      missed+=("$t")
    fi
  done
  restore
  if ((${#missed[@]})); then
    echo "plant-faults: $name: NOT caught by ${missed[*]} (log $log)" >&2
    failures=$((failures + 1))
  else
    echo "plant-faults: $name: caught by ${caught[*]}"
  fi
done

trap - EXIT INT TERM
restore
if ((${#touched[@]})); then
  echo "plant-faults: rebuilding the restored sources"
  # shellcheck disable=SC2046
  cmake --build "$build" -j "$jobs" --target $(printf '%s\n' "${touched[@]}" | tr ' ' '\n' | sort -u) >/dev/null
fi
if ((failures)); then
  echo "plant-faults: $failures fault(s) not caught" >&2
  exit 1
fi
echo "plant-faults: every fault caught"
