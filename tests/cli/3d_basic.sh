#!/usr/bin/env bash
# acd 3d: outputs, --verify, JSON, and bad input exit codes.
. "$(dirname "$0")/lib.sh"
# an L-shaped prism (closed, outward) written as OBJ
cat > "$T/l.obj" <<'OBJ'
v 0 0 0
v 4 0 0
v 4 2 0
v 2 2 0
v 2 4 0
v 0 4 0
v 0 0 1
v 4 0 1
v 4 2 1
v 2 2 1
v 2 4 1
v 0 4 1
f 1 3 2
f 1 4 3
f 1 6 4
f 4 6 5
f 7 8 9
f 7 9 10
f 7 10 12
f 10 11 12
f 1 2 8
f 1 8 7
f 2 3 9
f 2 9 8
f 3 4 10
f 3 10 9
f 4 5 11
f 4 11 10
f 5 6 12
f 5 12 11
f 6 1 7
f 6 7 12
OBJ
"$ACD" 3d "$T/l.obj" -t 0 --tau-abs -o "$T/h.obj" --parts "$T/p.obj" --json "$T/r.json" --verify > "$T/out.txt" || fail "3d exit $?"
grep -q "^2 parts" "$T/out.txt" || fail "L prism should give 2 parts: $(cat "$T/out.txt")"
[ "$(grep -c '^o hull_' "$T/h.obj")" = 2 ] || fail "hull groups"
[ "$(grep -c '^o part_' "$T/p.obj")" = 2 ] || fail "part groups"
python3 - "$T/r.json" <<'PY' || fail "json"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["stats"]["parts"] == 2 and len(d["parts"]) == 2
assert abs(sum(p["volume"] for p in d["parts"]) - d["input_volume"]) <= 1e-9 * d["input_volume"]
assert d["tree"][0]["parent"] == -1 and len(d["tree"][0]["children"]) == 2
PY
# exports for simulators
"$ACD" 3d "$T/l.obj" -t 0 --tau-abs --export "$T/x" --name lprism > /dev/null || fail "export exit $?"
for f in decomposition.obj summary.json lprism.urdf lprism.xml; do [ -s "$T/x/$f" ] || fail "export: $f missing"; done
[ "$(grep -c '<collision' "$T/x/lprism.urdf")" = 2 ] || fail "urdf collisions"
python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/x/summary.json" || fail "summary json"
# an open mesh in solid mode: its hole is closed (notice on stderr) and the closed L decomposed,
# volume 12 conserved; with --no-close-holes: exit 2 with a message naming the problem
head -n 31 "$T/l.obj" > "$T/open.obj"
"$ACD" 3d "$T/open.obj" -t 0 --tau-abs --verify --json "$T/o.json" > "$T/o.txt" 2> "$T/err.txt" || fail "open mesh exit $?"
grep -q "^2 parts" "$T/o.txt" || fail "closed L should give 2 parts: $(cat "$T/o.txt")"
grep -q "1 holes closed with 1 faces" "$T/err.txt" || fail "repair notice: $(cat "$T/err.txt")"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert abs(d['input_volume']-12)<1e-12, d['input_volume']" "$T/o.json" || fail "closed volume"
"$ACD" 3d "$T/open.obj" --no-close-holes 2> "$T/err.txt"; rc=$?
[ $rc = 2 ] || fail "open mesh with --no-close-holes exit $rc"
grep -q "closed" "$T/err.txt" || fail "open mesh message: $(cat "$T/err.txt")"
# a third face on an edge cannot be repaired: exit 2, saying so
{ cat "$T/l.obj"; echo "f 1 2 11"; } > "$T/nm.obj"
"$ACD" 3d "$T/nm.obj" 2> "$T/err.txt"; rc=$?
[ $rc = 2 ] || fail "non-manifold exit $rc"
grep -q "could not be closed" "$T/err.txt" || fail "non-manifold message: $(cat "$T/err.txt")"
# missing file -> 4, bad option -> 1, garbage -> 2
"$ACD" 3d "$T/nope.obj" 2>/dev/null; [ $? = 4 ] || fail "missing file"
"$ACD" 3d "$T/l.obj" -t abc 2>/dev/null; [ $? = 1 ] || fail "bad tau"
printf 'v 0 0 0\nf 1 2 3\n' > "$T/bad.obj"
"$ACD" 3d "$T/bad.obj" 2>/dev/null; [ $? = 2 ] || fail "bad indices"
# surface mode takes the open mesh, and the parts tile it
"$ACD" 3d "$T/open.obj" --mode surface -t 0 --tau-abs --verify --parts "$T/sp.obj" > "$T/s.txt" || fail "surface mode exit $?"
[ "$(grep -c '^f ' "$T/sp.obj")" = 19 ] || fail "surface parts should hold the 19 faces"
# a closed part carrying a sliver that every plane separates again is still split within tau
"$ACD" 3d "$SRC/tests/data/meshes/sliver_part.off" -t 0.5 --tau-abs --verify --json "$T/s.json" >"$T/s.out" 2>"$T/s.err" ||
  fail "sliver part: exit $? $(cat "$T/s.err")"
