#!/usr/bin/env bash
# acd 3d speed: wall and CPU seconds per mesh with 1 and 2 threads, at the settings of the issue-target
# table (bench/bench_3d.sh), for this build and, when given, a baseline binary in the same run; and
# whether the hull OBJ files are byte-identical across thread counts and binaries.
# usage: bench/bench_3d_speed.sh [BUILD_DIR]   (needs data/meshes: bash scripts/fetch-data.sh)
# Environment: BASE_REF a git revision to build as the baseline (its acd_cli, in a temporary directory:
# a few minutes on 2 cores), or BASE_ACD a baseline acd binary; REPS runs per (mesh, threads, binary)
# (default 3; the smallest wall time is reported: the machine may be shared), THREADS (default "1 2 2p";
# a trailing p runs with OMP_WAIT_POLICY=passive: waiting threads sleep instead of spinning),
# MESHES (default all six), OUT a file to copy the table to.
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
ACD=$B/acd
M=data/meshes
[ -x "$ACD" ] || { echo "bench_3d_speed: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_3d_speed: no $M; run scripts/fetch-data.sh"; exit 77; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
REPS=${REPS:-3}
THREADS=${THREADS:-"1 2 2p"}
BASE=${BASE_ACD:-}
if [ -z "$BASE" ] && [ -n "${BASE_REF:-}" ]; then
  mkdir -p "$T/base"
  git archive "$BASE_REF" | tar -x -C "$T/base" || { echo "bench_3d_speed: cannot export $BASE_REF"; exit 1; }
  (cmake -S "$T/base" -B "$T/base/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$T/base.log" 2>&1 &&
    cmake --build "$T/base/build" -j2 --target acd_cli >> "$T/base.log" 2>&1) || { echo "bench_3d_speed: baseline build failed"; tail "$T/base.log"; exit 1; }
  BASE=$T/base/build/acd
fi
# mesh, tau, merge tau: the target table's settings (docs/results/3d-target.md)
SETS=${MESHES:-"camel.off:0.03:0.04 knot1.off:0.045:0.06 fandisk.off:0.03:0.04 armadillo.off:0.045:0.05 bunny00.off:0.045:0.045 bunny.obj:0.045:0.05"}
run() { # BIN FILE TAU MTAU THREADS[p] OBJ -> "wall cpu"
  local pol=${OMP_WAIT_POLICY:-}
  case $5 in *p) pol=passive;; esac
  env ${pol:+OMP_WAIT_POLICY=$pol} /usr/bin/time -o "$T/time" -f "%e %U %S" timeout 900 "$1" 3d "$2" -t "$3" --merge-tau "$4" \
    --threads "${5%p}" -o "$6" > /dev/null 2>&1 || { echo "fail fail"; return; }
  awk '{printf "%s %.2f\n", $1, $2 + $3}' "$T/time"
}
min() { awk 'BEGIN { m = "" } { if ($1 != "fail" && (m == "" || $1 + 0 < m + 0)) { m = $1; c = $2 } } END { print (m == "" ? "fail fail" : m " " c) }'; }
{
echo "acd 3d speed, $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')."
echo "Load average at start $(cut -d' ' -f1 /proc/loadavg). wall: the smallest of $REPS runs (seconds, process"
echo "elapsed, reading the mesh included); cpu: user + system seconds of that run. Runs alternate between"
echo "the two binaries, so the two figures of a row saw about the same load."
[ -n "$BASE" ] && echo "Baseline: ${BASE_REF:-$BASE}; ratio = baseline wall / this build's wall."
echo
echo "| model | threads | wall | cpu | base wall | base cpu | ratio | load (end) | hull OBJ as with $(echo $THREADS | awk '{print $1}') thread(s) | hull OBJ as the baseline's |"
echo "|---|---|---|---|---|---|---|---|---|---|"
} > "$T/out.md"
cat "$T/out.md"
for s in $SETS; do
  IFS=: read -r mf tau mt <<< "$s"
  f=$M/$mf
  [ -f "$f" ] || continue
  m=${mf%.*}
  for th in $THREADS; do
    : > "$T/new"; : > "$T/basetimes"
    for r in $(seq "$REPS"); do
      run "$ACD" "$f" "$tau" "$mt" "$th" "$T/$m.$th.obj" >> "$T/new"
      [ -n "$BASE" ] && run "$BASE" "$f" "$tau" "$mt" "$th" "$T/$m.$th.base.obj" >> "$T/basetimes"
    done
    read -r w c <<< "$(min < "$T/new")"
    bw="" bc="" ratio="" sameb=""
    if [ -n "$BASE" ]; then
      read -r bw bc <<< "$(min < "$T/basetimes")"
      ratio=$(awk -v a="$bw" -v b="$w" 'BEGIN { if (a + 0 > 0 && b + 0 > 0) printf "%.2f", a / b }')
      sameb=yes
      cmp -s "$T/$m.$th.obj" "$T/$m.$th.base.obj" || sameb=no
    fi
    first=$(echo $THREADS | awk '{print $1}')
    samet=yes
    cmp -s "$T/$m.$th.obj" "$T/$m.$first.obj" || samet=no
    echo "| $m | $th | $w | $c | $bw | $bc | $ratio | $(cut -d' ' -f1 /proc/loadavg) | $samet | $sameb |" | tee -a "$T/out.md"
  done
done
[ -n "${OUT:-}" ] && cp "$T/out.md" "$OUT"
exit 0
