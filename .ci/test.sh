#!/usr/bin/env bash
# Builds everything (library checks, CLI, examples, tests, benchmark) and runs the whole
# test suite with CTest, one Catch2 case per CTest entry.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j"$(nproc)"
