#!/usr/bin/env bash
# The 3D ACD benchmark: the dissertation's Table 5 on the models the Debian packages have, and the
# figures users compare with the peers (acd eval). Writes docs/results/3d.md.
# usage: bench/bench_3d.sh [BUILD_DIR] [target]   (needs data/meshes: bash scripts/fetch-data.sh)
# Environment (target table): ACD_EXTRA more acd 3d options for every run (e.g. "--cut-weight product"),
# TARGET_OUT another file for the table, TARGET_MESHES the meshes of data/meshes to run (default the six),
# SKIP_TARGET=1 makes only docs/results/3d.md.
# With "target", only the issue-target table (docs/results/3d-target.md) is made; without it, both
# docs/results/3d.md and docs/results/3d-target.md.
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
ACD=$B/acd
M=data/meshes
OUT=docs/results/3d.md
[ -x "$ACD" ] || { echo "bench_3d: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_3d: no $M; run scripts/fetch-data.sh"; exit 77; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
ONLY=${2:-}

# The issue-4 item-6 target table: per mesh, the largest tau of 0.05, 0.045, ..., 0.02 whose result
# (merge pass on, the default) reaches concavity_max <= 0.02, and the same tau with --no-merge.
run_eval() { # FILE TAU [ARGS] -> parts seconds cpu concavity_max iou coverage
  local f=$1 tau=$2; shift 2
  rm -f "$T/h.obj"
  /usr/bin/time -o "$T/time" -f "%U" timeout 900 "$ACD" 3d "$f" -t "$tau" -o "$T/h.obj" --threads 2 ${ACD_EXTRA:-} "$@" > "$T/line" 2>/dev/null || true
  local parts secs cpu ev
  parts=$(head -1 "$T/line" | awk '{print $1}'); secs=$(head -1 "$T/line" | awk '{print $(NF-1)}')
  cpu=$(tail -1 "$T/time" 2>/dev/null)
  ev=$("$ACD" eval "$f" "$T/h.obj" --json 2>/dev/null | python3 -c "import json,sys; d=json.load(sys.stdin); print('%.4f %.4f %.4f' % (d['concavity_max'], d['iou'], d['coverage']))" 2>/dev/null || echo "fail fail fail")
  echo "${parts:-fail} ${secs:-fail} ${cpu:-fail} $ev"
}
ok_c() { awk -v c="$1" 'BEGIN { exit !(c != "fail" && c + 0 <= 0.02) }'; }
# The tight pipeline (docs/acd3d.md "Hull tightness"): cut choice by hull volume, the merge ordered
# by the hull volume a join adds and stopped at TIGHT_PARTS parts; the merge tolerance set so that the
# merge bound (a two-sided distance per part) is 0.0195 of the bounding-box diagonal (the target's
# 0.02 with a margin), i.e. 0.0195 x diagonal / radius in tau's units; then up to TIGHT_REFINE
# refinement steps at that part count (cuts by volume planes with joins, re-cuts of pairs).
TIGHT_PARTS=${TIGHT_PARTS:-40}
TIGHT_REFINE=${TIGHT_REFINE:-40}
TIGHT0="--cut-choice volume --merge-order volume --merge-parts $TIGHT_PARTS"
TIGHT="$TIGHT0 --merge-refine $TIGHT_REFINE"
# The budget pipeline (docs/acd3d.md "Excess-driven budget"): no tau-driven splitting (-t 10 keeps the
# input whole), then best-first plane cuts by the hull volume they save up to BUDGET_PARTS parts, every
# part brought within the merge tolerance, then the tight merge and refinement at that count.
BUDGET_PARTS=${BUDGET_PARTS:-$TIGHT_PARTS}
BUDGET="--budget $BUDGET_PARTS --cut-choice volume --merge-order volume --merge-parts $BUDGET_PARTS --merge-refine $TIGHT_REFINE"
# The budget pipeline with the hulls trimmed (docs/acd3d.md "Trimmed hulls"): at most TRIM_F of the
# input's volume left outside the hulls; at TRIM_PARTS parts (the armadillo at 43, CoACD's largest
# count in the issue, where the untrimmed budget column is at 40).
TRIM_F=${TRIM_F:-0.0008}
trim_parts() { case $1 in armadillo.off) echo 43;; *) echo "$BUDGET_PARTS";; esac; }
diag_radius() { # FILE -> diagonal radius
  local f=$1 r d
  r=$("$ACD" 3d "$f" -t 100 --no-merge --threads 2 2>/dev/null | head -1 | sed 's/.*radius \([0-9.e+-]*\)).*/\1/')
  d=$("$ACD" info "$f" 2>/dev/null | python3 -c "
import re,sys
for l in sys.stdin:
    if l.startswith('bounding box'):
        v=[float(x) for x in re.findall(r'[-+]?[0-9][0-9.eE+-]*', l[len('bounding box'):])]
        print(sum((v[3+k]-v[k])**2 for k in range(3))**0.5)")
  echo "$d $r"
}
meets() { # "ROW" (tau mt parts secs cpu conc iou cov): the whole target met (parts <= TIGHT_PARTS)
  awk -v r="$1" -v np="$TIGHT_PARTS" 'BEGIN { n = split(r, f, " "); exit !(n >= 8 && f[6] != "fail" && f[6] + 0 <= 0.02 &&
      f[3] + 0 <= np && f[7] + 0 >= 0.95 && f[8] + 0 >= 0.999) }'
}
pick_better() { # "ROW_A" "ROW_B" (tau mt parts secs cpu conc iou cov) -> the better: concavity_max <= 0.02 first, then parts <= TIGHT_PARTS, then IoU
  awk -v a="$1" -v b="$2" -v np="$TIGHT_PARTS" 'function key(r, f, n) { n = split(r, f, " "); if (n < 8 || f[6] == "fail") return -1;
      return (f[6] + 0 <= 0.02) * 4 + (f[3] + 0 <= np) * 2 + f[7] / 10 }
    BEGIN { if (a == "" || key(b) > key(a)) print b; else print a }'
}
target_table() {
  local TO=${TARGET_OUT:-docs/results/3d-target.md}
  {
  echo "# 3D ACD against the issue's target (issue 4 item 6)"
  echo
  [ -n "${ACD_EXTRA:-}" ] && { echo "Every run with \`$ACD_EXTRA\`."; echo; }
  echo "Generated by \`bench/bench_3d.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $cpu;"
  echo "load average at start $(cut -d' ' -f1 /proc/loadavg). The cores may be shared with other jobs (see the reading below):"
  echo "wall times are noisy and inflated by the load; the user CPU seconds are the steadier figure (an idle"
  echo "machine's wall time was not measured; with 2 threads it cannot be below cpu / 2)."
  echo
  echo "Target: at a tau reaching concavity_max <= 0.02 (acd eval: two-sided surface distance between the mesh"
  echo "and the union of the hulls, relative to the bounding-box diagonal), no more parts than CoACD (27-43),"
  echo "IoU >= 0.95, coverage >= 0.999, under 2 s per mesh on 2 cores. CoACD's reference figures on this"
  echo "machine: 13-54 s per mesh, 27-43 parts, concavity_max 0.015-0.028, IoU 0.83-0.97."
  echo
  echo "**Default** (the defaults of \`acd 3d\`): per mesh, the first of tau = 0.05, 0.045, ..., 0.02 (relative"
  echo "to the minimum enclosing sphere's radius) whose result with \`--merge-tau\` = tau reaches concavity_max <= 0.02;"
  echo "at that tau the largest merge tau of 4/3, 5/4, 7/6, 10/9 x tau that still reaches it (else tau)."
  echo "**Tight** (\`$TIGHT\`, docs/acd3d.md \"Hull tightness\"): merge tau = 0.0195 x bbox diagonal / radius"
  echo "(the merge bound, a two-sided distance per part, then stays under the target's 0.02 of the diagonal);"
  echo "of tau = 0.05, 0.045, ..., 0.025 the result with concavity_max <= 0.02 and at most $TIGHT_PARTS parts of highest IoU."
  echo "**Fastest met**: of the same tight runs, and of tight runs without the refinement (\`$TIGHT0\`, same taus, scan"
  echo "stopped at the first met), the first of each (largest tau: the fewest splits) meeting the whole target"
  echo "(concavity_max <= 0.02, at most $TIGHT_PARTS parts, IoU >= 0.95, coverage >= 0.999); of the two the one of"
  echo "least wall time, its setting (r0: no refinement, r$TIGHT_REFINE: refined), wall seconds and cpu; \"-\" when none does."
  echo "**Budget** (\`-t 10 $BUDGET\`, docs/acd3d.md \"Excess-driven budget\"): the tight column's merge tau; one run."
  echo "**Trimmed**: the budget run with \`--trim-coverage $TRIM_F\` (docs/acd3d.md \"Trimmed hulls\": caps of the hulls"
  echo "that are mostly air cut off, at most $TRIM_F of the input's volume left outside the hulls), at $BUDGET_PARTS parts"
  echo "and the armadillo at 43."
  echo "**No merge**: the default's tau with \`--no-merge\`. cpu: user CPU seconds of the run (both threads)."
  echo
  echo "| model | triangles | default: tau / merge tau | parts | concavity_max | IoU | coverage | cpu | tight: tau / merge tau | parts | concavity_max | IoU | coverage | seconds | cpu | fastest met: tau | setting | IoU | seconds | cpu | budget: parts | concavity_max | IoU | coverage | seconds | cpu | trimmed: parts | concavity_max | IoU | coverage | seconds | cpu | no merge: parts | concavity_max | IoU |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  } > "$T/target.md"
  local mf f m tri best tau r
  for mf in ${TARGET_MESHES:-camel.off knot1.off fandisk.off armadillo.off bunny00.off bunny.obj}; do
    f=$M/$mf
    [ -f "$f" ] || continue
    m=${mf%.*}
    if [ "${mf##*.}" = off ]; then tri=$(awk 'NR>1 && NF>=3 && !/^#/ {print $2; exit}' "$f"); else tri=$(grep -c '^f ' "$f"); fi
    best=""
    local mt r1
    for tau in 0.05 0.045 0.04 0.035 0.03 0.025 0.02; do
      # merge tau = tau first; when it reaches the target, the largest of 4/3, 5/4, 7/6, 10/9 x tau
      # that still does (fewer parts), else tau
      r1=$(run_eval "$f" $tau --merge-tau $tau)
      best="$tau $tau $r1"
      ok_c "$(echo "$r1" | awk '{print $4}')" || continue
      for mt in $(awk -v t=$tau 'BEGIN { printf "%.4g %.4g %.4g %.4g", t * 4 / 3, t * 5 / 4, t * 7 / 6, t * 10 / 9 }'); do
        r=$(run_eval "$f" $tau --merge-tau $mt)
        if ok_c "$(echo "$r" | awk '{print $4}')"; then best="$tau $mt $r"; break; fi
      done
      break
    done
    set -- $best
    local dtau=$1 row="| $m | $tri | $1 / $2 | $3 | $6 | $7 | $8 | $5"
    # tight
    local dr tmt tbest="" tfast=""
    dr=$(diag_radius "$f")
    tmt=$(echo "$dr" | awk '{ printf "%.4g", 0.0195 * $1 / $2 }')
    for tau in 0.05 0.045 0.04 0.035 0.03 0.025; do
      r=$(run_eval "$f" $tau --merge-tau $tmt $TIGHT)
      tbest=$(pick_better "$tbest" "$tau $tmt $r")
      [ -z "$tfast" ] && meets "$tau $tmt $r" && tfast="$tau $tmt $r"
    done
    local tfast0=""
    for tau in 0.05 0.045 0.04 0.035 0.03 0.025; do
      r=$(run_eval "$f" $tau --merge-tau $tmt $TIGHT0)
      meets "$tau $tmt $r" && { tfast0="$tau $tmt $r"; break; }
    done
    local fset="r$TIGHT_REFINE"
    if [ -n "$tfast0" ] && { [ -z "$tfast" ] || awk -v a="$(echo "$tfast0" | awk '{print $4}')" \
        -v b="$(echo "$tfast" | awk '{print $4}')" 'BEGIN { exit !(a + 0 < b + 0) }'; }; then
      tfast=$tfast0; fset=r0
    fi
    set -- $tbest
    row="$row | $1 / $2 | $3 | $6 | $7 | $8 | $4 | $5"
    if [ -n "$tfast" ]; then set -- $tfast; row="$row | $1 | $fset | $7 | $4 | $5"; else row="$row | - | | | | "; fi
    # budget
    set -- $(run_eval "$f" 10 --merge-tau $tmt $BUDGET)
    row="$row | $1 | $4 | $5 | $6 | $2 | $3"
    local tn
    tn=$(trim_parts "$mf")
    set -- $(run_eval "$f" 10 --merge-tau $tmt --budget "$tn" --cut-choice volume --merge-order volume --merge-parts "$tn" \
      --merge-refine $TIGHT_REFINE --trim-coverage $TRIM_F)
    row="$row | $1 | $4 | $5 | $6 | $2 | $3"
    set -- $(run_eval "$f" "$dtau" --no-merge)
    echo "$row | $1 | $4 | $5 |" >> "$T/target.md"
  done
  cp "$T/target.md" "$TO"
  cat "$TO"
}
if [ "$ONLY" = target ]; then target_table; exit 0; fi

{
echo "# 3D ACD: benchmark results"
echo
echo "Generated by \`bench/bench_3d.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $cpu;"
echo "load average at start $(cut -d' ' -f1 /proc/loadavg) (the machine may be shared: wall times are then inflated)."
echo "tau is relative to the radius of the minimum enclosing sphere (the seeds normalize to radius 1)."
echo
echo "## Table 5 (parts), solid and surface, tau 0.2 and 0.02"
echo
echo "Solid columns use the default resolver (global cuts); 'witness' is the baseline resolver"
echo "(\`--resolver witness\`, planes through the most concave vertex) measured in the same run; 'band' is solid"
echo "mode with \`--cut-choice band\` (the cut of least hull volume within a concavity band, docs/acd3d.md"
echo "\"Cut choice by band\", docs/results/3d-table5.md)."
echo
echo "| model | triangles | solid 0.2 | solid 0.02 | surface 0.2 | surface 0.02 | witness 0.2 | witness 0.02 | band 0.2 | band 0.02 | paper (solid 0.2/0.02, surface 0.2/0.02) | seconds (solid 0.02) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$T/out.md"
paper() {
  case $1 in
    bunny00) echo "6 / 178, 6 / 97";; armadillo) echo "11 / 98, 11 / 85";; elephant) echo "13 / 136, 15 / 123";;
    bull) echo "12 / 211, 12 / 191";; *) echo "—";;
  esac
}
for m in elephant bull bunny00 armadillo camel dino; do
  f=$M/$m.off
  [ -f "$f" ] || continue
  tri=$(grep -m1 -v '^#' "$f" | head -1 >/dev/null; awk 'NR>1 && NF>=3 && !/^#/ {print $2; exit}' "$f")
  row="| $m | $tri"
  secs=""
  for mode in solid surface; do
    for tau in 0.2 0.02; do
      line=$(timeout 900 "$ACD" 3d "$f" --mode $mode -t $tau 2>/dev/null | head -1)
      parts=$(echo "$line" | awk '{print $1}')
      [ -n "$parts" ] || parts="fail"
      row="$row | $parts"
      [ $mode = solid ] && [ $tau = 0.02 ] && secs=$(echo "$line" | awk '{print $(NF-1)}')
    done
  done
  for tau in 0.2 0.02; do
    line=$(timeout 900 "$ACD" 3d "$f" --resolver witness -t $tau 2>/dev/null | head -1)
    parts=$(echo "$line" | awk '{print $1}')
    row="$row | ${parts:-fail}"
  done
  for tau in 0.2 0.02; do
    line=$(timeout 900 "$ACD" 3d "$f" --cut-choice band -t $tau 2>/dev/null | head -1)
    parts=$(echo "$line" | awk '{print $1}')
    row="$row | ${parts:-fail}"
  done
  echo "$row | $(paper $m) | $secs |" >> "$T/out.md"
