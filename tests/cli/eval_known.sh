#!/usr/bin/env bash
# acd eval on decompositions with known answers: a cube scored against itself, split in two
# (one o group each), and against a hull missing half of it; JSON keys; errors and exit codes.
. "$(dirname "$0")/lib.sh"

# box X0 X1 Y0 Y1 Z0 Z1 OFFSET: 8 vertices and 12 triangles (indices from OFFSET+1)
box() {
  local x0=$1 x1=$2 y0=$3 y1=$4 z0=$5 z1=$6 o=$7
  printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $x0 $y0 $z0 $x1 $y0 $z0 $x1 $y1 $z0 $x0 $y1 $z0
  printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $x0 $y0 $z1 $x1 $y0 $z1 $x1 $y1 $z1 $x0 $y1 $z1
  for f in "1 3 2" "1 4 3" "5 6 7" "5 7 8" "1 2 6" "1 6 5" "3 4 8" "3 8 7" "2 3 7" "2 7 6" "1 5 8" "1 8 4"; do
    set -- $f
    echo "f $(($1 + o)) $(($2 + o)) $(($3 + o))"
  done
}
box 0 1 0 1 0 1 0 > "$T/cube.obj"
{ echo "o left"; box 0 0.5 0 1 0 1 0; echo "o right"; box 0.5 1 0 1 0 1 8; } > "$T/halves.obj"
{ echo "g left"; box 0 0.5 0 1 0 1 0; } > "$T/half.obj"

"$ACD" eval "$T/cube.obj" "$T/cube.obj" --json --samples 64000 --surface-samples 20000 > "$T/self.json" || fail "self exit $?"
for k in parts hull_vertices mesh_volume hull_volume_sum union_volume iou coverage excess distance \
         mesh_to_hulls_max mesh_to_hulls_mean hulls_to_mesh_max hulls_to_mesh_mean concavity_max samples seed seconds; do
  grep -q "\"$k\"" "$T/self.json" || fail "key $k missing"
done
near "$(get iou "$T/self.json")" 1 0 || fail "self iou"
near "$(get concavity_max "$T/self.json")" 0 1e-12 || fail "self concavity"
[ "$(get parts "$T/self.json")" = 1 ] || fail "self parts"

"$ACD" eval "$T/cube.obj" "$T/halves.obj" --json --samples 64000 --surface-samples 20000 > "$T/halves.json" || fail "halves exit"
[ "$(get parts "$T/halves.json")" = 2 ] || fail "halves parts"
[ "$(get hull_vertices "$T/halves.json")" = 16 ] || fail "halves hull vertices"
near "$(get iou "$T/halves.json")" 1 0 || fail "halves iou"
near "$(get hulls_to_mesh_max "$T/halves.json")" 0 1e-12 || fail "shared face counted as boundary"

"$ACD" eval "$T/cube.obj" "$T/half.obj" --json --samples 64000 --surface-samples 20000 -o "$T/half.json" || fail "half exit"
near "$(get coverage "$T/half.json")" 0.5 0 || fail "half coverage"
near "$(get excess "$T/half.json")" 0 0 || fail "half excess"
near "$(get mesh_to_hulls_max "$T/half.json")" 0.28867513459481287 1e-12 || fail "half mesh_to_hulls_max"

# determinism: the same report twice except the time
"$ACD" eval "$T/cube.obj" "$T/half.obj" --json --samples 64000 --surface-samples 20000 | grep -v seconds > "$T/a"
"$ACD" eval "$T/cube.obj" "$T/half.obj" --json --samples 64000 --surface-samples 20000 | grep -v seconds > "$T/b"
cmp -s "$T/a" "$T/b" || fail "not deterministic"

# text output
"$ACD" eval "$T/cube.obj" "$T/halves.obj" --samples 1000 --surface-samples 1000 | grep -q "^iou" || fail "text report"

# errors: usage 1, bad input 2, missing file 4
"$ACD" eval "$T/cube.obj" > /dev/null 2>&1; [ $? = 1 ] || fail "missing argument exit"
"$ACD" eval "$T/cube.obj" "$T/half.obj" --samples x > /dev/null 2>&1; [ $? = 1 ] || fail "bad number exit"
"$ACD" eval "$T/cube.obj" "$T/half.obj" --bogus > /dev/null 2>&1; [ $? = 1 ] || fail "unknown option exit"
"$ACD" eval "$T/nothere.obj" "$T/half.obj" > /dev/null 2>&1; [ $? = 4 ] || fail "missing file exit"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' > "$T/bad.obj"
"$ACD" eval "$T/cube.obj" "$T/bad.obj" 2> "$T/err" > /dev/null; [ $? = 2 ] || fail "bad decomposition exit"
printf 'o flat\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$T/flat.obj"
"$ACD" eval "$T/cube.obj" "$T/flat.obj" 2> "$T/err" > /dev/null; [ $? = 2 ] || fail "flat decomposition exit"
grep -q "solid" "$T/err" || fail "flat decomposition message: $(cat "$T/err")"
echo "eval_known: ok"
