#!/usr/bin/env bash
# campo installed to a temporary prefix, the example planner plugin built
# against the installed package, and the installed program running it.
# Usage: installed_plugin_test.sh CMAKE BUILD_DIR EXAMPLE_DIR BUILD_TYPE SANITIZE(0|1)
set -euo pipefail
cmake_bin=$1 build_dir=$2 example_dir=$3 build_type=${4:-Release} sanitize=${5:-0}

work=$(mktemp -d "${TMPDIR:-/tmp}/campo_installed_plugin.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }

"$cmake_bin" --install "$build_dir" --prefix "$prefix" >/dev/null

# The layout the install promises, and nothing of the tests or benchmarks.
for f in bin/campo lib/libcampo.so include/campo/planner.hpp include/campo/plugin.hpp include/campo/version.hpp \
         share/campo/scenes/two_barriers.json share/campo/scenes/sweeps/resolution_000.json \
         lib/cmake/campo/campoConfig.cmake lib/cmake/campo/campoConfigVersion.cmake lib/cmake/campo/campoTargets.cmake; do
  [ -e "$prefix/$f" ] || fail "$f is not installed"
done
unexpected=$(find "$prefix" -name 'test_*' -o -name '*gtest*' -o -name '*bench*' -o -name '*.hpp.in')
[ -z "$unexpected" ] || fail "installed what it should not: $unexpected"
# The exported interface names no object library of the build tree and none of the private dependencies.
leaks=$(grep -hEio 'campo_(core|scene|physics|sensors|vehicles|grid|planners|run|render|sweep|reproduce)\b|bullet|osmesa|opencv|embree' \
  "$prefix"/lib/cmake/campo/campoTargets*.cmake | sort -u | tr "\n" " " || true)
[ -z "$leaks" ] || fail "the exported targets name build-tree or private dependencies: $leaks"

# The example, out of tree: find_package(campo CONFIG REQUIRED) from the prefix alone.
flags=()
if [ "$sanitize" = 1 ]; then
  # A sanitized campo loads plugins built with the same sanitizers (CMakeLists.txt, CAMPO_SANITIZE).
  flags=(-DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
         -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=address,undefined")
fi
"$cmake_bin" -S "$example_dir" -B "$work/example" -DCMAKE_BUILD_TYPE="$build_type" -DCMAKE_PREFIX_PATH="$prefix" \
  "${flags[@]}" >"$work/configure.log" 2>&1 || { cat "$work/configure.log" >&2; fail "configuring the example"; }
"$cmake_bin" --build "$work/example" -j2 >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; fail "building the example"; }
plugin=$work/example/liblidar_steer.so
[ -f "$plugin" ] || fail "the example built no $plugin"

# From a folder without scenes/: the installed program finds its bundled files under the prefix.
cd "$work"
campo=$prefix/bin/campo
version=$("$campo" --version)
grep -q "^campo $(sed -n 's/^#define CAMPO_VERSION_STRING "\(.*\)"$/\1/p' "$prefix/include/campo/version.hpp") " \
  <<<"$version" || fail "campo --version ($version) is not the installed headers' version"

list=$("$campo" run --list-planners --plugin "$plugin")
grep -qx "lidar_steer ($plugin): .*" <<<"$list" || fail "--list-planners does not list lidar_steer from $plugin: $list"

# Fewer LIDAR beams than the scene's 256 x 256 keep the run short; the planner still sees both barriers.
"$campo" run two_barriers --plugin "$plugin" --planner lidar_steer --no-figures \
  --set /objects/drone/sensors/scanner/resolution=[64,64] --out run >run.log 2>&1 || { cat run.log >&2; fail "campo run"; }
outcome=$(jq -r .metrics.outcome run/run.json)
[ "$outcome" = reached ] || fail "lidar_steer did not reach the goal of two_barriers: $outcome ($(jq -c .metrics run/run.json))"
[ "$(jq -r .provenance.scene.file run/run.json)" = "$prefix/share/campo/scenes/two_barriers.json" ] ||
  fail "the scene was not the installed one: $(jq -r .provenance.scene.file run/run.json)"
[ "$(jq -r .provenance.planner.source run/run.json)" = "$plugin" ] || fail "provenance.planner.source is not $plugin"
# The plugin's own metric, declared by its record and measured on its decisions: the largest
# |steer_deg| it recorded in events.jsonl (0 if it never steered), in run.json's metrics.
steer_max=$(jq -r .metrics.steer_deg_max run/run.json)
steer_events=$(jq -s '[.[].decisions.steer_deg | select(. != null) | if . < 0 then -. else . end] | max // 0' run/events.jsonl)
[ "$steer_max" != null ] || fail "run.json's metrics have no steer_deg_max: $(jq -c .metrics run/run.json)"
jq -en --argjson a "$steer_max" --argjson b "$steer_events" '$a == $b' >/dev/null ||
  fail "steer_deg_max is $steer_max, the events' largest |steer_deg| is $steer_events"
[ "$(jq -s '[.[].decisions.steer_deg | select(. != null)] | length' run/events.jsonl)" -gt 0 ] ||
  fail "lidar_steer recorded no steer_deg on two_barriers: the metric would be checked against nothing"
[ "$(jq -r .provenance.planner.sha256 run/run.json)" = "$(sha256sum "$plugin" | cut -d' ' -f1)" ] ||
  fail "provenance.planner.sha256 is not the plugin's"

# A sweep whose spec names the plugin (relative to the spec): two seeds, each run in its own process.
mkdir sweep
cat >sweep/spec.json <<'SPEC'
{
  "campo_sweep": 1,
  "name": "plugin_sweep",
  "plugins": ["../example/liblidar_steer.so"],
  "scenes": ["two_barriers"],
  "planners": ["lidar_steer"],
  "set": { "/objects/drone/sensors/scanner/resolution": [64, 64] },
  "seeds": { "first": 1, "count": 2 }
}
SPEC
"$campo" sweep sweep/spec.json --out sweep/out --jobs 2 >sweep.log 2>&1 || { cat sweep.log >&2; fail "campo sweep"; }
[ "$(jq -s 'map(select(.status == "completed" and .metrics.outcome == "reached")) | length' sweep/out/results.jsonl)" = 2 ] ||
  fail "the sweep's runs did not all reach the goal: $(cat sweep/out/results.jsonl)"
[ "$(jq -r '.plugins[0].path' sweep/out/sweep.json)" = "$plugin" ] || fail "sweep.json does not name the plugin"

# A bundled sweep spec by name, from the prefix.
"$campo" sweep resolution_000 --list >list.log 2>&1 || { cat list.log >&2; fail "campo sweep resolution_000 --list"; }
echo "installed campo $version ran plugin $plugin: reached; sweep of 2 runs reached"
