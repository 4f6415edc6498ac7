#!/usr/bin/env bash
# Fuzzes the scene loader and the sweep spec reader with libFuzzer under ASan
# and UBSan for SECONDS each, both at once on two or more cores, then the file
# readers (terrain CSV, PNG, MovingAI map) for SECONDS / 2 each, two at a time:
# about 2 x SECONDS of wall time on two cores (docs/running.md, "Fuzzing").
# Builds only the fuzz targets with clang in build-fuzz/. The seed corpus is
# the bundled files plus the regression corpus
# tests/hostile/corpus/{scenes,sweeps,maps} (terrain .csv and .png files
# included) but for its slow_* files, and the benchmark maps of tests/data,
# copied into a scratch corpus under
# build-fuzz/fuzz/ that keeps what the fuzzer finds; the source tree is never
# written. Exit 0: nothing found; 1: a crash, a sanitizer report, an uncaught
# exception other than the reader's refusal, a timeout or an out-of-memory, with the
# input that caused it printed; 2: bad usage.
#   tools/fuzz.sh [SECONDS]                  default 60
#   CAMPO_FUZZ_BUILD_DIR=dir tools/fuzz.sh   build and fuzz elsewhere
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${CAMPO_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: tools/fuzz.sh [SECONDS]  (a whole number of seconds > 0, got \"$seconds\")" >&2
  exit 2
fi
# Bundled scene names in sweep specs are found from the working directory.
cd "$root"

if ! command -v clang++ >/dev/null; then
  echo "campo fuzz: clang++ not found; tools/setup.sh --tests installs it (Debian packages clang, libclang-rt-dev)" >&2
  exit 1
fi
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build_dir" -DCAMPO_FUZZ=ON >/dev/null
fi
jobs="$(nproc 2>/dev/null || echo 2)"
targets=(--target fuzz_scene_loader fuzz_sweep_spec fuzz_heightfield_csv fuzz_png fuzz_movingai)
cmake --build "$build_dir" -j "$jobs" "${targets[@]}" -- --no-print-directory -s >/dev/null \
  || cmake --build "$build_dir" -j 1 "${targets[@]}"   # on failure, rebuild serially so the error is readable

# Leak detection stays on: the readers do not load Mesa (whose contexts keep
# allocations until exit, the reason the sanitizer suite turns it off), and
# a leak per input would be a bug. UBSan stops at the first report.
export ASAN_OPTIONS="detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
if [ -z "${ASAN_SYMBOLIZER_PATH:-}" ] && ! command -v llvm-symbolizer >/dev/null; then
  for s in /usr/lib/llvm-*/bin/llvm-symbolizer; do
    if [ -x "$s" ]; then export ASAN_SYMBOLIZER_PATH="$s"; fi
  done
fi

# Prepares fuzz_NAME's work folder: the scratch corpus with the seeds copied in
# (bundled-* and hostile-*, refreshed on every run), and a dictionary of the
# seeds' quoted words (keys, type names, aliases) and the words the given docs
# write as `code` (keys and names no seed uses), so mutations write real keys.
prepare() {
  local name="$1" bundled_glob="$2" hostile_dir="$3" hostile_glob="${HOSTILE_GLOB:-*}"
  shift 3
  local work="$build_dir/fuzz/$name"
  mkdir -p "$work/corpus" "$work/findings"
  local f
  for f in $bundled_glob; do
    if [ -f "$f" ]; then cp "$f" "$work/corpus/bundled-$(basename "$f")"; fi
  done
  if [ -d "$hostile_dir" ]; then
    # slow_*: valid inputs at the documented work limits (seconds each in an
    # instrumented build); tests/hostile replays them, the fuzzer would only stall on them.
    for f in "$hostile_dir"/$hostile_glob; do
      case "$(basename "$f")" in slow_*) continue ;; esac
      if [ -f "$f" ]; then cp "$f" "$work/corpus/hostile-$(basename "$f")"; fi
    done
  fi
  {
    printf '"%s"\n' '{' '}' '[' ']' ':' ',' 'true' 'false' 'null' '-1' '0' '1e308' '1e-308' '\"'
    {
      cat "$work"/corpus/bundled-* "$work"/corpus/hostile-* 2>/dev/null | grep -ao '"[A-Za-z0-9_./@-]\{1,40\}"' || true
      cat "$@" | grep -o '`[a-z][a-z0-9_]\{0,39\}`' | tr '`' '"' || true
    } | sort -u | sed 's/"/\\"/g; s/.*/"&"/'
  } >"$work/dict"
}

# Runs fuzz_NAME for SECONDS (default: all of them); its output goes to the work folder's fuzz.log.
run() {
  local name="$1" time="${2:-$seconds}" work="$build_dir/fuzz/$1"
  "$build_dir/fuzz_$name" "$work/corpus" -dict="$work/dict" -max_total_time="$time" -rss_limit_mb=2048 \
    -timeout=10 -print_final_stats=1 -artifact_prefix="$work/findings/" >"$work/fuzz.log" 2>&1
}

# One line per fuzzer; on a finding, the report and where the input is.
report() {
  local name="$1" status="$2" kind="$3" work="$build_dir/fuzz/$1"
  local log="$work/fuzz.log"
  if [ "$status" -eq 0 ]; then
    local runs units
    runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)"
    units="$(ls "$work/corpus" | wc -l)"
    echo "fuzz_$name: no finding in ${runs:-?} inputs (corpus: $units units in $work/corpus)"
    return 0
  fi
  echo "fuzz_$name: FOUND a failure (libFuzzer exit $status); report from $log:" >&2
  # Without the progress lines and the input's hex and base64 dumps (the file is named below).
  grep -v -e '^#[0-9]' -e '^0x' -e '^Base64:' "$log" | tail -n 60 >&2
  local input
  input="$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)"
  if [ -n "$input" ]; then
    echo "fuzz_$name: the input is $input; reproduce with: $build_dir/fuzz_$name $input" >&2
    echo "fuzz_$name: once understood, keep it as tests/hostile/corpus/$kind/WHAT_IT_DOES.${4:-json}" >&2
  fi
  return 1
}

