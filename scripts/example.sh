#!/usr/bin/env bash
# The bundled example, from a fresh Debian machine: installs the build dependencies, builds acd,
# decomposes South Africa (with Lesotho as a hole; examples/south-africa.geojson, Natural Earth
# via npm world-atlas, see examples/README.md) with tau = TAU degrees (default 0.2), rechecks the
# result independently (--verify) and says where the picture and the JSON report are.
#
# `scripts/example.sh 3d [PARTS]`: the 3D job instead: fetches the real meshes (scripts/fetch-data.sh:
# Debian's libcgal-demo, npm's bunny), decomposes CGAL's camel into at most PARTS (default 40)
# convex hulls as tight as the budget pipeline makes them (`acd 3d --budget`), verifies the parts,
# scores the hulls with `acd eval` and draws the input and the hulls side by side.
#
# usage: scripts/example.sh [TAU] [MEASURE]     (MEASURE: sl, sp, h1, h2; default sl)
#        scripts/example.sh 3d [PARTS]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target acd_cli
mkdir -p out
if [ "${1:-}" = "3d" ]; then
  PARTS=${2:-40}
  bash scripts/fetch-data.sh
  build/acd 3d data/meshes/camel.off --budget "$PARTS" --verify -o out/camel-hulls.obj --json out/camel.json
  build/acd eval data/meshes/camel.off out/camel-hulls.obj | tee out/camel-eval.txt
  python3 scripts/render_mesh_svg.py out/camel.svg data/meshes/camel.off:input out/camel-hulls.obj:"$PARTS hulls" \
    --azimuth 30 --elevation 20 --up y
  echo
  echo "hulls:   $(pwd)/out/camel-hulls.obj   (one 'o' group per convex hull)"
  echo "picture: $(pwd)/out/camel.svg   (open it in a web browser)"
  echo "report:  $(pwd)/out/camel.json, scores: $(pwd)/out/camel-eval.txt"
  exit 0
fi
TAU=${1:-0.2}
MEASURE=${2:-sl}
build/acd 2d examples/south-africa.geojson -t "$TAU" -m "$MEASURE" \
  --svg out/example.svg --json out/example.json -o out/example-components.geojson --verify
echo
echo "picture:    $(pwd)/out/example.svg   (open it in a web browser)"
echo "report:     $(pwd)/out/example.json"
echo "components: $(pwd)/out/example-components.geojson"
