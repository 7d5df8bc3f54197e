#!/usr/bin/env bash
# acd segment: on the committed torus (144 faces; literal valleys, tau 0.2: the default clamp
# keeps this coarse torus whole, docs/corise.md) the outputs exist and parse (.seg has one
# label per face, labels 0..parts-1; PARTS.obj re-read has all faces; HULLS.obj one group per
# part; JSON has parts and seconds), --verify passes, the run is deterministic; exit codes for
# bad input (2), bad command lines (1); --cage gives a closed genus-1 cage around the 5 parts.
# With the fetched meshes: elephant verifies.
. "$(dirname "$0")/lib.sh"

M="$SRC/tests/data/meshes/torus.off"
"$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --seg "$T/t.seg" --parts "$T/p.obj" -o "$T/h.obj" --json "$T/t.json" --verify \
  > "$T/out.txt" || fail "segment exit $?"
[ "$(wc -l < "$T/t.seg")" = 144 ] || fail ".seg has $(wc -l < "$T/t.seg") lines, 144 faces"
P=$(get parts "$T/t.json")
[ -n "$P" ] && [ "$P" -ge 2 ] || fail "a torus needs at least 2 parts, got '$P'"
[ -n "$(get seconds "$T/t.json")" ] || fail "no seconds in JSON"
grep -q '"volume_ratio"' "$T/t.json" || fail "no volume_ratio"
[ "$(grep -c '"concavity"' "$T/t.json")" = "$P" ] || fail "per-part concavity missing"
MAXL=$(sort -n "$T/t.seg" | tail -1); MINL=$(sort -n "$T/t.seg" | head -1)
[ "$MINL" = 0 ] && [ "$MAXL" = $((P - 1)) ] || fail "labels $MINL..$MAXL for $P parts"
[ "$(sort -u "$T/t.seg" | wc -l)" = "$P" ] || fail "not every part has a face"
[ "$(grep -c '^o part_' "$T/p.obj")" = "$P" ] || fail "PARTS.obj groups"
[ "$(grep -c '^f ' "$T/p.obj")" = 144 ] || fail "PARTS.obj faces"
[ "$(grep -c '^o hull_' "$T/h.obj")" = "$P" ] || fail "HULLS.obj groups"
"$ACD" info "$T/p.obj" --json > /dev/null || fail "PARTS.obj does not read back"
"$ACD" info "$T/h.obj" --json > /dev/null || fail "HULLS.obj does not read back"
"$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --seg "$T/t2.seg" > /dev/null || fail "second run"
cmp -s "$T/t.seg" "$T/t2.seg" || fail "not deterministic"
for th in 1 2 3; do
  "$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --threads $th --seg "$T/t$th.seg" -o "$T/h$th.obj" > /dev/null || fail "--threads $th"
  cmp -s "$T/t.seg" "$T/t$th.seg" || fail "--threads $th: other labels"
  cmp -s "$T/h.obj" "$T/h$th.obj" || fail "--threads $th: other hulls"
done
"$ACD" segment "$M" --threads -1 2> /dev/null; [ $? = 1 ] || fail "--threads -1 accepted"
# --verify names a part that stays deeper than tau (literal valleys at tau 0.05 leave unresolved parts)
"$ACD" segment "$M" -t 0.05 --clamp-hull-depth 0 --verify > /dev/null 2> "$T/v.txt"; rc=$?
[ $rc = 3 ] || fail "--verify on unresolved parts: exit $rc"
grep -q "part [0-9]*" "$T/v.txt" || fail "--verify message: $(cat "$T/v.txt")"

# --cage: the 5 hulls of the literal split expanded and unioned: one closed, oriented surface
# without self-intersections that keeps the torus's hole (genus 1), every mesh vertex inside
"$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --cage "$T/cage.obj" > "$T/cage.txt" 2>&1 || fail "--cage exit $?"
grep -q "cage: .* 0 of 72 vertices outside" "$T/cage.txt" || fail "--cage report: $(grep cage: "$T/cage.txt")"
"$ACD" info "$T/cage.obj" --json > "$T/cage.json" || fail "cage does not read back"
for k in '"closed":[[:space:]]*true' '"oriented":[[:space:]]*true' '"boundary_edges":[[:space:]]*0,' \
         '"self_intersections":[[:space:]]*0,' '"genus":[[:space:]]*1,' '"components":[[:space:]]*1,'; do
  grep -q "$k" "$T/cage.json" || fail "cage: no $k in acd info"
done
"$ACD" segment "$M" --cage "$T/c2.obj" --cage-vertices 3 2> /dev/null; [ $? = 1 ] || fail "--cage-vertices 3 accepted"
"$ACD" segment "$M" --cage "$T/c2.obj" --cage-offset -1 2> /dev/null; [ $? = 1 ] || fail "negative --cage-offset accepted"

# exit codes
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' > "$T/bad.off"
"$ACD" segment "$T/bad.off" 2> "$T/err.txt"; rc=$?
[ $rc = 2 ] || fail "bad index: exit $rc"
grep -q "bad.off" "$T/err.txt" || fail "message does not name the file: $(cat "$T/err.txt")"
"$ACD" segment "$T/missing.off" 2> /dev/null; rc=$?
[ $rc = 4 ] || [ $rc = 2 ] || fail "missing file: exit $rc"
"$ACD" segment "$M" -t -1 2> /dev/null; [ $? = 1 ] || fail "negative tau accepted"
"$ACD" segment "$M" --bogus 2> /dev/null; [ $? = 1 ] || fail "unknown option accepted"
"$ACD" segment 2> /dev/null; [ $? = 1 ] || fail "no input accepted"
"$ACD" segment "$M" --seg 2> /dev/null; [ $? = 1 ] || fail "--seg without a file accepted"
"$ACD" segment "$M" --seg "$T/nodir/x.seg" > /dev/null 2>&1; [ $? = 4 ] || fail "unwritable .seg: not exit 4"

E="$SRC/data/meshes/elephant.off"
if [ -f "$E" ]; then
  "$ACD" segment "$E" --seg "$T/e.seg" --verify > /dev/null || fail "elephant: exit $?"
  [ "$(wc -l < "$T/e.seg")" = 5558 ] || fail "elephant .seg lines"
else
  echo "note: $E absent (bash scripts/fetch-data.sh), elephant part skipped"
fi
echo OK
