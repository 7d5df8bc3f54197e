#!/usr/bin/env bash
# The one command for the 2D experiments of the dissertation (IV.D) and the 2D peers:
#   bash scripts/bench-2d-experiments.sh
# installs libcgal-dev and npm poly-decomp when missing, builds bench_2d_experiments and the CGAL
# harness, runs the sweeps, MCD/HM and the peers on the same polygons, and writes
# docs/results/2d-experiments.md with the SVG plots under docs/results/img/.
# Environment: DATA (default ../shared/data/polygons-lien), PEER_TIMEOUT seconds for poly-decomp's
# exhaustive decomp (default 20), CGAL_OPTIMAL_TIMEOUT for CGAL's optimal partition (default 60),
# OUT (default build/exper2d), D2 (real-world polygons, default data/2d from scripts/fetch-data.sh),
# STAR_CPU_LIMIT (default 1500 s of CPU, for MCD and CGAL's optimal partition on the star series), STARS
# (default "star_star5 star_star6"). See docs/experiments-2d.md.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
DATA=${DATA:-$ROOT/../shared/data/polygons-lien}
OUT=${OUT:-$ROOT/build/exper2d}
PEER_TIMEOUT=${PEER_TIMEOUT:-20}
CGAL_OPTIMAL_TIMEOUT=${CGAL_OPTIMAL_TIMEOUT:-60}
PEERS=$ROOT/bench/peers
mkdir -p "$OUT"

# --- dependencies (bench only, not CI) ---
if [ ! -d /usr/include/CGAL ]; then
  echo "installing libcgal-dev" >&2
  SUDO=; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get install -y --no-install-recommends libcgal-dev >&2 || echo "libcgal-dev not installed: CGAL peers skipped" >&2
fi
if [ ! -d "$PEERS/node_modules/poly-decomp" ] && command -v npm >/dev/null; then
  echo "installing poly-decomp into bench/peers/node_modules" >&2
  (cd "$PEERS" && npm install --no-save --no-package-lock --silent poly-decomp >&2) || echo "npm install failed: poly-decomp skipped" >&2
fi

# --- build ---
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2 --target bench_2d_experiments bench_2d_real acd_cli >/dev/null
BENCH=$ROOT/build/bench/bench_2d_experiments
ACD=$ROOT/build/acd
CGAL_BIN=$OUT/cgal_partition
if [ -d /usr/include/CGAL ]; then
  g++ -O2 -std=c++17 -o "$CGAL_BIN" "$PEERS/cgal_partition.cpp" -lgmp -lmpfr || CGAL_BIN=
else
  CGAL_BIN=
fi

# --- the star target, started in the background now (they take longest): exact partition of the
# star series by our MCD and by CGAL's optimal partition, each under the same CPU-time limit
# (ulimit -t STAR_CPU_LIMIT; the wall-clock guard is 3 times that) and memory limit (8 GB) ---
STAR_CPU_LIMIT=${STAR_CPU_LIMIT:-1500}
STAR_JOBS=
star_job() { # label csv command...: runs under the limits, writes "status,pieces,cpu" to csv
  local label=$1 csv=$2; shift 2
  local rc=0 out
  out=$( { /usr/bin/time -f "cpu %U %S" bash -c 'ulimit -t '"$STAR_CPU_LIMIT"'; ulimit -v 8000000; exec "$@"' _ \
          timeout $((3 * STAR_CPU_LIMIT)) "$@"; } 2>&1 ) || rc=$?
  local cpu pieces st
  cpu=$(echo "$out" | awk '/^cpu /{printf "%.2f", $2 + $3}')
  pieces=$(echo "$out" | sed -n -e 's/.*exact mcd: \([0-9]*\) components.*/\1/p' -e 's/^optimal,\([0-9]*\),.*/\1/p' | head -n 1)
  case $rc in
    0) st=ok ;;
    124) st="wall-clock guard (>$((3 * STAR_CPU_LIMIT)) s)"; pieces= ;;
    137|152) st="CPU limit (>${STAR_CPU_LIMIT} s)"; pieces= ;;
    *) st="error (exit $rc: $(echo "$out" | grep -v '^cpu ' | tail -n 1 | tr ',' ';' | cut -c1-120))"; pieces= ;;
  esac
  echo "$label,$st,$pieces,$cpu" > "$csv"
}
for s in ${STARS:-star_star5 star_star6}; do
  f=$DATA/$s.poly
  [ -f "$f" ] || continue
  mkdir -p "$OUT/polys"
  python3 - "$f" "$OUT/polys/$s.txt" <<'PY'
