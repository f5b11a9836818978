#!/usr/bin/env bash
# The README's first command: installs what is missing, builds the CLI and runs the main
# job on the shipped default mesh (a genus-2 solid): its topology report.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target polycube_iga > /dev/null
build/bin/polycube_iga info test/Polycube_IGA/data/eight.off
echo "(JSON with the loops: build/bin/polycube_iga info test/Polycube_IGA/data/eight.off --json)"
