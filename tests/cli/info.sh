#!/usr/bin/env bash
# CLI test of `acd info`: JSON report on the committed test meshes, --repair, error exit codes.
# Usage: info.sh ACD_BINARY SOURCE_DIR SHARED_DATA_DIR
. "$(dirname "$0")/lib.sh"
set -eo pipefail
D="$SRC/tests/data/meshes"
command -v python3 >/dev/null || { echo "python3 missing: skipping"; exit 77; }

check() { # check FILE PYTHON-CONDITION [acd info options...]
  local file=$1 cond=$2
  shift 2
  "$ACD" info --json "$@" "$file" > "$T/out.json"
  python3 - "$T/out.json" "$cond" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for k in ["vertices", "faces", "boundary_edges", "nonmanifold_edges", "components", "genus", "closed",
          "oriented", "volume", "area", "self_intersections"]:
    assert k in d, "missing key " + k
if not eval(sys.argv[2], {}, {"d": d, "abs": abs}):
    sys.exit("condition failed: %s\n%s" % (sys.argv[2], json.dumps(d, indent=1)))
PY
}

check "$D/two_parts.obj" 'd["vertices"] == 8 and d["faces"] == 8 and d["components"] == 2 and d["closed"] and d["genus"] == 0 and abs(d["volume"] - 1/3) < 1e-12 and d["self_intersections"] == 0'
check "$D/torus.off" 'd["vertices"] == 72 and d["faces"] == 144 and d["genus"] == 1 and d["closed"] and d["oriented"] and d["volume"] > 0'
check "$D/cube_flipped.stl" 'd["vertices"] == 8 and d["faces"] == 12 and not d["oriented"] and d["orientation_conflicts"] == 9 and d["closed"]'
check "$D/cube_flipped.stl" 'd["oriented"] and abs(d["volume"] - 1) < 1e-12 and d["repair"]["faces_flipped"] == 3' --repair "$T/fixed.obj.gz"
check "$T/fixed.obj.gz" 'd["oriented"] and d["vertices"] == 8 and abs(d["volume"] - 1) < 1e-12'
check "$D/torus.off" 'd["self_intersections"] is None' --no-self-intersections

# text output names the genus
"$ACD" info "$D/torus.off" | grep -q "^genus *1"

# errors: exit 2 with the line number for a malformed file, 4 for a missing file, 1 for usage
printf 'v 0 0 0\nv 1 0 0\nf 1 2 3\n' > "$T/bad.obj"
set +e
"$ACD" info "$T/bad.obj" 2> "$T/err"; rc=$?
set -e
[ $rc -eq 2 ] || { echo "bad.obj: exit $rc, expected 2"; exit 1; }
grep -q "bad.obj:3" "$T/err" || { echo "no line number in: $(cat "$T/err")"; exit 1; }
set +e
"$ACD" info "$T/missing.off" 2>/dev/null; rc=$?
"$ACD" info 2>/dev/null; rc2=$?
"$ACD" info --bogus "$D/torus.off" 2>/dev/null; rc3=$?
"$ACD" info "$T" 2>/dev/null; rc4=$?
set -e
[ $rc -eq 4 ] && [ $rc2 -eq 1 ] && [ $rc3 -eq 1 ] && [ $rc4 -eq 4 ] || { echo "exit codes $rc $rc2 $rc3 $rc4, expected 4 1 1 4"; exit 1; }
# a mesh through a pipe
cat "$D/torus.off" | "$ACD" info --json /dev/stdin | grep -q '"genus":	1' 
echo "acd info: all checks passed"