import sys
t = " ".join(l.split("#")[0] for l in open(sys.argv[1])).split()
n = int(t[1])  # "1", "n out", n points, the order line
pts = [(t[3 + 2 * i], t[4 + 2 * i]) for i in range(n)]
order = [int(x) for x in t[3 + 2 * n:3 + 3 * n]]
with open(sys.argv[2], "w") as f:
    f.write("%d\n" % n)
    for o in order:
        f.write("%s %s\n" % pts[o - 1])
PY
  n=$(head -n 1 "$OUT/polys/$s.txt")
  star_job "$s,$n,acd MCD (Keil-Snoeyink)" "$OUT/star-$s-acd.csv" "$ACD" 2d "$f" --exact mcd --verify &
  STAR_JOBS="$STAR_JOBS $!"
  if [ -n "$CGAL_BIN" ]; then
    star_job "$s,$n,CGAL optimal_convex_partition_2" "$OUT/star-$s-cgal.csv" \
      "$CGAL_BIN" optimal "$OUT/polys/$s.txt" "$OUT/pieces-$s-cgal-optimal.txt" &
    STAR_JOBS="$STAR_JOBS $!"
  fi
done

# --- acd sweeps, MCD, HM ---
"$BENCH" --data "$DATA" --out "$OUT"

# --- real-world polygons (data/2d from scripts/fetch-data.sh): ACD, HM, MCD, pictures ---
D2=${D2:-$ROOT/data/2d}
if [ -d "$D2" ]; then
  "$ROOT/build/bench/bench_2d_real" --data "$D2" --out "$OUT" || echo "bench_2d_real reported a failure" >&2
  rm -f "$ROOT"/docs/results/img/2d-real-*.svg
  tail -n +2 "$OUT/real/models.csv" | while IFS=, read -r name source n holes notches; do
    # run from OUT/real so that the pictures' captions name the file without a local path
    (cd "$OUT/real" && "$ACD" 2d "$name.poly" -t 0.05 --normalize --verify \
      --svg "$ROOT/docs/results/img/2d-real-$name-acd.svg" >/dev/null)
    if [ "$holes" = 0 ]; then ex=mcd; else ex=hm; fi
    (cd "$OUT/real" && "$ACD" 2d "$name.poly" --exact $ex --verify \
      --svg "$ROOT/docs/results/img/2d-real-$name-$ex.svg" >/dev/null)
  done
else
  echo "no $D2 (run scripts/fetch-data.sh): real-world section skipped" >&2
fi

