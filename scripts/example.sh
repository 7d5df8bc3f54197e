#!/usr/bin/env bash
# The bundled example, from a fresh Debian machine: installs the build dependencies, builds acd,
# decomposes South Africa (with Lesotho as a hole; examples/south-africa.geojson, Natural Earth
# via npm world-atlas, see examples/README.md) with tau = TAU degrees (default 0.2), rechecks the
# result independently (--verify) and says where the picture and the JSON report are.
#
# usage: scripts/example.sh [TAU] [MEASURE]     (MEASURE: sl, sp, h1, h2; default sl)
set -euo pipefail
cd "$(dirname "$0")/.."
TAU=${1:-0.2}
MEASURE=${2:-sl}
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target acd_cli
mkdir -p out
build/acd 2d examples/south-africa.geojson -t "$TAU" -m "$MEASURE" \
  --svg out/example.svg --json out/example.json -o out/example-components.geojson --verify
echo
echo "picture:    $(pwd)/out/example.svg   (open it in a web browser)"
echo "report:     $(pwd)/out/example.json"
echo "components: $(pwd)/out/example-components.geojson"