grep -q '"no_cut"' "$T/s.json" && fail "sliver part: a part stayed above tau"
# hull tightness options (docs/acd3d.md "Hull tightness"): --verify passes with them, and the
# merge stops at --merge-parts; bad values are usage errors (exit 1)
"$ACD" 3d "$SRC/tests/data/meshes/sliver_part.off" -t 0.05 --cut-choice volume --merge-order volume --merge-parts 3 \
  --verify > "$T/tight.txt" 2> "$T/tight.err" || fail "tight options: exit $? $(cat "$T/tight.err")"
np=$(head -1 "$T/tight.txt" | awk '{print $1}')
"$ACD" 3d "$SRC/tests/data/meshes/sliver_part.off" -t 0.05 --no-merge > "$T/nm.txt" 2>/dev/null || fail "no-merge exit $?"
nn=$(head -1 "$T/nm.txt" | awk '{print $1}')
[ "$nn" -le 3 ] || [ "$np" -ge 3 ] || fail "--merge-parts 3 gave $np parts (from $nn)"
# the cut choice by band (docs/acd3d.md "Cut choice by band"): --verify passes with it
"$ACD" 3d "$SRC/tests/data/meshes/sliver_part.off" -t 0.05 --cut-choice band --verify > /dev/null 2> "$T/band.err" ||
  fail "--cut-choice band: exit $? $(cat "$T/band.err")"
for bad in "--cut-choice x" "--merge-order x" "--merge-parts -1" "--threads 100000"; do
  "$ACD" 3d "$T/l.obj" $bad > /dev/null 2>&1; rc=$?
  [ $rc = 1 ] || fail "$bad: exit $rc"
done
# CGAL's spool.off (fetched data): a cut through nearly coincident section points left a speck
# shell (area 1e-33, volume -3e-22 from rounding) taken as a cavity, its piece then
# self-intersecting and left above tau; the plane cut now drops shells whose volume is within
# rounding. --verify fails (exit 3) when a part is above tau. Checked when
# scripts/fetch-data.sh has been run.
SPOOL="$SRC/data/meshes/spool.off"
if [ -f "$SPOOL" ]; then
  "$ACD" 3d "$SPOOL" -t 0.1 --verify >"$T/spool.out" 2>"$T/spool.err" ||
    fail "spool: exit $? $(cat "$T/spool.err")"
  # --no-merge at tau 0.02: a chain of cuts chips crescents off a curved face, the last ones no
  # cut can split (measured 1.2-2.1 tau by the patch measure); they are within tau of their hulls
  # both ways, so they end as hull_distance leaves instead of no_cut parts above tau
  "$ACD" 3d "$SPOOL" -t 0.02 --no-merge --verify --json "$T/spool.json" >"$T/spool.out" 2>"$T/spool.err" ||
    fail "spool --no-merge: exit $? $(cat "$T/spool.err")"
  grep -q '"no_cut"' "$T/spool.json" && fail "spool --no-merge: a no_cut leaf is left"
  grep -q '"hull_distance"' "$T/spool.json" || fail "spool --no-merge: no hull_distance leaf (the case this checks is gone)"
