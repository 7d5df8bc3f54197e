#!/usr/bin/env bash
# CLI test of the OpenMP wait policy: the CLI makes idle threads wait passively unless the user chose
# (OMP_WAIT_POLICY or GOMP_SPINCOUNT set), and the result does not depend on the policy.
# Usage: threads.sh ACD_BINARY SOURCE_DIR
. "$(dirname "$0")/lib.sh"
set -eo pipefail
if "$ACD" --version | grep -q "^threads: none"; then echo "built without OpenMP: skipping"; exit 77; fi

env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$ACD" --version > "$T/v"
grep -q "^threads: OpenMP, OMP_WAIT_POLICY=passive$" "$T/v" || { cat "$T/v"; echo "FAIL: not passive by default"; exit 1; }
env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active "$ACD" --version > "$T/v"
grep -q "^threads: OpenMP, OMP_WAIT_POLICY=active$" "$T/v" || { cat "$T/v"; echo "FAIL: the user's policy was overridden"; exit 1; }
env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=1000 "$ACD" --version > "$T/v"
grep -q "^threads: OpenMP, OMP_WAIT_POLICY=(unset), GOMP_SPINCOUNT=1000$" "$T/v" || { cat "$T/v"; echo "FAIL: GOMP_SPINCOUNT not left to the user"; exit 1; }

# same hulls whatever the policy (2 threads, a budget run with trimming: parallel rounds)
M="$SRC/tests/data/meshes/torus.off"
env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$ACD" 3d "$M" --budget 6 --trim-coverage 0.001 --threads 2 -o "$T/a.obj" > "$T/out"
grep -Eq "^trimmed hulls: [1-9][0-9]* caps cut off" "$T/out" || { cat "$T/out"; echo "FAIL: no cap was cut: the rounds did not run"; exit 1; }
env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active "$ACD" 3d "$M" --budget 6 --trim-coverage 0.001 --threads 2 -o "$T/b.obj" > /dev/null
cmp "$T/a.obj" "$T/b.obj" || { echo "FAIL: the hulls depend on the wait policy"; exit 1; }
[ "$(grep -c "^o " "$T/a.obj")" -ge 6 ] || { echo "FAIL: expected at least 6 hulls"; exit 1; }
echo "threads: ok"
