#!/usr/bin/env bash
# acd 2d on bad input: exit 2 with a message naming the file and where (chain, vertex, line,
# byte); a missing file exits 4. Never a crash.
. "$(dirname "$0")/lib.sh"
# bad CODE FILE WORD...: exit CODE, stderr names the file and holds every WORD
bad() {
  local code=$1 file=$2; shift 2
  "$ACD" 2d "$T/$file" > "$T/out" 2> "$T/err"
  local rc=$?
  [ "$rc" = "$code" ] || fail "$file: exit $rc, expected $code: $(cat "$T/err")"
  grep -q "$file" "$T/err" || fail "$file: message does not name the file: $(cat "$T/err")"
  for w in "$@"; do grep -q -- "$w" "$T/err" || fail "$file: message lacks '$w': $(cat "$T/err")"; done
}
printf '1\n4 out\n0 0\n2 2\n2 0\n0 2\n1 2 3 4\n' > "$T/bowtie.poly"
bad 2 bowtie.poly "chain 0" "crosses"
printf '1\n3 out\n0 0\n1 0\n' > "$T/short.poly"
bad 2 short.poly "chain 0" "point 3"
printf '1\n3 out\n0 0\n1 0\nnan 1\n1 2 3\n' > "$T/nan.poly"
bad 2 nan.poly "chain 0"
printf '1\n3 out\n0 0\n1 0\n2 0\n1 2 3\n' > "$T/flat.poly"
"$ACD" 2d "$T/flat.poly" > /dev/null 2> "$T/err"; rc=$?
[ $rc = 2 ] || fail "collinear triangle: exit $rc: $(cat "$T/err")"
printf '2\n4 out\n0 0\n1 0\n1 1\n0 1\n1 2 3 4\n3 in\n5 5\n6 5\n5 6\n1 2 3\n' > "$T/hole_outside.poly"
bad 2 hole_outside.poly "chain 1" "outside"
printf '2\n4 out\n0 0\n4 0\n4 4\n0 4\n1 2 3 4\n4 in\n1 1\n5 2\n3 3\n1 3\n1 2 3 4\n' > "$T/hole_crossing.poly"
bad 2 hole_crossing.poly "chain"
printf '1\n4 out\n0 0\n1 0\n1 1\n1 2 3 4\n' > "$T/count.poly"
bad 2 count.poly
printf '{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1],[0,0]]' > "$T/trunc.geojson"
bad 2 trunc.geojson "byte"
printf '{"type":"Point","coordinates":[0,0]}' > "$T/point.geojson"
"$ACD" 2d "$T/point.geojson" > /dev/null 2> "$T/err"; rc=$?
[ $rc = 2 ] || fail "Point geometry: exit $rc: $(cat "$T/err")"
printf 'POLYGON((0 0, 1 0, 1 1, 0 1, 0 0)' > "$T/trunc.wkt"
bad 2 trunc.wkt
: > "$T/empty.poly"
bad 2 empty.poly "empty"
printf 'hello world\n' > "$T/garbage.txt"
bad 2 garbage.txt
printf '3\n4 out\n0 0\n10 0\n10 10\n0 10\n1 2 3 4\n4 in\n1 1\n1 9\n9 9\n9 1\n1 2 3 4\n4 in\n2 2\n2 3\n3 3\n3 2\n1 2 3 4\n' > "$T/nested_hole.poly"
bad 2 nested_hole.poly "chain 2" "inside hole chain 1"
printf '2\n4 out\n0 0\n10 0\n10 10\n0 10\n1 2 3 4\n3 in\n0 5\n3 6\n3 4\n1 2 3\n' > "$T/hole_touching.poly"
bad 2 hole_touching.poly "chain 1 vertex 0" "touches chain 0"
printf '3\n4 out\n0 0\n10 0\n10 10\n0 10\n1 2 3 4\n4 in\n1 1\n1 5\n5 5\n5 1\n1 2 3 4\n4 in\n4 4\n4 8\n8 8\n8 4\n1 2 3 4\n' > "$T/holes_crossing.poly"
bad 2 holes_crossing.poly "chain 2" "chain 1"
printf '1\n3 out\n0 0\n1e999 0\n0 1\n1 2 3\n' > "$T/inf.poly"
bad 2 inf.poly "chain 0" "point 2"
printf '1\n4 out\n0 0\n1 0\n1 0\n0 0\n1 2 3 4\n' > "$T/two_distinct.poly"
bad 2 two_distinct.poly "chain 0" "distinct"
printf '1\n3 in\n0 0\n1 0\n0 1\n1 2 3\n' > "$T/hole_first.poly"
bad 2 hole_first.poly "chain 0"
printf '1\n3 out\n0 0\n1 0\n0 1\n1 1 3\n' > "$T/bad_order.poly"
bad 2 bad_order.poly "chain 0" "permutation"
printf '{"type":"Polygon","coordinates":[[[0,0],[2,0],[1,0],[1,1],[0,0]]]}' > "$T/spike.geojson"
bad 2 spike.geojson "vertex 1"
printf 'POLYGON((0 0, 1 0, x 1, 0 0))' > "$T/bad_point.wkt"
bad 2 bad_point.wkt
printf '{"type":"FeatureCollection","features":[]}' > "$T/no_polygon.geojson"
bad 2 no_polygon.geojson "no polygon"
"$ACD" 2d "$T/missing.poly" > /dev/null 2> "$T/err"; rc=$?
[ $rc = 4 ] || fail "missing file: exit $rc"
grep -q "missing.poly" "$T/err" || fail "missing file not named: $(cat "$T/err")"
echo "ok"