# --- peers on the same polygons ---
echo "model,peer,status,pieces,cpu_s,covered,verify" > "$OUT/peers.csv"
run_peer() { # name timeout command...; uses model, poly, checkpoly, peers_csv
  local name=$1 to=$2; shift 2
  local pieces=$OUT/pieces-$model-$(echo "$name" | tr ' /' '__').txt line rc=0
  line=$(timeout "$to" "$@" "$poly" "$pieces" 2>/dev/null) || rc=$?
  if [ $rc -eq 124 ]; then echo "$model,$name,timeout (>${to} s),,,," >> "$peers_csv"; return; fi
  if [ $rc -ne 0 ]; then echo "$model,$name,error (exit $rc),,,," >> "$peers_csv"; return; fi
  local cpu=${line##*,}
  local chk
  chk=$("$BENCH" --check "$checkpoly" "$pieces") || { echo "$model,$name,check failed,,,," >> "$peers_csv"; return; }
  IFS=, read -r np ia pa cov ver <<< "$chk"
  echo "$model,$name,ok,$np,$cpu,$cov,$ver" >> "$peers_csv"
}
peers_csv=$OUT/peers.csv
tail -n +2 "$OUT/models.csv" | while IFS=, read -r model file n notches holes; do
  poly=$OUT/polys/$model.txt
  checkpoly=$DATA/$file.poly
  if [ -d "$PEERS/node_modules/poly-decomp" ]; then
    run_peer "poly-decomp quickDecomp" 120 env NODE_PATH="$PEERS/node_modules" node "$PEERS/polydecomp.js" quick
    run_peer "poly-decomp decomp" "$PEER_TIMEOUT" env NODE_PATH="$PEERS/node_modules" node "$PEERS/polydecomp.js" exact
  fi
  if [ -n "$CGAL_BIN" ]; then
    run_peer "CGAL approx (HM)" 120 "$CGAL_BIN" approx
    run_peer "CGAL greene_approx" 120 "$CGAL_BIN" greene
    run_peer "CGAL optimal" "$CGAL_OPTIMAL_TIMEOUT" "$CGAL_BIN" optimal
  fi
  echo "peers: $model done" >&2
done
# the real-world polygons without holes (the peers take simple polygons only)
if [ -f "$OUT/real/models.csv" ]; then
  peers_csv=$OUT/real/peers.csv
  echo "model,peer,status,pieces,cpu_s,covered,verify" > "$peers_csv"
  tail -n +2 "$OUT/real/models.csv" | while IFS=, read -r model source n holes notches; do
    [ "$holes" = 0 ] || continue
    poly=$OUT/polys/$model.txt
    checkpoly=$OUT/real/$model.poly
    if [ -d "$PEERS/node_modules/poly-decomp" ]; then
      run_peer "poly-decomp quickDecomp" 120 env NODE_PATH="$PEERS/node_modules" node "$PEERS/polydecomp.js" quick
    fi
    if [ -n "$CGAL_BIN" ]; then
      run_peer "CGAL approx (HM)" 120 "$CGAL_BIN" approx
      run_peer "CGAL greene_approx" 120 "$CGAL_BIN" greene
      run_peer "CGAL optimal" "$CGAL_OPTIMAL_TIMEOUT" "$CGAL_BIN" optimal
    fi
    echo "peers: $model done" >&2
  done
fi

# --- the star target: collect the jobs started after the build ---
wait $STAR_JOBS 2>/dev/null || true
echo "polygon,vertices,method,status,pieces,cpu_s" > "$OUT/star.csv"
for s in ${STARS:-star_star5 star_star6}; do
  cat "$OUT/star-$s-acd.csv" "$OUT/star-$s-cgal.csv" 2>/dev/null >> "$OUT/star.csv" || true
done

MODEL=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
MACHINE="Machine: $(nproc) cores online, $MODEL; load average $(cut -d' ' -f1 /proc/loadavg) at the end of the run; $(date -u '+%Y-%m-%d %H:%M UTC'); g++ $(g++ -dumpversion), node $(node --version 2>/dev/null || echo none), CGAL $(grep -m1 'define CGAL_VERSION ' /usr/include/CGAL/version.h 2>/dev/null | awk '{print $3}'), poly-decomp $(node -p "require('$PEERS/node_modules/poly-decomp/package.json').version" 2>/dev/null || echo none)."
python3 "$ROOT/bench/bench_2d_experiments_report.py" "$OUT" "$ROOT/docs/results/2d-experiments.md" "$ROOT/docs/results/img" "$MACHINE"
echo "wrote docs/results/2d-experiments.md and docs/results/img/2d-exp-*.svg" >&2