else
  echo "note: $SPOOL absent (run scripts/fetch-data.sh): spool check skipped"
fi
# an open wavy sheet: its hole closed by a flat cap that the sheet crosses, so solid mode cannot
# split the crossing part; the result is refused as bad input (exit 2) naming the crossing faces,
# the outputs still written; surface mode takes the sheet as it is
python3 "$SRC/tests/cli/wavy_sheet.py" "$T/wavy.obj" || fail "wavy sheet generator"
"$ACD" 3d "$T/wavy.obj" -t 0.2 -o "$T/wavy_h.obj" >/dev/null 2>"$T/wavy.err"
rc=$?
[ $rc -eq 2 ] || fail "wavy sheet (solid): exit $rc, expected 2 $(cat "$T/wavy.err")"
grep -q "intersects itself (.* face pairs, first: faces [0-9]* and [0-9]*), so [0-9]* part(s) stay above tau" "$T/wavy.err" ||
  fail "wavy sheet (solid): no self-intersection message: $(cat "$T/wavy.err")"
grep -q '^o ' "$T/wavy_h.obj" || fail "wavy sheet (solid): hulls not written"
"$ACD" 3d "$T/wavy.obj" -t 0.2 --verify >/dev/null 2>"$T/wavy.err"
[ $? -eq 2 ] || fail "wavy sheet (solid, --verify): expected exit 2 (bad input before the verification)"
"$ACD" 3d "$T/wavy.obj" -t 0.2 --mode surface --verify >/dev/null 2>"$T/wavy.err" ||
  fail "wavy sheet (surface): exit $? $(cat "$T/wavy.err")"
# --budget is solid mode only and excludes --max-hulls: a usage error naming the option, not ignored
"$ACD" 3d "$T/l.obj" --mode surface --budget 4 -o "$T/b.obj" >/dev/null 2>"$T/b.err"
rc=$?
[ $rc -eq 1 ] || fail "--budget in surface mode: exit $rc, expected 1"
grep -q "budget.*solid mode only" "$T/b.err" || fail "--budget in surface mode: message: $(cat "$T/b.err")"
"$ACD" 3d "$T/l.obj" --max-hulls 2 --budget 4 -o "$T/b.obj" >/dev/null 2>"$T/b.err"
rc=$?
[ $rc -eq 1 ] || fail "--budget with --max-hulls: exit $rc, expected 1"
grep -q "exclude each other" "$T/b.err" || fail "--budget with --max-hulls: message: $(cat "$T/b.err")"
"$ACD" 3d "$T/l.obj" -t 10 --budget 3 --verify -o "$T/b.obj" >/dev/null 2>"$T/b.err" || fail "--budget 3 --verify: exit $? $(cat "$T/b.err")"
# solid mode's options in surface mode, --merge-refine without --merge-parts, --no-merge with the
# merge pass's options: usage errors (exit 1) naming the option, not silently ignored
for opts in "--mode surface --cut-choice volume" "--mode surface --merge-order volume" \
            "--mode surface --merge-parts 3" "--merge-refine 4" "--no-merge --merge-parts 3"; do
  "$ACD" 3d "$T/l.obj" $opts -o "$T/b.obj" >/dev/null 2>"$T/b.err"
  rc=$?
  [ $rc -eq 1 ] || fail "$opts: exit $rc, expected 1"
  grep -q -- "-\(cut-choice\|merge-order\|merge-parts\|merge-refine\)" "$T/b.err" || fail "$opts: message: $(cat "$T/b.err")"
done
echo ok