prepare scene_loader "scenes/*.json" tests/hostile/corpus/scenes docs/scene-format.md docs/planners.md docs/vehicles.md
prepare sweep_spec "scenes/sweeps/*.json" tests/hostile/corpus/sweeps docs/sweeps.md
HOSTILE_GLOB="*.csv" prepare heightfield_csv "scenes/*.csv" tests/hostile/corpus/scenes docs/scene-format.md
HOSTILE_GLOB="*.png" prepare png "scenes/*.png" tests/hostile/corpus/scenes docs/scene-format.md
HOSTILE_GLOB="*.map" prepare movingai "tests/data/movingai/*.map*" tests/hostile/corpus/maps docs/grid.md

# The two readers of whole scenes and specs share SECONDS; the three file readers, smaller and
# faster per input, SECONDS / 2 each (at least 1 s), two at a time.
share=$(( seconds / 2 > 0 ? seconds / 2 : 1 ))
declare -A status
if [ "$jobs" -ge 2 ]; then
  for pair in "scene_loader:$seconds sweep_spec:$seconds" "heightfield_csv:$share png:$share" "movingai:$share"; do
    declare -A pids=()
    for job in $pair; do
      run "${job%%:*}" "${job##*:}" & pids[${job%%:*}]=$!
    done
    for name in "${!pids[@]}"; do
      status[$name]=0
      wait "${pids[$name]}" || status[$name]=$?
    done
    unset pids
  done
else
  for job in scene_loader:$seconds sweep_spec:$seconds heightfield_csv:$share png:$share movingai:$share; do
    status[${job%%:*}]=0
    run "${job%%:*}" "${job##*:}" || status[${job%%:*}]=$?
  done
fi

failed=0
report scene_loader "${status[scene_loader]}" scenes || failed=1
report sweep_spec "${status[sweep_spec]}" sweeps || failed=1
report heightfield_csv "${status[heightfield_csv]}" scenes csv || failed=1
report png "${status[png]}" scenes png || failed=1
report movingai "${status[movingai]}" maps map || failed=1
exit "$failed"
