#!/usr/bin/env bash
# The whole test suite, as CI runs it: installs the Debian packages, builds the release and the
# ASan+UBSan configurations, runs every CTest test in both, and runs each libFuzzer target
# briefly. Usage: scripts/test.sh   (env FUZZ_SECONDS=N to change the fuzzing time per target,
# FUZZ_JOBS=N for the number of targets run at a time; default the core count)
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=$(nproc 2>/dev/null || echo 2)
FUZZ_SECONDS=${FUZZ_SECONDS:-20}
# Each phase's wall time and CPU time (user+sys of the finished child processes, from
# /proc/$$/stat), printed as it ends: CI's budget is 20 minutes on 2 cores (docs/results/ci.md).
TICKS=$(getconf CLK_TCK 2>/dev/null || echo 100)
child_cpu() { local st; read -r st < /proc/$$/stat; st=${st##*) }; read -ra st <<< "$st"; echo $((st[13] + st[14])); }
PHASE_T0=$SECONDS; PHASE_CPU0=$(child_cpu)
phase_done() { # name
  local cpu; cpu=$(child_cpu)
  echo "== $1: $((SECONDS - PHASE_T0)) s wall, $(((cpu - PHASE_CPU0) / TICKS)) s CPU"
  PHASE_T0=$SECONDS; PHASE_CPU0=$cpu
}

bash scripts/install-deps.sh
# Real meshes for the data-driven tests (Debian's libcgal-demo and assimp-testmodels, npm's bunny;
# about 15 s). Without them those tests skip and say so.
bash scripts/fetch-data.sh || echo "test: fetch-data failed; the tests that need real meshes will skip"

phase_done "dependencies and data"
echo "== release build"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$JOBS"
phase_done "release build"
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
phase_done "release ctest"

echo "== ASan+UBSan build"
# -Og (Debug's flags otherwise; asserts stay on): the same ASan and UBSan checks on every test as at
# -O0, at about 1.6x the speed (AddressSanitizer's documentation asks for -O1 or more for a
# reasonable speed; GCC 12's -O1 with ASan gives a false -Wstringop-overread in src/acd2/tree.c).
# The ASan run was 400 of CI's 1000 s; docs/results/ci.md.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG="-g -Og" -DACD_SANITIZE=ON -DACD_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$JOBS"
phase_done "ASan+UBSan build"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 run_ctest build-asan -LE slow
phase_done "ASan+UBSan ctest"

echo "== libFuzzer targets (${FUZZ_SECONDS}s each)"
CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DACD_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$JOBS"
phase_done "fuzz build"
shopt -s nullglob
targets=(build-fuzz/fuzz/fuzz_*)
# Two targets at a time (FUZZ_JOBS, default the core count): each target is one process on one
# core, so running them one after another left a core idle for the whole phase. Each target still
# fuzzes for FUZZ_SECONDS; its log is printed whole once it is done, in the targets' order.
FUZZ_JOBS=${FUZZ_JOBS:-$JOBS}
fuzzdir=$(mktemp -d)
fuzz_one() { # index, target: fuzzes it, leaves its log in $fuzzdir/i.log and its exit code in $fuzzdir/i.rc
  local i=$1 f=$2 name corpus work rc=0
  name=$(basename "$f")
  corpus=fuzz/corpus/${name#fuzz_}
  work=$fuzzdir/$i.corpus
  mkdir -p "$work"
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
  # -timeout: an input running longer is a failure (a hang). 60 s, not 10: the sanitizer build runs
  # some valid inputs for 10-25 s of CPU (fuzz_acd3d_tight's budget-open-piece: 22 s, 1 s in release;
  # docs/results/fuzz.md), and CI's run at aed2f80 on a machine shared with other jobs took 41 s on it
  "$f" -max_total_time="$FUZZ_SECONDS" -max_len=65536 -timeout=60 -rss_limit_mb=2048 "$work" \
    > "$fuzzdir/$i.log" 2>&1 || rc=$?
  rm -rf "$work"
  echo "$rc" > "$fuzzdir/$i.rc.tmp" && mv "$fuzzdir/$i.rc.tmp" "$fuzzdir/$i.rc"
}
fuzz_report() { # index: prints target i's result whole and counts it
  local i=$1 name
  name=$(basename "${targets[$i]}")
  echo "-- $name"
  if [ "$(cat "$fuzzdir/$i.rc")" = 0 ]; then
    tail -n 2 "$fuzzdir/$i.log"; TOTAL_PASS=$((TOTAL_PASS + 1))
  else
    tail -n 60 "$fuzzdir/$i.log"; echo "FUZZ FAILURE in $name"; TOTAL_FAIL=$((TOTAL_FAIL + 1))
  fi
}
next_report=0
report_done() { # prints, in order, every target that has finished and whose predecessors are printed
  while [ "$next_report" -lt "${#targets[@]}" ] && [ -f "$fuzzdir/$next_report.rc" ]; do
    fuzz_report "$next_report"; next_report=$((next_report + 1))
  done
}
for i in "${!targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$FUZZ_JOBS" ]; do wait -n || true; done
  report_done
  fuzz_one "$i" "${targets[$i]}" &
done
wait || true
for ((i = next_report; i < ${#targets[@]}; i++)); do # after every target ended: none may lack a result
  if [ -f "$fuzzdir/$i.rc" ]; then fuzz_report "$i"; continue; fi
  echo "-- $(basename "${targets[$i]}")"; cat "$fuzzdir/$i.log" 2>/dev/null || true
  echo "FUZZ FAILURE in $(basename "${targets[$i]}") (the script did not record its result)"
  TOTAL_FAIL=$((TOTAL_FAIL + 1))
done
rm -rf "$fuzzdir"
phase_done "fuzz targets"
echo "== summary (ctest release + ctest ASan + fuzz targets)"
echo "all: ${TOTAL_PASS} passed, ${TOTAL_FAIL} failed, ${TOTAL_SKIP} skipped"
[ "$TOTAL_FAIL" -eq 0 ]
