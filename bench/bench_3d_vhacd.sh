#!/usr/bin/env bash
# 3D ACD and V-HACD side by side, in the same run (issue 4 item 6: V-HACD is one of the peers).
# V-HACD 4 (kmammou/v-hacd, BSD-3-Clause) as the npm package vhacd-js compiles it to WebAssembly,
# run by the bench-only harness bench/peers/vhacd_run.mjs (never part of libacd or CI), once with
# its defaults (64 hulls, 400000 voxels) and once limited to our part count (maxHulls = ours, tight).
# Ours at the default and the tight settings of docs/results/3d-target.md (each at the tau reaching
# concavity_max <= 0.02), read from that table so the two stay in step. Every result is scored by `acd eval`.
# Writes docs/results/3d-vhacd.md. Without node/npm or the package the script says so and exits 0.
#
# usage: bench/bench_3d_vhacd.sh [BUILD_DIR]
#   env VHACD_MODULES: a node_modules directory holding vhacd-js (default: installed by npm into
#   ${XDG_CACHE_HOME:-~/.cache}/acd-peers); VHACD_TIMEOUT seconds per V-HACD run (default 300).
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
ACD=$B/acd
M=data/meshes
OUT=docs/results/3d-vhacd.md
TARGET=docs/results/3d-target.md
TIMEOUT=${VHACD_TIMEOUT:-300}
TIGHT="--cut-choice volume --merge-order volume --merge-parts 40" # the target table's tight column
[ -x "$ACD" ] || { echo "bench_3d_vhacd: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_3d_vhacd: no $M; run scripts/fetch-data.sh; skipped"; exit 0; }
command -v node >/dev/null || { echo "bench_3d_vhacd: node not found (apt-get install nodejs npm); skipped"; exit 0; }
MOD=${VHACD_MODULES:-}
if [ -z "$MOD" ]; then
  P=${XDG_CACHE_HOME:-$HOME/.cache}/acd-peers
  if [ ! -f "$P/node_modules/vhacd-js/lib/vhacd.js" ]; then
    mkdir -p "$P" && npm install --prefix "$P" --no-audit --no-fund vhacd-js@0.0.1 >/dev/null 2>&1 ||
      { echo "bench_3d_vhacd: cannot install vhacd-js from npm; skipped"; exit 0; }
  fi
  MOD=$P/node_modules
fi
[ -f "$MOD/vhacd-js/lib/vhacd.js" ] || { echo "bench_3d_vhacd: $MOD/vhacd-js missing; skipped"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')

. bench/peers/score.sh
target() { # MODEL -> "tau merge_tau tight_tau tight_merge_tau" from the target table (empty when missing)
  awk -F'|' -v m="$1" '{gsub(/ /, "", $2)} $2 == m {gsub(/ /, "", $4); gsub(/ /, "", $10); sub("/", " ", $4); sub("/", " ", $10); print $4, $10; exit}' "$TARGET"
}
vhacd() { # MESH HULLS [maxHulls] -> "hulls cpu" or "timeout" / "failed"
  local res rc
  res=$(timeout "$TIMEOUT" node bench/peers/vhacd_run.mjs "$MOD" "$1" "$2" ${3:-} 2>"$T/vh.err")
  rc=$?
  if [ $rc -eq 0 ]; then echo "${res%%,*} ${res##*,}"
  elif [ $rc -eq 124 ]; then echo "timeout"
  else echo "failed"; fi
}
rows=()
for mf in camel.off knot1.off fandisk.off armadillo.off bunny00.off bunny.obj; do
  f=$M/$mf; name=${mf%.*}
  [ -f "$f" ] || { echo "bench_3d_vhacd: $f missing, skipped"; continue; }
  read -r tau mtau ttau tmtau <<<"$(target "$name")"
  [ -n "${tmtau:-}" ] || { echo "bench_3d_vhacd: $name not in $TARGET, skipped"; continue; }
  faces=$("$ACD" info "$f" 2>/dev/null | awk '$1 == "faces" {print $2; exit}')
  ours=
  for run in "default:$tau:$mtau" "tight:$ttau:$tmtau"; do
    IFS=: read -r kind t mt <<<"$run"
    args=(-t "$t" --merge-tau "$mt" --threads 2 -o "$T/ours.obj")
    [ "$kind" = tight ] && args+=($TIGHT)
    c=$(cputime "$ACD" 3d "$f" "${args[@]}")
    p=$(head -1 "$T/out" | awk '{print $1}')
    read -r cm iou cov <<<"$(ev "$f" "$T/ours.obj")"
    rows+=("| $name | $faces | acd 3d ($kind) -t $t --merge-tau $mt | $p | $c | $cm | $iou | $cov |")
    [ "$kind" = tight ] && ours=$p
  done
  for mh in "" "$ours"; do
    r=$(vhacd "$f" "$T/vh.obj" $mh)
    label="V-HACD maxHulls $mh"; [ -z "$mh" ] && label="V-HACD defaults (64 hulls)"
    case $r in
      timeout|failed) rows+=("| $name | $faces | $label | $r | | | | |") ;;
      *) read -r hp hc <<<"$r"; read -r cm iou cov <<<"$(ev "$f" "$T/vh.obj")"
         rows+=("| $name | $faces | $label | $hp | $hc | $cm | $iou | $cov |") ;;
    esac
  done
  echo "bench_3d_vhacd: $name done"
done
{
  echo "# 3D ACD and V-HACD side by side (bench/bench_3d_vhacd.sh)"
  echo
  echo "Generated on $(date -u '+%Y-%m-%d %H:%M UTC'); machine: $(nproc) cores, $cpu; load average at start"
  echo "$(cut -d' ' -f1 /proc/loadavg) (shared machine: CPU seconds are the steadier figure). V-HACD 4 is the npm"
  echo "package vhacd-js 0.0.1 (V-HACD compiled to WebAssembly, one thread; native V-HACD is faster, the issue"
  echo "measured 4-10 s per mesh for it), run by bench/peers/vhacd_run.mjs with its defaults and with maxHulls"
  echo "set to our part count; its CPU seconds are those of computeConvexHulls only. Ours: CPU seconds (user +"
  echo "system) of the whole \`acd 3d\` process with 2 threads, reading and writing included, at the default"
  echo "and the tight (\`$TIGHT\`) settings of docs/results/3d-target.md. concavity_max, IoU and coverage: \`acd eval\` of the union of the hulls"
  echo "against the mesh (concavity_max: two-sided surface distance over the bounding-box diagonal)."
  echo
  echo "| mesh | faces | method | parts | CPU s | concavity_max | IoU | coverage |"
  echo "|---|---:|---|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
} > "$OUT"
echo "bench_3d_vhacd: wrote $OUT"
