#!/usr/bin/env bash
# Two builds of `acd segment` side by side in the same run (before / after a speed change): per
# mesh, the best of REPS process CPU times (user + system, from /proc via GNU time's format, which
# the machine's other jobs disturb less than wall time) and wall times, their ratio, and whether
# the .seg labels and the JSON summary (all but "seconds") are identical, for --threads 1 and 2.
#
# usage: bench/bench_corise_speed.sh BEFORE_ACD AFTER_ACD [MESH ...]
#   e.g. git worktree/checkout of the old commit built in /tmp/old: bench/bench_corise_speed.sh /tmp/old/acd build/acd
# Meshes: data/meshes (scripts/fetch-data.sh); tau 0.1, default parameters.
set -uo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: $0 BEFORE_ACD AFTER_ACD [MESH ...]"; exit 1; }
OLD=$1 NEW=$2
shift 2
MESHES=${*:-"camel homer elephant dino hand armadillo"}
REPS=${REPS:-3}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); $(nproc) cores, $(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'); load $(cut -d' ' -f1 /proc/loadavg)"
# best (by CPU) of REPS runs: prints "cpu wall"
best() {
  local b=""
  for _ in $(seq "$REPS"); do
    /usr/bin/time -f "%U %S %e" -o "$T/t" "$@" > /dev/null 2>&1 || { echo "failed"; return; }
    read -r u s e < "$T/t"
    local c; c=$(python3 -c "print('%.3f %.3f' % ($u + $s, $e))")
    if [ -z "$b" ] || python3 -c "import sys; sys.exit(0 if float('${c% *}') < float('${b% *}') else 1)"; then b=$c; fi
  done
  echo "$b"
}
echo "| mesh | faces | threads | CPU s before | CPU s after | before / after | wall s before | wall s after | CPU s per 20k faces after | output |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for m in $MESHES; do
  f=data/meshes/$m.off
  [ -f "$f" ] || { echo "| $m | missing | | | | | | | | |"; continue; }
  faces=$(awk '!/^#/ && NF {n++; if (n == 2) {print $2; exit}} /^OFF[ \t]+[0-9]/ {print $3; exit}' "$f")
  for th in 1 2; do
    thr=(--threads "$th")
    "$OLD" segment --help 2>&1 | grep -q -- --threads || thr=()
    read -r co wo <<< "$(best "$OLD" segment "$f" -t 0.1 "${thr[@]}")"
    read -r cn wn <<< "$(best "$NEW" segment "$f" -t 0.1 --threads "$th")"
    "$OLD" segment "$f" -t 0.1 "${thr[@]}" --seg "$T/a.seg" --json "$T/a.json" > /dev/null 2>&1
    "$NEW" segment "$f" -t 0.1 --threads "$th" --seg "$T/b.seg" --json "$T/b.json" > /dev/null 2>&1
    same="identical"
    cmp -s "$T/a.seg" "$T/b.seg" || same="labels differ"
    diff -q <(grep -v '"seconds"' "$T/a.json") <(grep -v '"seconds"' "$T/b.json") > /dev/null || same="$same, JSON differs"
    label=$th; [ ${#thr[@]} = 0 ] && label="$th (before: 1)"
    echo "| $m | $faces | $label | $co | $cn | $(python3 -c "print('%.2f' % ($co / max($cn, 1e-3)))") | $wo | $wn | $(python3 -c "print('%.3f' % ($cn * 20000 / $faces))") | $same |"
  done
done
