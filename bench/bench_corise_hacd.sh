#!/usr/bin/env bash
# CoRiSe (acd segment) and HACD side by side, in the same run: the columns of the paper's Table 1
# (parts, time, volume of the union of the hulls over the mesh's volume) at tau 0.1, on CGAL's
# meshes (data/meshes, scripts/fetch-data.sh), next to the paper's category means where a
# category matches. Rewrites the section between the markers "<!-- bench_corise_hacd -->" and
# "<!-- /bench_corise_hacd -->" of docs/results/corise.md (appends it when absent).
#
# HACD: Debian's libbullet-extras-dev (libHACD, zlib licence), through the bench-only harness
# bench/peers/hacd_run.cpp, built here with g++ (never part of libacd or CI). Without the package
# the script says so and exits 0. HACD gets HACD_TIMEOUT seconds per mesh (default 120).
#
# usage: bench/bench_corise_hacd.sh [BUILD_DIR] [MESH ...]
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
shift || true
MESHES=${*:-"eight hand elephant dino homer camel armadillo"}
ACD=$B/acd
M=data/meshes
OUT=docs/results/corise.md
TIMEOUT=${HACD_TIMEOUT:-120}
SAMPLES=${EVAL_SAMPLES:-200000}
. bench/peers/hacd.sh
hacd_available bench_corise_hacd || exit 0
[ -x "$ACD" ] || { echo "bench_corise_hacd: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_corise_hacd: no $M; run scripts/fetch-data.sh; skipped"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
hacd_build bench_corise_hacd "$T/hacd_run" || exit 1

# union volume / mesh volume of the hulls in an OBJ (acd eval, stratified Monte Carlo)
volratio() {
  "$ACD" eval "$1" "$2" --json --samples "$SAMPLES" --surface-samples 1000 2>/dev/null |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("%.3f" % (d["union_volume"] / d["mesh_volume"]))' 2>/dev/null ||
    echo "n/a"
}
# the paper's Table 1 category means (parts HACD / CoRiSe, seconds HACD / CoRiSe, ratio HACD / CoRiSe)
paper() {
  case $1 in
    homer) echo "Human | 12.10 / 9.85 | 84.80 / 2.33 | 1.23 / 1.31";;
    hand) echo "Hand | 9.10 / 9.00 | 205.92 / 1.67 | 1.14 / 1.27";;
    armadillo) echo "Armadillo | 15.30 / 14.90 | 56.89 / 5.46 | 1.12 / 1.19";;
    camel|elephant|dino) echo "Four-leg | 12.95 / 12.25 | 61.85 / 1.86 | 1.20 / 1.25";;
    *) echo "— | | |";;
  esac
}

cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
{
echo "<!-- bench_corise_hacd -->"
echo "## CoRiSe vs HACD, Table 1 columns (bench/bench_corise_hacd.sh)"
echo
echo "Generated on $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $cpu; load average at"
echo "start $(cut -d' ' -f1 /proc/loadavg) (shared machine: times are CPU seconds, user + system)."
echo "tau = 0.1 for both. Ours: \`acd segment -t 0.1\` (default parameters, tau relative to the bounding"
echo "sphere's radius), CPU time of the whole process (reading, segmentation, per-part concavity, hulls,"
echo "writing). HACD: Debian's libHACD (libbullet-extras-dev) through bench/peers/hacd_run.cpp, concavity"
echo "0.1 x its normalisation (half the bounding-box diagonal = scale 1000, concavity 100: Bullet's"
echo "demo setting), no decimation, CPU time of Compute() only, timeout ${TIMEOUT} s. Volume ratio = volume"
echo "of the union of the hulls / volume of the mesh (\`acd eval\`, ${SAMPLES} stratified samples; the"
echo "paper's definition). Paper: the category means of Table 1 (Princeton benchmark models, not these"
echo "meshes; their machine: two Xeon 2.30 GHz), HACD / CoRiSe."
echo
echo "| mesh | faces | parts ours | parts HACD | CPU s ours | CPU s HACD | HACD / ours time | vol. ratio ours | vol. ratio HACD | paper category | paper parts | paper seconds | paper vol. ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$T/section.md"

for m in $MESHES; do
  f=$M/$m.off
  if [ ! -f "$f" ]; then echo "bench_corise_hacd: $f missing, skipped"; continue; fi
  faces=$(awk '!/^#/ && NF {n++; if (n == 2) {print $2; exit}} /^OFF[ \t]+[0-9]/ {print $3; exit}' "$f")
  TIMEFORMAT=%U+%S
  t_ours=$( { time "$ACD" segment "$f" -t 0.1 -o "$T/ours.obj" --json "$T/ours.json" >/dev/null 2>"$T/ours.err"; } 2>&1 )
  t_ours=$(python3 -c "print('%.2f' % ($t_ours))")
  p_ours=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["parts"])' "$T/ours.json" 2>/dev/null || echo "failed")
  v_ours=$(volratio "$f" "$T/ours.obj")
  res=$(timeout "$TIMEOUT" "$T/hacd_run" "$f" "$T/hacd.obj" 0.1 2>"$T/hacd.err")
  rc=$?
  if [ $rc -eq 124 ]; then
    p_h="timeout"; t_h="> $TIMEOUT (wall)"; ratio="> $(python3 -c "print('%.0f' % ($TIMEOUT / max($t_ours, 0.01)))")"; v_h="—"
  elif [ $rc -ne 0 ]; then
    p_h="failed ($rc)"; t_h="—"; ratio="—"; v_h="—"
  else
    p_h=${res%%,*}; t_h=${res##*,}
    ratio=$(python3 -c "print('%.0f' % ($t_h / max($t_ours, 0.01)))")
    v_h=$(volratio "$f" "$T/hacd.obj")
  fi
  row="| $m | $faces | $p_ours | $p_h | $t_ours | $t_h | $ratio | $v_ours | $v_h | $(paper "$m") |"
  echo "$row"
  echo "$row" >> "$T/section.md"
done
echo "<!-- /bench_corise_hacd -->" >> "$T/section.md"

python3 - "$OUT" "$T/section.md" <<'EOF'
import sys
path, sec = sys.argv[1], open(sys.argv[2]).read()
doc = open(path).read()
a, b = "<!-- bench_corise_hacd -->", "<!-- /bench_corise_hacd -->"
if a in doc and b in doc:
    doc = doc[:doc.index(a)] + sec.rstrip("\n") + doc[doc.index(b) + len(b):]
else:
    doc = doc.rstrip("\n") + "\n\n" + sec
open(path, "w").write(doc if doc.endswith("\n") else doc + "\n")
EOF
echo "bench_corise_hacd: wrote $OUT"
