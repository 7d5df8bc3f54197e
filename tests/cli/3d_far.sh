#!/usr/bin/env bash
# Input far from the origin (docs/acd3d.md "Local frame"): the committed torus moved 1e4, 1e6 and
# 1e8 times its extent (every coordinate + d, rounded as a file written there holds it).
#  - acd 3d --verify passes (default, and --budget 8 --trim-coverage 0.0008); before the local frame,
#    --verify summed volumes about the origin and failed on valid results (fandisk 1e4 extents away:
#    "part 3 has no positive volume");
#  - the hulls are written where the input is (model coordinates), input volume as near (1e-6);
#  - acd segment --verify: the input's volume as near (1e-6; before: summed about the origin,
#    fandisk 1e6 extents away reported hull/mesh 0.00013), and acd info's;
#  - dino and bones (data/meshes, when present) 1e6 extents away: --budget 16 --trim-coverage
#    0.0008 --verify passes, the volume outside the trimmed hulls exact (below);
#  - coordinates that cannot resolve the extent (a cube of side 1e-3 at 1e12, 8 doubles a side):
#    refused, exit 2, naming a vertex.
. "$(dirname "$0")/lib.sh"
M="$SRC/tests/data/meshes/torus.off"
# the torus's coordinates + d (OFF: header, counts, vertices; comments dropped)
move() {
  awk -v d="$1" '
    /^[[:space:]]*#/ || NF == 0 { next }
    n == 0 { print; n = 1; next }
    n == 1 { print; nv = $1; n = 2; next }
    nv > 0 { printf "%.17g %.17g %.17g\n", $1 + d, $2 + d, $3 + d; nv--; next }
    { print }' "$M" > "$2"
}
close_to() { awk -v a="$1" -v b="$2" -v r="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(d <= r * m) }'; }

"$ACD" 3d "$M" --json "$T/near.json" -o "$T/near.obj" > /dev/null 2>&1 || fail "near run: exit $?"
V0=$(get input_volume "$T/near.json")
"$ACD" segment "$M" -t 0.2 --json "$T/snear.json" -o "$T/snear.obj" > /dev/null 2>&1 || fail "near segment: exit $?"
S0=$(get mesh_volume "$T/snear.json")
E=5 # the torus's largest side (R 1.5 + r 1 each way)
for ratio in 1e4 1e6 1e8; do
  d=$(awk -v r="$ratio" -v e="$E" 'BEGIN { printf "%.17g", r * e }')
  move "$d" "$T/far.off"
  "$ACD" 3d "$T/far.off" --verify --json "$T/far.json" -o "$T/far.obj" > "$T/out" 2> "$T/err" ||
    fail "$ratio extents: acd 3d --verify exit $?: $(grep -v '(.*s)$' "$T/err" | tail -1)"
  V=$(get input_volume "$T/far.json")
  close_to "$V" "$V0" 1e-6 || fail "$ratio extents: input volume $V, near $V0"
  X=$(awk '$1 == "v" { print $2; exit }' "$T/far.obj")
  awk -v x="$X" -v d="$d" 'BEGIN { exit !(x > d - 10 && x < d + 10) }' || fail "$ratio extents: hull vertex x $X, not near $d"
  "$ACD" 3d "$T/far.off" --budget 8 --trim-coverage 0.0008 --verify -o "$T/farb.obj" > /dev/null 2> "$T/err" ||
    fail "$ratio extents: --budget 8 --trim-coverage 0.0008 --verify exit $?: $(grep -v '(.*s)$' "$T/err" | tail -1)"
  "$ACD" segment "$T/far.off" -t 0.2 --verify --json "$T/sfar.json" -o "$T/sfar.obj" > /dev/null 2> "$T/err" ||
    fail "$ratio extents: acd segment --verify exit $?: $(tail -1 "$T/err")"
  S=$(get mesh_volume "$T/sfar.json")
  close_to "$S" "$S0" 1e-6 || fail "$ratio extents: segment's mesh volume $S, near $S0"
  I=$("$ACD" info "$T/far.off" | awk '$1 == "volume" { print $2 }')
  close_to "$I" "$S0" 1e-6 || fail "$ratio extents: acd info volume $I, near $S0"
done

# The budget + trim runs that failed --verify 1e6 extents away (docs/results/3d-far.md): a part the
# rounding back to model coordinates pinched made the exact cut of --verify's volume outside a
# trimmed hull fail, and the bound replacing it counts a region beyond two planes twice (dino: exit
# 3, "up to 0.00234" against 0.0008 x 2.457; bones, a mesh crossing itself: exit 2 where near it
# only warned). Now the volume is taken tetrahedron by tetrahedron there (geom3/hull_outside):
# exit 0, the exact value within the limit. On the data meshes when present.
move_data() { # FILE RATIO OUT: every coordinate + RATIO x the largest side of the box
  awk -v r="$2" '
    /^[[:space:]]*#/ || NF == 0 { next }
    n == 0 { n = 1; next }
    n == 1 { nv = $1; n = 2; next }
    n == 2 && nv > 0 { for (k = 1; k <= 3; k++) { x = $k + 0; if (!(k in lo) || x < lo[k]) lo[k] = x; if (!(k in hi) || x > hi[k]) hi[k] = x }; nv-- }
    END { e = 0; for (k = 1; k <= 3; k++) if (hi[k] - lo[k] > e) e = hi[k] - lo[k]; printf "%.17g\n", r * e }' "$1" > "$T/d"
  awk -v d="$(cat "$T/d")" '
    /^[[:space:]]*#/ || NF == 0 { next }
    n == 0 { print "OFF"; n = 1; next }
    n == 1 { print; nv = $1; n = 2; next }
    nv > 0 { printf "%.17g %.17g %.17g\n", $1 + d, $2 + d, $3 + d; nv--; next }
    { print }' "$1" > "$3" # (COFF's colours dropped)
}
for name in dino bones; do
  F="$SRC/data/meshes/$name.off"
  [ -f "$F" ] || { echo "note: $F missing, its far budget + trim run skipped"; continue; }
  move_data "$F" 1e6 "$T/$name.far.off"
  "$ACD" 3d "$T/$name.far.off" --budget 16 --trim-coverage 0.0008 --verify -v -o "$T/$name.obj" > /dev/null 2> "$T/err" ||
    fail "$name 1e6 extents: --budget 16 --trim-coverage 0.0008 --verify exit $?: $(grep -v '(.*s)$' "$T/err" | tail -1)"
  grep -q "outside the trimmed hulls (exact; limit 0.0008)" "$T/err" || fail "$name: $(grep verified "$T/err")"
