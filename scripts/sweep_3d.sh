#!/usr/bin/env bash
# Robustness sweep: `acd 3d --verify` on every mesh of a directory (default data/meshes, from
# scripts/fetch-data.sh), in solid and surface mode, with a time limit per run. A run passes when
# it decomposes and verifies (exit 0) or refuses the input with a message (exit 2: not closable,
# not a 2-manifold, ...); it fails on a verification failure (3), an internal error (5), a crash
# (a signal) or the time limit. Prints a markdown table and the failures; exit 1 if any failed.
#
# usage: scripts/sweep_3d.sh [BUILD_DIR] [DIR] (env TAU=0.1 LIMIT=120 MODES="solid surface"
#        MAX_FACES=200000: larger meshes are listed as skipped)
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
DIR=${2:-data/meshes}
TAU=${TAU:-0.1}
LIMIT=${LIMIT:-120}
MODES=${MODES:-"solid surface"}
MAX_FACES=${MAX_FACES:-200000}
ACD=$B/acd
[ -x "$ACD" ] || { echo "sweep_3d: build first ($ACD missing)"; exit 1; }
[ -d "$DIR" ] || { echo "sweep_3d: no $DIR (run scripts/fetch-data.sh)"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fails=0; runs=0
echo "| mesh | faces | mode | exit | parts | seconds | note |"
echo "|---|---:|---|---:|---:|---:|---|"
while IFS= read -r f; do
  name=${f#"$DIR"/}
  faces=$("$ACD" info "$f" 2>/dev/null | awk '$1 == "faces" {print $2; exit}')
  if [ -z "$faces" ]; then
    msg=$("$ACD" info "$f" 2>&1 >/dev/null | head -1 | cut -c1-90)
    echo "| $name | | read | | | | unreadable: ${msg//|//} |"
    continue
  fi
  if [ "$faces" -gt "$MAX_FACES" ]; then
    echo "| $name | $faces | | | | | skipped (more than $MAX_FACES faces) |"
    continue
  fi
  for mode in $MODES; do
    runs=$((runs + 1))
    start=$(date +%s.%N)
    timeout -s KILL "$LIMIT" "$ACD" 3d "$f" --mode "$mode" -t "$TAU" --verify --json "$T/r.json" >"$T/out" 2>"$T/err"
    rc=$?
    secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
    parts=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"]["parts"])' "$T/r.json" 2>/dev/null || echo "")
    rm -f "$T/r.json"
    note=""
    case $rc in
      0) ;;
      2) note="refused: $(grep -v '^acd 3d: 3d:' "$T/err" | tail -1 | cut -c1-110)";;
      137) note="TIME LIMIT ${LIMIT}s"; fails=$((fails + 1));;
      *) note="FAIL: $(tail -1 "$T/err" | cut -c1-110)"; fails=$((fails + 1));;
    esac
    printf '| %s | %s | %s | %s | %s | %.1f | %s |\n' "$name" "$faces" "$mode" "$rc" "$parts" "$secs" "${note//|//}"
  done
done < <(find "$DIR"/ -type f \( -iname '*.off' -o -iname '*.obj' -o -iname '*.ply' -o -iname '*.stl' -o -iname '*.off.gz' \) | LC_ALL=C sort)
echo
echo "sweep_3d: $runs runs, $fails failed (tau $TAU, limit ${LIMIT}s, $(date -u +%F), $(nproc) cores)"
[ "$fails" -eq 0 ]
