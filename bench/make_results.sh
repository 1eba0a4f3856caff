#!/usr/bin/env bash
# Regenerates doc/results.md and doc/results/*.png: the paper's Table 2
# protocol against PCL's MLS and Poisson. Run after ./quickstart.sh (it needs
# the build); installs Debian's libcgal-demo for the fandisk model if missing.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! [ -f /usr/share/doc/libcgal-dev/data.tar.gz ]; then
  sudo_if_needed() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
  sudo_if_needed env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends libcgal-demo
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$work" data/meshes/fandisk.off
cmake --build build --target evaluate_table2 -j "$(nproc)" >/dev/null
./build/bench/evaluate_table2 doc "$work/data/meshes/fandisk.off" >/dev/null
echo "wrote doc/results.md and doc/results/*.png"