done

# a cube of side 1e-3 at 1e12: 8 doubles a side
cat > "$T/farcube.off" <<'EOF_OFF'
OFF
8 12 0
1000000000000 1000000000000 1000000000000
1000000000000.001 1000000000000 1000000000000
1000000000000 1000000000000.001 1000000000000
1000000000000.001 1000000000000.001 1000000000000
1000000000000 1000000000000 1000000000000.001
1000000000000.001 1000000000000 1000000000000.001
1000000000000 1000000000000.001 1000000000000.001
1000000000000.001 1000000000000.001 1000000000000.001
3 0 2 1
3 1 2 3
3 4 5 6
3 5 7 6
3 0 1 5
3 0 5 4
3 2 6 7
3 2 7 3
3 0 4 6
3 0 6 2
3 1 3 7
3 1 7 5
EOF_OFF
"$ACD" info "$T/farcube.off" | grep -q "^closed *yes" || fail "the far cube is not closed"
"$ACD" 3d "$T/farcube.off" --verify -o "$T/fc.obj" > /dev/null 2> "$T/err"
rc=$?
[ $rc = 2 ] || fail "far cube: exit $rc, want 2 (refused): $(tail -1 "$T/err")"
grep -q "cannot resolve" "$T/err" && grep -q "vertex" "$T/err" || fail "far cube: message $(tail -1 "$T/err")"
echo "ok"
