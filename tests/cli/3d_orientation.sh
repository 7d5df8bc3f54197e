#!/usr/bin/env bash
# acd 3d and acd info --repair on inputs oriented as a whole or in parts against their nesting
# (bench/audit_3d_transforms.py, docs/results/3d-robustness.md): an inside-out closed mesh is
# repaired and decomposed (it was refused as "flat or oriented inward"); a cavity keeps facing
# inward through repair (it was turned outward: a solid inside a solid, volume counted twice).
. "$(dirname "$0")/lib.sh"
# box(x0 y0 z0 x1 y1 z1 first_index inward): an axis-aligned box as OBJ (first_index: the OBJ index of its first vertex)
box() {
  local x0=$1 y0=$2 z0=$3 x1=$4 y1=$5 z1=$6 b=$7 in=$8
  for z in $z0 $z1; do for y in $y0 $y1; do for x in $x0 $x1; do echo "v $x $y $z"; done; done; done
  # corners: index = b + x + 2y + 4z; outward faces
  while read -r p q r; do
    if [ "$in" = 1 ]; then echo "f $((b + p)) $((b + r)) $((b + q))"; else echo "f $((b + p)) $((b + q)) $((b + r))"; fi
  done <<'F'
0 2 3
0 3 1
4 5 7
4 7 6
0 1 5
0 5 4
2 6 7
2 7 3
0 4 6
0 6 2
1 3 7
1 7 5
F
}
# a 2 x 1 x 1 box written inside out: every face reversed
box 0 0 0 2 1 1 1 1 > "$T/inside_out.obj"
"$ACD" 3d "$T/inside_out.obj" --verify --json "$T/io.json" > "$T/io.out" 2> "$T/io.err" || fail "inside-out box: exit $? $(cat "$T/io.err")"
grep -q "the input is inside out (signed volume -2)" "$T/io.err" || fail "inside-out message: $(cat "$T/io.err")"
grep -q "12 faces flipped" "$T/io.err" || fail "inside-out flips: $(cat "$T/io.err")"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert abs(d['input_volume']-2)<1e-12, d['input_volume']" "$T/io.json" ||
  fail "inside-out volume"
# with --no-close-holes it is refused as before (exit 2, naming the orientation)
"$ACD" 3d "$T/inside_out.obj" --no-close-holes > /dev/null 2> "$T/io.err"; rc=$?
[ $rc = 2 ] || fail "inside-out --no-close-holes: exit $rc"
grep -q "oriented inward" "$T/io.err" || fail "inside-out --no-close-holes message: $(cat "$T/io.err")"
# a box of side 3 with a unit cube cavity, both shells reversed (the whole model inside out):
# repaired to the outer shell outward, the cavity inward, volume 27 - 1 = 26
{ box 0 0 0 3 3 3 1 1; box 1 1 1 2 2 2 9 0; } > "$T/cavity.obj"
"$ACD" 3d "$T/cavity.obj" --verify --json "$T/cav.json" > /dev/null 2> "$T/cav.err" || fail "cavity: exit $? $(cat "$T/cav.err")"
grep -q "1 closed part(s) inside others kept as cavities" "$T/cav.err" || fail "cavity message: $(cat "$T/cav.err")"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert abs(d['input_volume']-26)<1e-12, d['input_volume']" "$T/cav.json" ||
  fail "cavity volume (26 expected)"
# the same model with both shells outward (as a soup writer may give it): acd info --repair
# turns the inner shell inward (a cavity), it does not leave two nested solids (volume 28)
{ box 0 0 0 3 3 3 1 0; box 1 1 1 2 2 2 9 0; } > "$T/nested.obj"
"$ACD" info "$T/nested.obj" --json --repair "$T/rep.obj" > "$T/rep.json" || fail "info --repair exit $?"
python3 - "$T/rep.json" <<'PY' || fail "repaired cavity: $(cat "$T/rep.json")"
import json, sys
d = json.load(open(sys.argv[1]))
assert abs(d["volume"] - 26) < 1e-12, d["volume"]
assert d["repair"]["cavities"] == 1 and d["repair"]["faces_flipped"] == 12, d["repair"]
PY
# acd 3d on that file (closed, consistently oriented, positive volume: decomposed as given, a
# solid inside a solid) warns that the inner shell faces against the nesting; the cavity model
# oriented right gets no warning
"$ACD" 3d "$T/nested.obj" > /dev/null 2> "$T/n.err" || fail "nested: exit $? $(cat "$T/n.err")"
grep -q "warning: 12 faces are oriented against the nesting of the closed shells" "$T/n.err" || fail "nested warning: $(cat "$T/n.err")"
"$ACD" 3d "$T/rep.obj" > /dev/null 2> "$T/r.err" || fail "repaired cavity: exit $? $(cat "$T/r.err")"
grep -q "warning" "$T/r.err" && fail "warning on a correctly oriented cavity: $(cat "$T/r.err")"
echo ok
