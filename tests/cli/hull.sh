#!/usr/bin/env bash
# acd hull: a cube with interior, face and duplicate points -> 8 vertices, 12 triangles, volume 1,
# written OBJ re-read by acd info; per-part hulls; planar and collinear input; errors and exit codes.
. "$(dirname "$0")/lib.sh"

{
  for x in 0 1; do for y in 0 1; do for z in 0 1; do echo "v $x $y $z"; done; done; done
  echo "v 0.5 0.5 0.5"; echo "v 0.25 0.5 1"; echo "v 1 1 1"; echo "v 0.1 0.2 0.3"
  echo "f 1 2 3"
} > "$T/cloud.obj"
"$ACD" hull "$T/cloud.obj" -o "$T/hull.obj" --json > "$T/h.json" || fail "hull exit $?"
[ "$(get vertices "$T/h.json")" = 8 ] || fail "vertices $(cat "$T/h.json")"
[ "$(get triangles "$T/h.json")" = 12 ] || fail "triangles"
[ "$(get dimension "$T/h.json")" = 3 ] || fail "dimension"
near "$(get volume "$T/h.json")" 1 1e-12 || fail "volume"
near "$(get area "$T/h.json")" 6 1e-12 || fail "area"
[ "$(grep -c '^v ' "$T/hull.obj")" = 8 ] || fail "written vertices"
[ "$(grep -c '^f ' "$T/hull.obj")" = 12 ] || fail "written faces"
"$ACD" info "$T/hull.obj" --json > "$T/i.json" || fail "info on the hull"
near "$(get volume "$T/i.json")" 1 1e-12 || fail "re-read volume $(get volume "$T/i.json")"
grep -q '"closed":[[:space:]]*true' "$T/i.json" || fail "hull not closed"
grep -q '"oriented":[[:space:]]*true' "$T/i.json" || fail "hull not oriented"

# full precision: a coordinate that needs 17 digits survives the round trip
printf 'v 0.1 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0.30000000000000004\n' > "$T/tet.obj"
"$ACD" hull "$T/tet.obj" -o "$T/tet_hull.obj" > /dev/null || fail "tet"
grep -q '0.30000000000000004' "$T/tet_hull.obj" || fail "precision lost"

# parts: one hull per o group
{ echo "o a"; printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n'
  echo "o b"; printf 'v 5 0 0\nv 7 0 0\nv 5 2 0\nv 5 0 2\nf 5 7 6\nf 5 6 8\nf 6 7 8\nf 5 8 7\n'; } > "$T/two.obj"
"$ACD" hull "$T/two.obj" --parts -o "$T/two_hull.obj" --json > "$T/p.json" || fail "parts exit"
[ "$(get parts "$T/p.json")" = 2 ] || fail "parts count"
near "$(get volume_sum "$T/p.json")" "$(awk 'BEGIN{print 1/6 + 8/6}')" 1e-12 || fail "parts volume"
[ "$(grep -c '^o ' "$T/two_hull.obj")" = 2 ] || fail "parts groups"

# degenerate: coplanar square -> dimension 2, collinear -> 1
printf 'v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nv 0.5 0.5 2\n' > "$T/flat.obj"
"$ACD" hull "$T/flat.obj" --json > "$T/f.json" || fail "flat exit"
[ "$(get dimension "$T/f.json")" = 2 ] || fail "flat dimension"
near "$(get area "$T/f.json")" 1 1e-12 || fail "flat area"
printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\n' > "$T/line.obj"
"$ACD" hull "$T/line.obj" --json > "$T/l.json" || fail "line exit"
[ "$(get dimension "$T/l.json")" = 1 ] || fail "line dimension"

# errors
"$ACD" hull > /dev/null 2>&1; [ $? = 1 ] || fail "no argument"
"$ACD" hull "$T/cloud.obj" --bogus > /dev/null 2>&1; [ $? = 1 ] || fail "bad option"
"$ACD" hull "$T/missing.obj" > /dev/null 2>&1; [ $? = 4 ] || fail "missing file"
printf 'v 0 0 nan\nv 1 0 0\nv 0 1 0\nv 0 0 1\n' > "$T/nan.obj"
"$ACD" hull "$T/nan.obj" > /dev/null 2>&1; [ $? = 2 ] || fail "nan input"
"$ACD" hull --help | grep -q "usage: acd hull" || fail "help"
echo "hull CLI ok"
