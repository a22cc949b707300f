#!/usr/bin/env bash
# Measures Sierra's headline figures and writes docs/performance.md.
#
# Builds the programs (Release, in BUILD_DIR, default build/), runs every command of
# scripts/perf_tables.py (`perf_tables.py runs`) one after another, each writing its
# JSON report to BUILD_DIR/perf/NAME.json (its console output to NAME.log beside it),
# records the machine (CPU model and core count; the GL renderer comes from the
# reports), and turns the reports into docs/performance.md. About 3 minutes on 2 cores.
#
#   scripts/measure.sh              measure and write docs/performance.md
#   scripts/measure.sh --tables     only rebuild docs/performance.md from BUILD_DIR/perf/
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
out="$build/perf"
cd "$root"

if [[ "${1:-}" != "--tables" ]]; then
  if [[ ! -f "$build/CMakeCache.txt" ]]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" \
        --target sierra-render sierra-bench sierra-microbench sierra-tin \
        $(grep -q '^SIERRA_WITH_PYTHON:BOOL=ON' "$build/CMakeCache.txt" && echo _sierra) >/dev/null
  export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
  rm -rf "$out"
  mkdir -p "$out"
  python3 - "$out/machine.json" <<'PY'
import json, os, sys
model = "unknown CPU"
with open("/proc/cpuinfo") as fh:
    for line in fh:
        if line.startswith("model name"):
            model = " ".join(line.split(":", 1)[1].split())
            break
with open(sys.argv[1], "w") as fh:
    json.dump({"cpu": model, "cores": os.cpu_count()}, fh)
PY
  while IFS=$'\t' read -r name optional command; do
    eval "words=($command)"
    # A program of the build, or a Python script of the repository (run by Debian's
    # python3; a script that runs the programs itself gets their folder as {apps}).
    if [[ "${words[0]}" == python3 ]]; then
      words[0]=/usr/bin/python3
    else
      words[0]="$build/apps/${words[0]}"
    fi
    for k in "${!words[@]}"; do
      words[k]="${words[k]//\{json\}/$out/$name.json}"
      words[k]="${words[k]//\{out\}/$out}"
      words[k]="${words[k]//\{apps\}/$build/apps}"
    done
    if [[ "$optional" == 1 && "${words[1]:-}" == python/* && ! -d "$build/python/sierra" ]]; then
      echo "measure: $name: no Python module in this build, skipped" >&2
      continue
    fi
    if [[ "$optional" == 1 && "${words[0]}" == */sierra-microbench ]]; then
      # A benchmark another build may not have: skip the run when its filter matches nothing.
      filter=""
      for w in "${words[@]}"; do [[ "$w" == --benchmark_filter=* ]] && filter="$w"; done
      if [[ -z "$("${words[0]}" --benchmark_list_tests "$filter" 2>/dev/null)" ]]; then
        echo "measure: $name: no such benchmark in this build, skipped" >&2
        continue
      fi
    fi
    echo "measure: $name" >&2
    start=$SECONDS
    if ! "${words[@]}" >"$out/$name.log" 2>&1; then
      echo "measure: $name failed; the end of $out/$name.log:" >&2
      tail -20 "$out/$name.log" >&2
      exit 1
    fi
    echo "measure: $name: $((SECONDS - start)) s" >&2
  done < <(python3 "$root/scripts/perf_tables.py" runs)
fi

python3 "$root/scripts/perf_tables.py" tables "$out" "$root/docs/performance.md"
echo "measure: wrote docs/performance.md from $out" >&2
