#!/usr/bin/env bash
# The whole test suite, as CI runs it: installs the Debian packages, builds the release and the
# ASan+UBSan configurations, runs every CTest test in both, and runs each libFuzzer target
# briefly. Usage: scripts/test.sh   (env FUZZ_SECONDS=N to change the fuzzing time per target)
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=$(nproc 2>/dev/null || echo 2)
FUZZ_SECONDS=${FUZZ_SECONDS:-20}

bash scripts/install-deps.sh
# Real meshes for the data-driven tests (Debian's libcgal-demo and assimp-testmodels, npm's bunny;
# about 15 s). Without them those tests skip and say so.
bash scripts/fetch-data.sh || echo "test: fetch-data failed; the tests that need real meshes will skip"

echo "== release build"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$JOBS"
TOTAL_PASS=0; TOTAL_FAIL=0; TOTAL_SKIP=0
run_ctest() { # dir, extra args: runs ctest, keeps the counts for the closing line
  local dir=$1; shift
  local log; log=$(mktemp)
  local rc=0
  (cd "$dir" && ctest --output-on-failure -j"$JOBS" "$@") 2>&1 | tee "$log" || rc=1
  local total failed skipped
  total=$(sed -n 's/.*tests passed, \([0-9]*\) tests\{0,1\} failed out of \([0-9]*\).*/\2/p' "$log" | tail -1)
  failed=$(sed -n 's/.*tests passed, \([0-9]*\) tests\{0,1\} failed out of.*/\1/p' "$log" | tail -1)
  skipped=$(grep -c '\*\*\*Skipped\| Not Run' "$log" || true)
  TOTAL_PASS=$((TOTAL_PASS + ${total:-0} - ${failed:-0} - skipped))
  TOTAL_FAIL=$((TOTAL_FAIL + ${failed:-0}))
  TOTAL_SKIP=$((TOTAL_SKIP + skipped))
  rm -f "$log"
  return $rc
}
run_ctest build

echo "== ASan+UBSan build"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DACD_SANITIZE=ON -DACD_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$JOBS"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 run_ctest build-asan -LE slow

echo "== libFuzzer targets (${FUZZ_SECONDS}s each)"
CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DACD_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$JOBS"
shopt -s nullglob
targets=(build-fuzz/fuzz/fuzz_*)
for f in "${targets[@]}"; do
  name=$(basename "$f")
  corpus=fuzz/corpus/${name#fuzz_}
  work=$(mktemp -d)
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
  echo "-- $name"
  # -timeout: an input running longer is a failure (a hang). 60 s, not 10: the sanitizer build runs
  # some valid inputs for 10-25 s of CPU (fuzz_acd3d_tight's budget-open-piece: 22 s, 1 s in release;
  # docs/results/fuzz.md), and CI's run at aed2f80 on a machine shared with other jobs took 41 s on it
  if "$f" -max_total_time="$FUZZ_SECONDS" -max_len=65536 -timeout=60 -rss_limit_mb=2048 "$work" > "$work.log" 2>&1; then
    tail -n 2 "$work.log"; TOTAL_PASS=$((TOTAL_PASS + 1))
  else
    tail -n 60 "$work.log"; echo "FUZZ FAILURE in $name"; TOTAL_FAIL=$((TOTAL_FAIL + 1))
  fi
  rm -rf "$work" "$work.log"
done
echo "== summary (ctest release + ctest ASan + fuzz targets)"
echo "all: ${TOTAL_PASS} passed, ${TOTAL_FAIL} failed, ${TOTAL_SKIP} skipped"
[ "$TOTAL_FAIL" -eq 0 ]