done
{
echo
echo "## Against the peers' figures (acd eval, solid mode)"
echo
echo "The issue's reference figures, measured on 2 cores with the peers' defaults: CoACD 13-54 s per mesh,"
echo "27-43 parts, concavity_max 0.015-0.028 of the bbox diagonal, IoU 0.83-0.97; V-HACD 4-10 s, 64 parts,"
echo "0.055-0.096, IoU 0.73-0.90. These rows run with the default merge pass; the issue's target (per mesh"
echo "at the tau reaching concavity_max <= 0.02, with and without the merge pass) is in docs/results/3d-target.md."
echo
echo "| model | tau | resolver | parts | seconds | concavity_max | IoU | coverage |"
echo "|---|---|---|---|---|---|---|---|"
} >> "$T/out.md"
for m in camel knot1 fandisk armadillo bunny00; do
  f=$M/$m.off
  [ -f "$f" ] || continue
  for tau in 0.1 0.05; do
    for r in global witness; do
      rm -f "$T/h.obj"
      line=$(timeout 900 "$ACD" 3d "$f" -t $tau --resolver $r -o "$T/h.obj" 2>/dev/null | head -1) || true
      parts=$(echo "$line" | awk '{print $1}'); secs=$(echo "$line" | awk '{print $(NF-1)}')
      ev=$("$ACD" eval "$f" "$T/h.obj" --json 2>/dev/null | python3 -c "import json,sys; d=json.load(sys.stdin); print('%.4f | %.4f | %.4f' % (d['concavity_max'], d['iou'], d['coverage']))" 2>/dev/null || echo "fail | | ")
      echo "| $m | $tau | $r | ${parts:-fail} | ${secs:-} | $ev |" >> "$T/out.md"
    done
  done
done
cp "$T/out.md" "$OUT"
cat "$OUT"
[ "${SKIP_TARGET:-0}" = 1 ] || target_table
