#!/usr/bin/env bash
# acd 2d --exact mcd|hm: exact convex decompositions through every output of acd 2d.
# texas.poly: both methods pass --verify, the JSON report parses, has one more component than
# diagonals (no holes), convex components that are their own hulls, and MCD <= HM; a polygon with
# a hole is refused by MCD (exit 2) and decomposed by HM; bad or conflicting options exit 1.
. "$(dirname "$0")/lib.sh"
M="$DATA/polygons-lien"
if [ ! -d "$M" ]; then
  echo "skip: $M missing"
  exit 77
fi

for m in mcd hm; do
  "$ACD" 2d "$M/texas.poly" --exact $m --verify --json "$T/$m.json" -o "$T/$m.geojson" --svg "$T/$m.svg" \
    > "$T/out" 2> "$T/err"; rc=$?
  [ $rc = 0 ] || fail "texas --exact $m exit $rc: $(cat "$T/err")"
  grep -q "verify: passed" "$T/out" || fail "texas --exact $m: no pass line: $(cat "$T/out")"
  grep -q "exact $m" "$T/out" || fail "texas --exact $m: summary does not name the method: $(cat "$T/out")"
  python3 - "$T/$m.json" "$T/$m.geojson" $m > "$T/$m.count" <<'PY' || fail "texas --exact $m: JSON check"
import json, sys
d = json.load(open(sys.argv[1]))
m = sys.argv[3]
n = len(d["components"])
assert d["measure"] == "exact-" + m, d["measure"]
assert d["tau"] == 0 and d["stats"]["max_concavity"] == 0
assert d["stats"]["components"] == n and n > 1
assert n == len(d["cuts"]) + 1, (n, len(d["cuts"]))
assert d["hulls"] == d["components"]
assert d["concavities"] == [0] * n
assert d["input"]["vertices"] == 139 and d["input"]["holes"] == 0
assert d["verify"]["passed"] is True
# every cut joins two input vertices (diagonals, no Steiner points)
verts = {tuple(p) for c in d["components"] for p in c}
for c in d["cuts"]:
    assert len(c) == 2 and tuple(c[0]) in verts and tuple(c[1]) in verts, c
# each component convex: no clockwise turn
for c in d["components"]:
    k = len(c)
    for i in range(k):
        (ax, ay), (bx, by), (cx, cy) = c[i - 1], c[i], c[(i + 1) % k]
        assert (bx - ax) * (cy - by) - (by - ay) * (cx - bx) >= -1e-9, (c, i)
g = json.load(open(sys.argv[2]))
assert len(g["features"]) == n
print(n)
PY
  grep -q "<svg" "$T/$m.svg" || fail "texas --exact $m: no SVG"
done
mcd=$(cat "$T/mcd.count"); hm=$(cat "$T/hm.count")
[ "$mcd" -le "$hm" ] || fail "MCD $mcd > HM $hm components"
[ "$mcd" = 38 ] || fail "texas MCD has $mcd components, expected 38 (spec §7.4)"
[ "$hm" -le $((4 * mcd)) ] || fail "HM $hm > 4 x MCD $mcd"

# a hole: MCD unsupported (exit 2, message names the hole), HM fine; .poly output
"$ACD" 2d "$M/hole1.poly" --exact mcd > /dev/null 2> "$T/err"; rc=$?
[ $rc = 2 ] || fail "hole1 --exact mcd exit $rc"
grep -q "unsupported" "$T/err" && grep -q "hole" "$T/err" || fail "hole1 mcd message: $(cat "$T/err")"
"$ACD" 2d "$M/hole1.poly" --exact hm --verify -o "$T/h.poly" --json - > "$T/h.json" 2> "$T/err"; rc=$?
[ $rc = 0 ] || fail "hole1 --exact hm exit $rc: $(cat "$T/err")"
python3 -c "
import json, sys
d = json.load(open('$T/h.json'))
assert d['input']['holes'] == 1 and d['verify']['passed'] is True
assert len(d['cuts']) == len(d['components'])  # n - 1 + holes diagonals
" || fail "hole1 hm JSON"
"$ACD" 2d "$T/h.poly" > /dev/null || fail "hole1 hm .poly output does not read back"

# command-line errors
"$ACD" 2d "$M/texas.poly" --exact xyz > /dev/null 2> "$T/err"; rc=$?
[ $rc = 1 ] || fail "--exact xyz exit $rc"
grep -q "mcd or hm" "$T/err" || fail "--exact xyz message: $(cat "$T/err")"
"$ACD" 2d "$M/texas.poly" --exact mcd -m sp > /dev/null 2> "$T/err"; rc=$?
[ $rc = 1 ] || fail "--exact mcd -m sp exit $rc"
grep -q -- "-m .*--exact" "$T/err" || fail "-m conflict message: $(cat "$T/err")"
for o in "-t 0" "--tau=1" "--sc 1" "--sd 2" "--cut diagonal" "--normalize" "--notch-eps 0"; do
  # shellcheck disable=SC2086
  "$ACD" 2d "$M/texas.poly" $o --exact hm > /dev/null 2>&1; rc=$?
  [ $rc = 1 ] || fail "$o --exact hm exit $rc"
done
"$ACD" 2d "$M/texas.poly" --exact > /dev/null 2>&1; rc=$?
[ $rc = 1 ] || fail "--exact without a value exit $rc"
echo "ok"
