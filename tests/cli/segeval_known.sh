#!/usr/bin/env bash
# acd segeval on a strip of 4 unit squares (8 triangles) with hand-worked values (docs/segeval.md):
# A cuts at x = 2, B at x = 1: RI = 4/7, Rm = Rf = HD = 1/4, GCE = 1/4, LCE = 1/8,
# DCD both ways 1, CD = 2/avg_radius with avg_radius = (sqrt5+sqrt17+sqrt65+sqrt101)/24.
# Identical segmentations give 0 everywhere; a reference directory is averaged; errors and
# exit codes.
. "$(dirname "$0")/lib.sh"

{
  echo OFF
  echo "10 8 0"
  for y in 0 1; do for x in 0 1 2 3 4; do echo "$x $y 0"; done; done
  for x in 0 1 2 3; do
    echo "3 $x $((x + 1)) $((x + 6))"
    echo "3 $x $((x + 6)) $((x + 5))"
  done
} > "$T/strip.off"
printf '0\n0\n0\n0\n1\n1\n1\n1\n' > "$T/a.seg"
printf '5\n5\n9\n9\n9\n9\n9\n9\n' > "$T/b.seg"

"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/b.seg" --json > "$T/ab.json" || fail "exit $?"
near "$(get rand_index "$T/ab.json")" "$(awk 'BEGIN { printf "%.17g", 4/7 }')" 1e-9 || fail "rand index"
near "$(get hamming "$T/ab.json")" 0.25 1e-9 || fail "hamming"
near "$(get hamming_rm "$T/ab.json")" 0.25 1e-9 || fail "rm"
near "$(get hamming_rf "$T/ab.json")" 0.25 1e-9 || fail "rf"
near "$(get gce "$T/ab.json")" 0.25 1e-9 || fail "gce"
near "$(get lce "$T/ab.json")" 0.125 1e-9 || fail "lce"
CD=$(awk 'BEGIN { printf "%.17g", 48 / (sqrt(5) + sqrt(17) + sqrt(65) + sqrt(101)) }')
near "$(get cut_discrepancy "$T/ab.json")" "$CD" 1e-9 || fail "cut discrepancy $(get cut_discrepancy "$T/ab.json") vs $CD"
grep -q '"weights":[[:space:]]*"area"' "$T/ab.json" || fail "weights key"

# face weighting: same values here (equal areas)
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/b.seg" --json --weights faces > "$T/abf.json" || fail "faces exit"
near "$(get gce "$T/abf.json")" 0.25 1e-9 || fail "faces gce"

# identical: exact zeros, RI 1
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/a.seg" --json > "$T/aa.json" || fail "aa exit"
near "$(get rand_index "$T/aa.json")" 1 1e-9 || fail "aa ri"
for k in hamming gce lce cut_discrepancy; do near "$(get $k "$T/aa.json")" 0 1e-9 || fail "aa $k"; done

# a directory of references: both files, mean of (A,A) and (A,B)
mkdir "$T/refs"
cp "$T/a.seg" "$T/refs/1.seg"; cp "$T/b.seg" "$T/refs/2.seg"; echo junk > "$T/refs/readme.txt"
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/refs" --json > "$T/dir.json" || fail "dir exit"
grep -q '"references":[[:space:]]*2' "$T/dir.json" || fail "dir count"
MEAN=$(sed -n '/"mean"/,$p' "$T/dir.json" > "$T/mean.json"; get gce "$T/mean.json")
near "$MEAN" 0.125 1e-9 || fail "dir mean gce $MEAN"

# text output names the metrics
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/b.seg" > "$T/ab.txt" || fail "text exit"
for w in "rand index" hamming gce lce "cut discrepancy"; do grep -q "$w" "$T/ab.txt" || fail "text lacks $w"; done

# no cut in A: CD undefined (null in JSON)
printf '3\n3\n3\n3\n3\n3\n3\n3\n' > "$T/one.seg"
"$ACD" segeval "$T/strip.off" "$T/one.seg" "$T/b.seg" --json > "$T/one.json" || fail "one exit"
grep -q '"cut_discrepancy":[[:space:]]*null' "$T/one.json" || fail "undefined CD not null"

# errors: wrong count (exit 2), non-integer with its line (exit 2), missing file (exit 4), usage (exit 1)
printf '0\n1\n' > "$T/short.seg"
"$ACD" segeval "$T/strip.off" "$T/short.seg" "$T/b.seg" 2> "$T/err" >/dev/null; rc=$?
[ $rc = 2 ] || fail "short exit $rc"
grep -q "2 labels, but the mesh has 8 faces" "$T/err" || fail "short message: $(cat "$T/err")"
printf '0\n0\n0\nx1\n1\n1\n1\n1\n' > "$T/bad.seg"
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/bad.seg" 2> "$T/err" >/dev/null; rc=$?
[ $rc = 2 ] || fail "bad exit $rc"
grep -q "bad.seg:4:" "$T/err" || fail "bad message: $(cat "$T/err")"
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/missing.seg" 2>/dev/null >/dev/null; rc=$?
[ $rc = 4 ] || fail "missing exit $rc"
"$ACD" segeval "$T/strip.off" "$T/a.seg" 2>/dev/null >/dev/null; rc=$?
[ $rc = 1 ] || fail "usage exit $rc"
"$ACD" segeval "$T/strip.off" "$T/a.seg" "$T/b.seg" --weights volume 2>/dev/null >/dev/null; rc=$?
[ $rc = 1 ] || fail "bad weights exit $rc"
"$ACD" segeval --help | grep -q "usage: acd segeval" || fail "help"
echo "segeval_known: ok"
