#!/usr/bin/env bash
# Installs the Debian packages campo needs when any is missing, then builds it in Release
# under build/. Idempotent and silent when there is nothing to do; safe to run on every use.
#   tools/setup.sh                 what building and running campo needs; builds the library,
#                                  `campo` and the Python module
#   tools/setup.sh --tests         also what only the tests need (GoogleTest, Google Benchmark,
#                                  Chromium, Slurm, clang/LLVM, ...); builds everything:
#                                  the tests, the benchmarks and the test plugins too
#   CAMPO_BUILD_DIR=dir tools/setup.sh   build elsewhere
#   CAMPO_BUILD_TYPE=Debug tools/setup.sh
#   CAMPO_PEERS=1 tools/setup.sh   also the peers of bench/peers (MuJoCo, OMPL, Boost
#                                  Graph), whose benchmarks are built when they are present
set -euo pipefail

tests=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    -h | --help) sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/setup.sh: unknown argument '$arg' (expected --tests or nothing)" >&2; exit 2 ;;
  esac
done

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${CAMPO_BUILD_DIR:-$root/build}"
build_type="${CAMPO_BUILD_TYPE:-Release}"

# What building and running campo needs.
packages=(
  build-essential cmake pkg-config
  libbullet-dev libeigen3-dev libopencv-dev libosmesa6-dev libcli11-dev
  nlohmann-json3-dev libembree-dev
  libmuparser-dev libssl-dev liboctomap-dev libnanoflann-dev libpng-dev
  # Mesh obstacles (OBJ, STL, PLY, glTF) through assimp and DEM heightfields (GeoTIFF) through GDAL,
  # both loaded only when a scene uses them.
  libassimp-dev libgdal-dev
  # Figures (render/, sweep/chart): cairo draws PNG, PDF and SVG from the same calls, with
  # DejaVu Sans as the figures' font.
  libcairo2-dev fonts-dejavu-core
  # The Python module (python/): pybind11 against Debian's /usr/bin/python3 and its
  # numpy and pandas.
  pybind11-dev python3-dev python3-numpy python3-pandas
  # campo render --kind video encodes with the ffmpeg program.
  ffmpeg
  # campo bench --instructions counts instructions under callgrind (its header is valgrind's).
  valgrind
)
# What only the tests need (tools/setup.sh --tests).
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev
  # The tests' GeoTIFFs (gdal_translate); the figures' PDF and SVG read back with poppler's
  # pdftotext/pdftoppm and librsvg's rsvg-convert.
  gdal-bin poppler-utils librsvg2-bin
  # `pip install .` into a venv (pyproject.toml, setup.py; tests/python/test_pip_install.py);
  # matplotlib for the example analysis script.
  python3-venv python3-setuptools python3-wheel python3-matplotlib
  slurm-wlm munge jq # tests/slurm: a local single-node Slurm cluster (tools/slurm/)
  chromium # the replay's tests open the page in headless Chromium
  # tools/fuzz.sh: clang, libFuzzer's runtime (libclang-rt-dev, only a Recommends of clang's
  # packages) and llvm-symbolizer (llvm) for sanitizer reports with file and line.
  clang libclang-rt-dev llvm
)
((tests)) && packages+=("${test_packages[@]}")
# bench/peers: the tools campo is measured against side by side; only those benchmarks use
# them, so they are installed on request (docs/PERFORMANCE.md, "Peers").
if [ "${CAMPO_PEERS:-0}" = 1 ]; then
  packages+=(libmujoco-dev libompl-dev libboost-dev)
fi

# The replay viewer's three.js comes from the npm registry (web/replay/package-lock.json).
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "campo setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq >/dev/null
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# three.js for the replay viewer, as pinned by web/replay/package-lock.json; embedded in campo
# when it is built (CMakeLists.txt), so a fresh install reconfigures.
replay="$root/web/replay"
if [ ! -f "$replay/node_modules/.package-lock.json" ] ||
   [ "$replay/package-lock.json" -nt "$replay/node_modules/.package-lock.json" ]; then
  (cd "$replay" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  [ -f "$build_dir/CMakeCache.txt" ] && cmake -S "$root" -B "$build_dir" >/dev/null
fi

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
fi
# A configured build that lacked GoogleTest finds it once --tests has installed it.
if ((tests)) && ! grep -q '^GTest_DIR:PATH=/' "$build_dir/CMakeCache.txt"; then
  cmake -S "$root" -B "$build_dir" >/dev/null
fi
# Without --tests, only what running campo needs: the library, the program, the Python module
# and the library that embeds Python in campo (python: planners).
targets=()
if ((!tests)); then
  targets=(--target campo)
  # (no Python module in a sanitized build directory)
  # (grep -q on a pipe would stop cmake early, which pipefail counts as a failure)
  build_targets="$(cmake --build "$build_dir" --target help 2>/dev/null)"
  grep -qx '[.]\{3\} campo_python' <<<"$build_targets" && targets+=(campo_python campo_python_embed)
fi
jobs="$(nproc 2>/dev/null || echo 2)"
cmake --build "$build_dir" -j "$jobs" "${targets[@]}" -- --no-print-directory -s >/dev/null \
  || cmake --build "$build_dir" -j 1 "${targets[@]}"   # on failure, rebuild serially so the error is readable
