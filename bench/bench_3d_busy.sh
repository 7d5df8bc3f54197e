#!/usr/bin/env bash
# acd 3d on a busy machine: OpenMP's idle threads spinning (libgomp's default, GOMP_SPINCOUNT=300000)
# against waiting passively (the CLI's default since 2026-11-26: cli/main.c, docs/cli.md "Threads and
# a busy machine"), with 0, 1 and 2 other processes keeping the cores busy (busy loops started here).
# Per mesh, load and policy: wall and user CPU seconds of `acd 3d MESH --budget N --trim-coverage
# 0.0008` on 2 threads (the best of REPS runs), and the ratio spinning / passive in the same run.
# The hull OBJ must be the same under both policies (checked).
# usage: bench/bench_3d_busy.sh [BUILD_DIR]   (needs data/meshes: bash scripts/fetch-data.sh)
# Environment: REPS (default 2), MESHES (default "fandisk.off knot1.off armadillo.off"), LOADS
# (default "0 1 2").
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
ACD=$B/acd
M=data/meshes
[ -x "$ACD" ] || { echo "bench_3d_busy: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_3d_busy: no $M; run scripts/fetch-data.sh"; exit 77; }
T=$(mktemp -d)
BUSY=()
stop_busy() { for p in "${BUSY[@]}"; do kill "$p" 2>/dev/null; done; BUSY=(); }
trap 'stop_busy; rm -rf "$T"' EXIT
REPS=${REPS:-2}
MESHES=${MESHES:-"fandisk.off knot1.off armadillo.off"}
LOADS=${LOADS:-"0 1 2"}
parts() { case $1 in armadillo.off) echo 43 ;; *) echo 40 ;; esac; }
run() { # POLICY MESH OUT -> "wall user" (best wall of REPS)
  local best="" env
  if [ "$1" = spin ]; then env=(env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=300000); else env=(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT); fi
  for _ in $(seq "$REPS"); do
    "${env[@]}" /usr/bin/time -o "$T/t" -f "%e %U" "$ACD" 3d "$M/$2" --budget "$(parts "$2")" --trim-coverage 0.0008 \
      --threads 2 -o "$3" > /dev/null 2>&1 || { echo "fail fail"; return; }
    local w; w=$(cut -d' ' -f1 "$T/t")
    if [ -z "$best" ] || awk -v a="$w" -v b="${best%% *}" 'BEGIN{exit !(a < b)}'; then best=$(cat "$T/t"); fi
  done
  echo "$best"
}
echo "# bench_3d_busy: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1 /proc/loadavg) at the start"
echo "| mesh | other busy processes | spinning: wall | user | passive: wall | user | wall spinning / passive | same hulls |"
echo "|---|---|---|---|---|---|---|---|"
for load in $LOADS; do
  stop_busy
  for _ in $(seq "$load"); do (while :; do :; done) & BUSY+=($!); done
  for mf in $MESHES; do
    [ -f "$M/$mf" ] || continue
    read -r sw su <<< "$(run spin "$mf" "$T/s.obj")"
    read -r pw pu <<< "$(run passive "$mf" "$T/p.obj")"
    same=no; cmp -s "$T/s.obj" "$T/p.obj" && same=yes
    ratio=$(awk -v a="$sw" -v b="$pw" 'BEGIN{ if (b > 0) printf "%.2f", a / b; else print "-" }')
    echo "| $mf | $load | $sw | $su | $pw | $pu | $ratio | $same |"
  done
done
