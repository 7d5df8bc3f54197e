#!/usr/bin/env bash
# acd 3d --budget speed and identity: the six target meshes at the budget settings of docs/acd3d.md
# ("Excess-driven budget": -t 10 --budget N --merge-tau M --cut-choice volume --merge-order volume
# --merge-parts N --merge-refine 40), wall and user CPU seconds per mesh and thread count, for this
# build and, when given, a baseline binary in the same run; and whether the hull OBJ and the JSON (its
# "seconds" fields stripped) are byte-identical to the baseline's and across thread counts.
# usage: bench/bench_3d_budget.sh [BUILD_DIR]   (needs data/meshes: bash scripts/fetch-data.sh)
# Environment: BASE_ACD a baseline acd binary (e.g. main built in a temporary directory), THREADS
# (default "1 2"), REPS runs per (mesh, threads, binary) (default 1; the smallest times are reported:
# the machine may be shared), MESHES (a subset of the mesh files, e.g. "armadillo.off bunny00.off").
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
ACD=$B/acd
M=data/meshes
[ -x "$ACD" ] || { echo "bench_3d_budget: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_3d_budget: no $M; run scripts/fetch-data.sh"; exit 77; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
REPS=${REPS:-1}
THREADS=${THREADS:-"1 2"}
BASE=${BASE_ACD:-}
# mesh:merge tau:budget (docs/acd3d.md, the six meshes' budget table)
SETS="camel.off:0.04254:40 knot1.off:0.05418:40 fandisk.off:0.04476:40 armadillo.off:0.04903:43 bunny00.off:0.0487:40 bunny.obj:0.04872:40"
if [ -n "${MESHES:-}" ]; then
  keep=""
  for s in $SETS; do for mf in $MESHES; do [ "${s%%:*}" = "$mf" ] && keep="$keep $s"; done; done
  SETS=$keep
fi
run() { # BIN MESH MTAU N THREADS OUT -> "wall user"
  local cmd=("$1" 3d "$M/$2" -t 10 --budget "$4" --merge-tau "$3" --cut-choice volume --merge-order volume
    --merge-parts "$4" --merge-refine 40 --threads "$5" -o "$6.obj" --json "$6.json")
  /usr/bin/time -o "$T/time" -f "%e %U" "${cmd[@]}" > /dev/null 2>&1 || { echo "fail fail"; return; }
  cat "$T/time"
  sed -E -i 's/"seconds":[[:space:]]*[0-9.eE+-]+//g' "$6.json"
}
min() { awk '{ for (k = 1; k <= NF; k++) if ($k != "fail" && (m[k] == "" || $k + 0 < m[k] + 0)) m[k] = $k; if (NF > n) n = NF }
  END { s = ""; for (k = 1; k <= n; k++) s = s (k > 1 ? " " : "") (m[k] == "" ? "fail" : m[k]); print s }'; }
same() { cmp -s "$1.obj" "$2.obj" && cmp -s "$1.json" "$2.json" && echo same || echo DIFFERENT; }
echo "acd 3d --budget, $(date -u '+%Y-%m-%d %H:%M UTC'); $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); times: wall s, user s; min of $REPS"
ok=1
for s in $SETS; do
  IFS=: read -r mesh mt n <<< "$s"
  first=""
  for th in $THREADS; do
    new=$(for r in $(seq "$REPS"); do run "$ACD" "$mesh" "$mt" "$n" "$th" "$T/new$th"; done | min)
    line="$mesh threads $th: new $new"
    if [ -n "$first" ]; then
      x=$(same "$T/new$th" "$T/new$first"); line="$line, across threads $x"; [ "$x" = same ] || ok=0
    fi
    [ -z "$first" ] && first=$th
    if [ -n "$BASE" ]; then
      base=$(for r in $(seq "$REPS"); do run "$BASE" "$mesh" "$mt" "$n" "$th" "$T/base$th"; done | min)
      x=$(same "$T/new$th" "$T/base$th"); line="$line; base $base, output $x"; [ "$x" = same ] || ok=0
    fi
    echo "$line"
  done
done
[ "$ok" = 1 ] && echo "all outputs identical" || { echo "OUTPUTS DIFFER"; exit 1; }
