#!/usr/bin/env bash
# pcl_holefill quick start on Debian 12 (run as root, or with sudo available).
#   ./quickstart.sh demo   install, build, and run the built-in demo (writes demo/)
#   ./quickstart.sh test   install, build, install into a temporary prefix and move it (the
#                          install is relocatable), run the installed command, the downstream
#                          package check and the Python tests on the installed package, the
#                          test suite, fuzz the command's input path for 60 s, then run the
#                          whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer
#                          (SKIP_SANITIZERS=1 skips the last two, for a quick local run)
set -euo pipefail
cd "$(dirname "$0")"
mode=${1:-}
case "$mode" in demo|test) ;; *) echo "usage: $0 demo|test" >&2; exit 2 ;; esac

sudo_if_needed() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
packages="cmake g++ make ccache libpcl-dev libeigen3-dev libboost-dev libgtest-dev libpng-dev"
packages="$packages python3-dev pybind11-dev python3-numpy"
# libcgal-demo: fandisk.off, a CAD model of the corpus (its tests skip without it)
[ "$mode" = test ] && packages="$packages python3-pytest python3-open3d libcgal-demo"
[ "$mode" = test ] && [ -z "${SKIP_SANITIZERS:-}" ] && packages="$packages clang libclang-rt-14-dev"
missing=$(for p in $packages; do dpkg -s "$p" >/dev/null 2>&1 || echo "$p"; done)
if [ -n "$missing" ]; then
  echo "== installing:" $missing
  sudo_if_needed apt-get update -q
  sudo_if_needed env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing
fi

jobs=$(nproc)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
echo "== configuring and building (Release, $jobs jobs)"
# Debian's interpreter (another python3 may come first on PATH, without numpy).
python=/usr/bin/python3
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=$python "${launcher[@]}" >build.log 2>&1 \
  || { tail -40 build.log; exit 1; }
cmake --build build -j "$jobs" >>build.log 2>&1 || { grep -E "error|Error" build.log | head -40; exit 1; }

if [ "$mode" = demo ]; then
  ./build/pcl_holefill/tools/pcl_holefill -demo demo
  exit 0
fi

echo "== installed into a temporary prefix, then moved: the command, find_package, the Python module"
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install build --prefix "$prefix/install" >/dev/null
mv "$prefix/install" "$prefix/moved"
installed="$prefix/moved"
"$installed/bin/pcl_holefill" -h >/dev/null
"$installed/bin/pcl_holefill" -demo "$prefix/demo" >/dev/null
cmake -S test/downstream -B "$prefix/build" -DCMAKE_PREFIX_PATH="$installed" "${launcher[@]}" >"$prefix/log" 2>&1 \
  || { tail -40 "$prefix/log"; exit 1; }
cmake --build "$prefix/build" -j "$jobs" >>"$prefix/log" 2>&1 || { tail -40 "$prefix/log"; exit 1; }
"$prefix/build/downstream"
site=$(cd "$installed" && ls -d lib/python3*/dist-packages)
PYTHONPATH="$installed/$site" PCL_HOLEFILL_COMMAND="$installed/bin/pcl_holefill" \
  $python -m pytest -q -p no:cacheprovider test/python
PYTHONPATH="$installed/$site" $python doc/open3d_example.py --check

echo "== test suite"
ctest --test-dir build --output-on-failure -j "$jobs" -E '^python$'  # the Python tests ran on the install
[ -n "${SKIP_SANITIZERS:-}" ] && exit 0

echo "== fuzzing the command's input path for 60 s (libFuzzer, corpus in test/fuzz/corpus)"
cmake -S test/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ >build-fuzz.log 2>&1 || { tail -40 build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$jobs" >>build-fuzz.log 2>&1 || { grep -E "error|Error" build-fuzz.log | head -40; exit 1; }
corpus=$(mktemp -d)
cp test/fuzz/corpus/* "$corpus"/
(cd "$corpus" && "$OLDPWD/build-fuzz/fuzz_cloud_file" -max_total_time=60 -timeout=10 -rss_limit_mb=2048 \
   -print_final_stats=1 "$corpus" >fuzz.log 2>&1) || { tail -60 "$corpus/fuzz.log"; echo "fuzzing found a crash"; exit 1; }
grep -E "stat::number_of_executed_units" "$corpus/fuzz.log" || true
rm -rf "$corpus"

echo "== the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPCL_HOLEFILL_SANITIZE=ON \
  -DPCL_HOLEFILL_BUILD_BENCH=OFF -DPCL_HOLEFILL_PYTHON=OFF "${launcher[@]}" >build-sanitize.log 2>&1 || { tail -40 build-sanitize.log; exit 1; }
cmake --build build-sanitize -j "$jobs" >>build-sanitize.log 2>&1 || { grep -E "error|Error" build-sanitize.log | head -40; exit 1; }
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
