#!/usr/bin/env bash
# Far-from-the-origin sweep (docs/acd3d.md "Local frame"): every top-level mesh of a directory
# (default data/meshes; OBJ/OFF/PLY/STL) read by the library and written twice as OFF (%.17g): as
# read ("near") and with every coordinate + RATIO x its bounding box's largest side, rounded ("far");
# both through `acd 3d --verify` (default) and `acd 3d --budget 16 --trim-coverage 0.0008 --verify`.
# A row per mesh and pipeline: the exit codes and part counts near and far; a difference in exit
# code is listed at the end (exit 1 if any). The mover is a small C program built against the
# library (cc, the build's libacd.a).
#
# usage: scripts/sweep_far.sh [BUILD_DIR] [DIR] (env RATIO=1e6 LIMIT=120 MAX_FACES=200000
#        NAMES=REGEX: only the meshes whose file name matches)
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
DIR=${2:-data/meshes}
RATIO=${RATIO:-1e6}
LIMIT=${LIMIT:-120}
MAX_FACES=${MAX_FACES:-200000}
NAMES=${NAMES:-}
ACD=$B/acd
[ -x "$ACD" ] && [ -f "$B/libacd.a" ] || { echo "sweep_far: build first ($ACD, $B/libacd.a)"; exit 1; }
[ -d "$DIR" ] || { echo "sweep_far: no $DIR (run scripts/fetch-data.sh)"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
cat > "$T/mv.c" <<'EOF_C'
/* mv IN OUT RATIO: IN read by acd_mesh_read, every coordinate + RATIO x (largest side of the box),
 * rounded, written as OFF with %.17g (RATIO 0: the mesh as read) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "acd/mesh.h"
int main(int argc, char **argv) {
    if (argc != 4) return 1;
    acd_mesh m;
    acd_error err;
    if (acd_mesh_read(argv[1], &m, &err) != ACD_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 2;
    }
    double e = 0;
    for (int k = 0; k < 3 && m.nvertices; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t v = 0; v < m.nvertices; v++) lo = fmin(lo, m.vertices[3 * v + k]), hi = fmax(hi, m.vertices[3 * v + k]);
        e = fmax(e, hi - lo);
    }
    double d = atof(argv[3]) * e;
    FILE *f = fopen(argv[2], "w");
    if (!f) return 3;
    fprintf(f, "OFF\n%zu %zu 0\n", m.nvertices, m.ntriangles);
    for (size_t v = 0; v < m.nvertices; v++)
        fprintf(f, "%.17g %.17g %.17g\n", m.vertices[3 * v] + d, m.vertices[3 * v + 1] + d, m.vertices[3 * v + 2] + d);
    for (size_t t = 0; t < m.ntriangles; t++)
        fprintf(f, "3 %u %u %u\n", m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]);
    fclose(f);
    acd_mesh_free(&m);
    return 0;
}
EOF_C
cc -O2 -std=c17 -Iinclude "$T/mv.c" "$B/libacd.a" -lqhull_r -lcjson -lz -lm -fopenmp -o "$T/mv" || { echo "sweep_far: cannot build the mover"; exit 1; }
# run FILE ARGS...: "exit parts seconds" of acd 3d FILE ARGS --verify
run() {
  local f=$1; shift
  local s; s=$(date +%s.%N)
  timeout -s KILL "$LIMIT" "$ACD" 3d "$f" "$@" --verify --json "$T/r.json" -o "$T/h.obj" > "$T/out" 2> "$T/err"
  local rc=$?
  local p; p=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"]["parts"])' "$T/r.json" 2>/dev/null || echo "-")
  rm -f "$T/r.json"
  echo "$rc $p $(awk -v a="$s" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')"
}
echo "| mesh | faces | pipeline | exit near | exit far | parts near | parts far | s near | s far | note |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---|"
diffs=0; n=0
for f in "$DIR"/*; do
  [ -f "$f" ] || continue
  case "${f,,}" in *.off|*.obj|*.ply|*.stl) ;; *) continue;; esac
  name=${f#"$DIR"/}
  if [ -n "$NAMES" ] && ! [[ $name =~ $NAMES ]]; then continue; fi
  if ! "$T/mv" "$f" "$T/near.off" 0 2> "$T/merr" || ! "$T/mv" "$f" "$T/far.off" "$RATIO" 2>> "$T/merr"; then
    echo "| $name | | | | | | | | | unreadable: $(head -1 "$T/merr" | cut -c1-80 | tr '|' '/') |"
    continue
  fi
  faces=$(awk 'NR == 2 { print $2; exit }' "$T/near.off")
  if [ "$faces" -gt "$MAX_FACES" ]; then
    echo "| $name | $faces | | | | | | | | skipped (more than $MAX_FACES faces) |"
    continue
  fi
  for pipe in default budget; do
    args=(); [ $pipe = budget ] && args=(--budget 16 --trim-coverage 0.0008)
    read -r rn pn sn <<< "$(run "$T/near.off" "${args[@]}")"
    nerr=$(grep -v '(.*s)$' "$T/err" | tail -1 | cut -c1-100 | tr '|' '/')
    read -r rf pf sf <<< "$(run "$T/far.off" "${args[@]}")"
    ferr=$(grep -v '(.*s)$' "$T/err" | tail -1 | cut -c1-100 | tr '|' '/')
    n=$((n + 1))
    note=""
    if [ "$rn" != "$rf" ]; then
      diffs=$((diffs + 1)); note="DIFFERENT EXIT: near: ${nerr:-ok}; far: ${ferr:-ok}"
    elif [ "$rf" != 0 ]; then
      note="both: $ferr"
    fi
    echo "| $name | $faces | $pipe | $rn | $rf | $pn | $pf | $sn | $sf | $note |"
  done
done
echo
echo "$n pipelines run, $diffs with a different exit code far ($RATIO x extent) than near"
[ "$diffs" = 0 ]
