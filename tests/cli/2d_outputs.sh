#!/usr/bin/env bash
# acd 2d outputs: --json (all documented keys; components counterclockwise, first point not
# repeated; parses with python3 -m json.tool), --json - on stdout, -o .geojson/.json/.poly that
# read back, --svg (well-formed XML with one path per component); every polygon of a
# multi-polygon input is decomposed; -v reports normalization fixes.
. "$(dirname "$0")/lib.sh"
command -v python3 > /dev/null || { echo "skip: python3 missing"; exit 77; }
printf '1\n6 out\n0 0\n2 0\n2 1\n1 1\n1 2\n0 2\n1 2 3 4 5 6\n' > "$T/L.poly"

"$ACD" 2d "$T/L.poly" --json "$T/r.json" -o "$T/c.geojson" --svg "$T/p.svg" > "$T/out" || fail "exit $?"
python3 -m json.tool "$T/r.json" > /dev/null || fail "JSON report does not parse"
python3 -m json.tool "$T/c.geojson" > /dev/null || fail "GeoJSON does not parse"
python3 - "$T/r.json" <<'PY' || fail "JSON content"
import json, sys
d = json.load(open(sys.argv[1]))
for k in ["tau", "measure", "input", "components", "hulls", "cuts", "tree", "stats"]:
    assert k in d, k
for k in ["vertices", "notches", "holes"]:
    assert k in d["input"], k
assert d["input"]["vertices"] == 6 and d["input"]["notches"] == 1 and d["input"]["holes"] == 0
for k in ["components", "max_concavity", "seconds"]:
    assert k in d["stats"], k
comps = d["components"]
assert len(comps) == d["stats"]["components"] == 2
area = 0
for c in comps:
    assert c[0] != c[-1], "first point repeated"
    a = sum(c[i][0] * c[(i + 1) % len(c)][1] - c[(i + 1) % len(c)][0] * c[i][1] for i in range(len(c))) / 2
    assert a > 0, "clockwise component"
    area += a
assert abs(area - 3) < 1e-12, area
assert len(d["hulls"]) == 2 and len(d["cuts"]) == 1
assert len(d["cuts"][0]) == 2 and len(d["cuts"][0][0]) == 2
tree = d["tree"][0]
assert tree[0]["parent"] == -1 and len(tree[0]["children"]) == 2
assert sorted(n["component"] for n in tree if n["component"] >= 0) == [0, 1]
PY
python3 - "$T/p.svg" <<'PY' || fail "SVG"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
ns = "{http://www.w3.org/2000/svg}"
groups = {g.get("id"): g for g in root.iter(ns + "g") if g.get("id")}
assert len(groups["components"].findall(ns + "path")) == 2
assert len(groups["hulls"].findall(ns + "path")) == 2
assert len(groups["cuts"].findall(ns + "line")) == 1
assert len(groups["input"].findall(ns + "path")) == 1
PY
# the components read back: GeoJSON and .poly
"$ACD" 2d "$T/c.geojson" > "$T/out2" || fail "GeoJSON output does not read back"
grep -q "2 polygons, 8 vertices" "$T/out2" || fail "GeoJSON read back: $(cat "$T/out2")"
"$ACD" 2d "$T/L.poly" -o "$T/c.poly" > /dev/null || fail "-o .poly"
"$ACD" 2d "$T/c.poly" > "$T/out3" || fail ".poly output does not read back"
grep -q "2 polygons, 8 vertices" "$T/out3" || fail ".poly read back: $(cat "$T/out3")"
"$ACD" 2d "$T/L.poly" -o "$T/c.json" > /dev/null && python3 -m json.tool "$T/c.json" > /dev/null || fail "-o .json"
# JSON on stdout; the summary then goes to stderr
"$ACD" 2d "$T/L.poly" --json - 2> "$T/err" | python3 -m json.tool > /dev/null || fail "--json - does not parse"
grep -q "2 components" "$T/err" || fail "summary not on stderr with --json -"

# every polygon of a FeatureCollection (one with a hole) is decomposed
cat > "$T/fc.geojson" <<'GJ'
{"type": "FeatureCollection", "features": [
 {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
  "coordinates": [[[0,0],[4,0],[4,4],[0,4],[0,0]], [[1,1],[1,3],[3,3],[3,1],[1,1]]]}},
 {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon",
  "coordinates": [[[[10,0],[12,0],[12,1],[11,1],[11,2],[10,2],[10,0]]], [[[20,0],[21,0],[21,1],[20,1],[20,0]]]]}}]}
GJ
"$ACD" 2d "$T/fc.geojson" --verify --json "$T/fc.json" > "$T/out" || fail "FeatureCollection exit $?: $(cat "$T/out")"
grep -q "3 polygons, 18 vertices" "$T/out" || fail "FeatureCollection summary: $(cat "$T/out")"
python3 - "$T/fc.json" <<'PY' || fail "FeatureCollection JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["input"]["holes"] == 1 and len(d["polygons"]) == 3 and len(d["tree"]) == 3
n = [p["components"] for p in d["polygons"]]
assert n[0] >= 2 and n[1] == 2 and n[2] == 1, n
assert sum(n) == len(d["components"])
area = 0
for c in d["components"]:
    area += sum(c[i][0] * c[(i + 1) % len(c)][1] - c[(i + 1) % len(c)][0] * c[i][1] for i in range(len(c))) / 2
assert abs(area - (12 + 3 + 1)) < 1e-9, area
assert d["verify"]["passed"] is True
PY

# a .poly file with two outer chains, the first with a hole: both decomposed
printf '3\n4 out\n0 0\n4 0\n4 4\n0 4\n1 2 3 4\n4 in\n1 1\n1 3\n3 3\n3 1\n1 2 3 4\n6 out\n10 0\n12 0\n12 1\n11 1\n11 2\n10 2\n1 2 3 4 5 6\n' > "$T/two.poly"
"$ACD" 2d "$T/two.poly" --verify --json "$T/two.json" > "$T/out" || fail "two outer chains: exit $?"
grep -q "2 polygons, 14 vertices" "$T/out" || fail "two outer chains: $(cat "$T/out")"
python3 - "$T/two.json" <<'PY' || fail "two outer chains JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["input"]["holes"] == 1 and len(d["polygons"]) == 2
assert d["polygons"][1]["first_component"] == d["polygons"][0]["components"]
PY

# -v reports normalization fixes: a clockwise ring with a repeated vertex
printf '{"type":"Polygon","coordinates":[[[0,0],[0,1],[1,1],[1,1],[1,0],[0,0]]]}' > "$T/fix.geojson"
"$ACD" 2d "$T/fix.geojson" -v > /dev/null 2> "$T/err" || fail "-v exit $?"
grep -q "dropped 2 repeated vertices, reversed 1 rings" "$T/err" || fail "-v: $(cat "$T/err")"
grep -q "polygon 0: 4 vertices" "$T/err" || fail "-v per polygon: $(cat "$T/err")"
# unwritable outputs: exit 4
"$ACD" 2d "$T/L.poly" --svg /nonexistent-dir/p.svg > /dev/null 2> "$T/err"; rc=$?
[ $rc = 4 ] || fail "unwritable svg exit $rc"
"$ACD" 2d "$T/L.poly" --json /nonexistent-dir/r.json > /dev/null 2> "$T/err"; rc=$?
[ $rc = 4 ] || fail "unwritable json exit $rc"
echo "ok"
