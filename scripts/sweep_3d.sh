#!/usr/bin/env bash
# Robustness sweep: `acd 3d --verify` on every mesh of a directory (default data/meshes, from
# scripts/fetch-data.sh), in solid and surface mode, with a time limit per run. A run passes when
# it decomposes and verifies (exit 0) or refuses the input with a message (exit 2: not closable,
# not a 2-manifold, ...); it fails on a verification failure (3), an internal error (5), a crash
# (a signal) or the time limit. Prints a markdown table and the failures; exit 1 if any failed.
# Mode "budget" runs `acd 3d FILE --budget $BUDGET --verify` (the whole budget pipeline, solid)
# and scores its hulls with `acd eval` (coverage, concavity_max, iou in the note; an input that is
# not closed against its repair by `acd info --repair --fill-holes`, the solid acd 3d decomposed);
# such a run also fails when the hulls do not cover that closed solid (coverage below
# MIN_COVERAGE) or when `acd eval` fails or exceeds the time limit.
#
# usage: scripts/sweep_3d.sh [BUILD_DIR] [DIR] (env TAU=0.1 LIMIT=120 MODES="solid surface"
#        MAX_FACES=200000: larger meshes are listed as skipped; BUDGET=16 MIN_COVERAGE=0.999
#        for MODES="... budget"; NAMES=REGEX: only the meshes whose path matches)
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
DIR=${2:-data/meshes}
TAU=${TAU:-0.1}
LIMIT=${LIMIT:-120}
MODES=${MODES:-"solid surface"}
MAX_FACES=${MAX_FACES:-200000}
BUDGET=${BUDGET:-16}
MIN_COVERAGE=${MIN_COVERAGE:-0.999}
NAMES=${NAMES:-}
ACD=$B/acd
[ -x "$ACD" ] || { echo "sweep_3d: build first ($ACD missing)"; exit 1; }
[ -d "$DIR" ] || { echo "sweep_3d: no $DIR (run scripts/fetch-data.sh)"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fails=0; runs=0
echo "| mesh | faces | mode | exit | parts | seconds | note |"
echo "|---|---:|---|---:|---:|---:|---|"
while IFS= read -r f; do
  name=${f#"$DIR"/}
  if [ -n "$NAMES" ] && ! [[ $name =~ $NAMES ]]; then continue; fi
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
    if [ "$mode" = budget ]; then
      timeout -s KILL "$LIMIT" "$ACD" 3d "$f" --budget "$BUDGET" --verify --json "$T/r.json" -o "$T/h.obj" >"$T/out" 2>"$T/err"
    else
      timeout -s KILL "$LIMIT" "$ACD" 3d "$f" --mode "$mode" -t "$TAU" --verify --json "$T/r.json" >"$T/out" 2>"$T/err"
    fi
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
    if [ "$mode" = budget ] && [ "$rc" -eq 0 ]; then
      # the hulls must cover the input; coverage and concavity_max by acd eval. An input that is not
      # closed is scored against the solid acd 3d decomposed: the input repaired as it repairs it
      # (acd info --repair: welded, oriented, every hole closed), "(repaired)" in the note
      timeout -s KILL "$LIMIT" "$ACD" eval "$f" "$T/h.obj" --json >"$T/e.json" 2>"$T/eerr"
      erc=$?
      rep=""
      if [ "$erc" -eq 0 ] && ! python3 -c 'import json,sys; sys.exit(not json.load(open(sys.argv[1]))["mesh_closed"])' "$T/e.json" 2>/dev/null; then
        rep=" (repaired)"
        if "$ACD" info "$f" --no-self-intersections --repair "$T/rep.off" --fill-holes 1000000000 >/dev/null 2>"$T/eerr"; then
          timeout -s KILL "$LIMIT" "$ACD" eval "$T/rep.off" "$T/h.obj" --json >"$T/e.json" 2>"$T/eerr"
          erc=$?
        else
          erc=$?
        fi
        rm -f "$T/rep.off"
      fi
      ev=$(python3 -c '
import json, sys
e = json.load(open(sys.argv[1]))
closed = e.get("mesh_closed", False)
low = closed and e["coverage"] < float(sys.argv[2])
print("%d coverage %.4f%s%s, concavity_max %.4f, iou %.4f" % (low, e["coverage"], sys.argv[3], "" if closed else " (open)", e["concavity_max"], e["iou"]))
' "$T/e.json" "$MIN_COVERAGE" "$rep" 2>/dev/null)
      if [ "$erc" -ne 0 ] || [ -z "$ev" ]; then
        note="FAIL: acd eval exit $erc: $(tail -1 "$T/eerr" | cut -c1-90)"; fails=$((fails + 1))
      elif [ "${ev%% *}" = 1 ]; then
        note="FAIL: ${ev#* } (below $MIN_COVERAGE)"; fails=$((fails + 1))
      else
        note="${ev#* }"
      fi
    fi
    rm -f "$T/h.obj" "$T/e.json"
    printf '| %s | %s | %s | %s | %s | %.1f | %s |\n' "$name" "$faces" "$mode" "$rc" "$parts" "$secs" "${note//|//}"
  done
done < <(find "$DIR"/ -type f \( -iname '*.off' -o -iname '*.obj' -o -iname '*.ply' -o -iname '*.stl' -o -iname '*.off.gz' \) | LC_ALL=C sort)
echo
case " $MODES " in *" budget "*) bud=", budget $BUDGET";; *) bud="";; esac
echo "sweep_3d: $runs runs, $fails failed (tau $TAU$bud, limit ${LIMIT}s, $(date -u +%F), $(nproc) cores)"
[ "$fails" -eq 0 ]
