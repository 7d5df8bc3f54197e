#!/usr/bin/env bash
# acd 3d speed: wall and CPU seconds per mesh with 1 and 2 threads, at the settings of the issue-target
# table (bench/bench_3d.sh), for this build and, when given, a baseline binary in the same run; and
# whether the hull OBJ files are byte-identical across thread counts and binaries.
# usage: bench/bench_3d_speed.sh [BUILD_DIR]   (needs data/meshes: bash scripts/fetch-data.sh)
# Environment: BASE_REF a git revision to build as the baseline (its acd_cli, in a temporary directory:
# a few minutes on 2 cores), or BASE_ACD a baseline acd binary; REPS runs per (mesh, threads, binary)
# (default 3; the smallest wall and cpu times are reported: the machine may be shared), THREADS (default "1 2 2p";
# a trailing p runs with OMP_WAIT_POLICY=passive: waiting threads sleep instead of spinning),
# SETS (mesh:tau:merge tau:d|t, default: the target table's default and tight settings of the six meshes),
# MESHES (mesh files, e.g. "armadillo.off bunny00.off": only their sets), OUT a file to copy the table to.
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
# mesh, tau, merge tau, d|t: the target table's settings (docs/results/3d-target.md, 16:50 UTC): its
# default column (d) and its tight column (t: --cut-choice volume --merge-order volume --merge-parts 40)
SETS=${SETS:-"camel.off:0.03:0.04:d knot1.off:0.05:0.05556:d fandisk.off:0.04:0.04444:d armadillo.off:0.045:0.045:d bunny00.off:0.05:0.05:d bunny.obj:0.05:0.05:d camel.off:0.03:0.04254:t knot1.off:0.04:0.05418:t fandisk.off:0.025:0.04476:t armadillo.off:0.035:0.04903:t bunny00.off:0.025:0.0487:t bunny.obj:0.03:0.04872:t"}
if [ -n "${MESHES:-}" ]; then # a subset: only the sets of these mesh files
  keep=""
  for s in $SETS; do for mf in $MESHES; do [ "${s%%:*}" = "$mf" ] && keep="$keep $s"; done; done
  SETS=$keep
fi
TIGHT="--cut-choice volume --merge-order volume --merge-parts 40"
run() { # BIN FILE TAU MTAU THREADS[p] OBJ d|t -> "wall cpu"
  local pol=${OMP_WAIT_POLICY:-} opts=""
  case $5 in *p) pol=passive;; esac
  [ "${7:-d}" = t ] && opts=$TIGHT
  # shellcheck disable=SC2086
  env ${pol:+OMP_WAIT_POLICY=$pol} /usr/bin/time -o "$T/time" -f "%e %U %S" timeout 900 "$1" 3d "$2" -t "$3" --merge-tau "$4" \
    $opts --threads "${5%p}" -o "$6" > /dev/null 2>&1 || { echo "fail fail"; return; }
  awk '{printf "%s %.2f\n", $1, $2 + $3}' "$T/time"
}
min() { awk 'BEGIN { m = ""; c = "" } { if ($1 != "fail") { if (m == "" || $1 + 0 < m + 0) m = $1; if (c == "" || $2 + 0 < c + 0) c = $2 } } END { print (m == "" ? "fail fail" : m " " c) }'; }
{
echo "acd 3d speed, $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')."
echo "Load average at start $(cut -d' ' -f1 /proc/loadavg). wall: the smallest of $REPS runs (seconds, process"
echo "elapsed, reading the mesh included); cpu: the smallest user + system seconds of the $REPS runs. Runs"
echo "alternate between the two binaries, so the two figures of a row saw about the same load."
[ -n "$BASE" ] && echo "Baseline: ${BASE_REF:-$BASE}; cpu ratio = baseline cpu / this build's cpu."
echo
echo "Settings: d = the default options, t = $TIGHT; tau / merge tau as given."
echo
echo "| model | settings | threads | wall | cpu | base wall | base cpu | cpu ratio (base / this) | load (end) | hull OBJ as with $(echo $THREADS | awk '{print $1}') thread(s) | hull OBJ as the baseline's |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
} > "$T/out.md"
cat "$T/out.md"
for s in $SETS; do
  IFS=: read -r mf tau mt opt <<< "$s"
  f=$M/$mf
  [ -f "$f" ] || continue
  m=${mf%.*}.${opt:-d}
  for th in $THREADS; do
    : > "$T/new"; : > "$T/basetimes"
    for r in $(seq "$REPS"); do
      run "$ACD" "$f" "$tau" "$mt" "$th" "$T/$m.$th.obj" "${opt:-d}" >> "$T/new"
      [ -n "$BASE" ] && run "$BASE" "$f" "$tau" "$mt" "$th" "$T/$m.$th.base.obj" "${opt:-d}" >> "$T/basetimes"
    done
    read -r w c <<< "$(min < "$T/new")"
    bw="" bc="" ratio="" sameb=""
    if [ -n "$BASE" ]; then
      read -r bw bc <<< "$(min < "$T/basetimes")"
      ratio=$(awk -v a="$bc" -v b="$c" 'BEGIN { if (a + 0 > 0 && b + 0 > 0) printf "%.2f", a / b }')
      sameb=yes
      cmp -s "$T/$m.$th.obj" "$T/$m.$th.base.obj" || sameb=no
    fi
    first=$(echo $THREADS | awk '{print $1}')
    samet=yes
    cmp -s "$T/$m.$th.obj" "$T/$m.$first.obj" || samet=no
    echo "| ${m%.*} | ${opt:-d} | $th | $w | $c | $bw | $bc | $ratio | $(cut -d' ' -f1 /proc/loadavg) | $samet | $sameb |" | tee -a "$T/out.md"
  done
done
[ -n "${OUT:-}" ] && cp "$T/out.md" "$OUT"
exit 0
