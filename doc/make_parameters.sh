#!/usr/bin/env bash
# Writes the parameter table of doc/parameters.md from
# pcl_holefill/include/pcl_holefill/hole_filling_parameters.h (run after
# ./quickstart.sh; the test ParameterTableIsCurrent fails until it is run
# after a change there).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build >/dev/null
cmake --build build --target parameter_table -j "$(nproc)" >/dev/null
./build/test/parameter_table --update doc/parameters.md
