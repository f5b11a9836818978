#!/usr/bin/env bash
# The README's first command: installs what is missing, builds the CLI and runs the main
# job on the shipped default mesh (a genus-2 solid): its topology, then the whole chain
# mesh -> polycube layout -> multipatch B-spline volume, written to build/out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target polycube_iga > /dev/null
mesh=test/Polycube_IGA/data/eight.off
build/bin/polycube_iga info "$mesh"
mkdir -p build/out
# --allow-invalid: the baseline parameterization does not yet give certified-positive
# Jacobians on curved shapes (see the README); the report says where it stands.
build/bin/polycube_iga build "$mesh" -o build/out/eight.xml --vtu build/out/eight.vtu \
  --layout-vtu build/out/eight_layout.vtu --report build/out/eight_report.json --allow-invalid
echo "results in build/out/: eight.xml (G+Smo multipatch volume), eight.vtu (sampled volume with det J),"
echo "eight_layout.vtu (polycube layout on the surface), eight_report.json (counts, Jacobians, Hausdorff, seconds)"
