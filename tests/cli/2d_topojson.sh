#!/usr/bin/env bash
# acd 2d on TopoJSON: detection, --feature / --object selection (on a committed excerpt of
# world-atlas: South Africa with Lesotho as its hole), the messages of a selector that selects
# nothing, and the real world-atlas file when scripts/fetch-data.sh has fetched it.
. "$(dirname "$0")/lib.sh"
SA=$SRC/fuzz/corpus/topojson/south_africa_110m.json

"$ACD" 2d "$SA" --exact hm > "$T/out" 2> "$T/err" || fail "whole file: $(cat "$T/err")"
grep -q "2 polygons, 103 vertices" "$T/out" || fail "whole file: $(cat "$T/out")"
"$ACD" 2d "$SA" --feature "South Africa" -t 0.2 --verify > "$T/out" 2> "$T/err" || fail "South Africa: $(cat "$T/err")"
grep -q "1 polygon, 92 vertices, .* 1 holes" "$T/out" || fail "South Africa: $(cat "$T/out")"
"$ACD" 2d "$SA" --feature=name=Lesotho --object countries --exact mcd > "$T/out" 2> "$T/err" || fail "Lesotho: $(cat "$T/err")"
grep -q "1 polygon, 11 vertices, .* 0 holes" "$T/out" || fail "Lesotho: $(cat "$T/out")"
"$ACD" 2d "$SA" --format topojson --feature id=426 > "$T/out" 2> "$T/err" || fail "id=426: $(cat "$T/err")"
grep -q "1 polygon, 11 vertices" "$T/out" || fail "id=426: $(cat "$T/out")"

"$ACD" 2d "$SA" --feature Narnia > "$T/out" 2> "$T/err"
[ $? = 2 ] || fail "Narnia: exit not 2"
grep -q "no geometry matches the selector 'Narnia' (3 geometries looked at" "$T/err" || fail "Narnia: $(cat "$T/err")"
"$ACD" 2d "$SA" --object land > "$T/out" 2> "$T/err"
[ $? = 2 ] || fail "--object land: exit not 2"
grep -q "no object named 'land' in objects (it has 'countries')" "$T/err" || fail "land: $(cat "$T/err")"
printf '1\n3 out\n0 0\n1 0\n0 1\n1 2 3\n' > "$T/t.poly"
"$ACD" 2d "$T/t.poly" --feature x > "$T/out" 2> "$T/err"
[ $? != 0 ] || fail "--feature on .poly accepted"
grep -q "GeoJSON and TopoJSON only" "$T/err" || fail ".poly selector: $(cat "$T/err")"

W=$SRC/data/2d/world-atlas/countries-50m.json
if [ -s "$W" ]; then
  "$ACD" 2d "$W" --feature Italy --exact hm --verify > "$T/out" 2> "$T/err" || fail "Italy: $(cat "$T/err")"
  grep -q "2 holes" "$T/out" || fail "Italy: $(cat "$T/out")"
else
  echo "skip: $W not fetched (scripts/fetch-data.sh)"
fi
echo ok
