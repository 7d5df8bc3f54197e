#!/usr/bin/env bash
# acd 3d --trim-coverage F (docs/acd3d.md "Trimmed hulls"): on a bumpy sphere at a part budget the
# hulls are trimmed (caps cut off, reported on stdout and in --json's "trim"), --verify passes with
# the volume outside the trimmed hulls (measured exactly) within F of the input's (also on
# ChineseDragon-10kv, where the bound it used before failed), and acd eval (independent code) finds the union's
# coverage at least 1 - F (up to sampling) and a higher IoU than without trimming; a run without the
# option writes no "trim"; bad values and surface mode are usage errors.
. "$(dirname "$0")/lib.sh"
M="$T/bumpy.off"
python3 - "$M" <<'PY'
import math, sys
nu, nv = 48, 32
V = [(0.0, 0.0, 1.0)]
F = []
def r(t, p): return 1 + 0.25 * math.sin(3 * t) * math.cos(4 * p) + 0.1 * math.cos(5 * t)
for i in range(1, nv):
    t = math.pi * i / nv
    for j in range(nu):
        p = 2 * math.pi * j / nu
        R = r(t, p)
        V.append((R * math.sin(t) * math.cos(p), R * math.sin(t) * math.sin(p), R * math.cos(t)))
V.append((0.0, 0.0, -r(math.pi, 0)))
V[0] = (0.0, 0.0, r(0, 0))
ring = lambda i, j: 1 + (i - 1) * nu + j % nu
for j in range(nu): F.append((0, ring(1, j), ring(1, j + 1)))
for i in range(1, nv - 1):
    for j in range(nu):
        a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
        F += [(a, d, c), (a, c, b)]
s = len(V) - 1
for j in range(nu): F.append((s, ring(nv - 1, j + 1), ring(nv - 1, j)))
with open(sys.argv[1], "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
    f.writelines("%.17g %.17g %.17g\n" % v for v in V)
    f.writelines("3 %d %d %d\n" % t for t in F)
PY
"$ACD" 3d "$M" --budget 6 -o "$T/p.obj" --json "$T/p.json" > "$T/p.txt" 2> "$T/p.err" || fail "untrimmed: $(cat "$T/p.err")"
"$ACD" 3d "$M" --budget 6 --trim-coverage 0.002 --verify -o "$T/t.obj" --json "$T/t.json" > "$T/t.txt" 2> "$T/t.err" ||
  fail "--trim-coverage 0.002 --verify: exit $? $(cat "$T/t.err")"
grep -q "^trimmed hulls: [1-9][0-9]* caps cut off, at most [0-9.e-]* of the input's volume outside the hulls (limit 0.002)" "$T/t.txt" ||
  fail "trim line: $(cat "$T/t.txt")"
grep -q "^trimmed" "$T/p.txt" && fail "untrimmed run prints a trim line"
# --verify checks the parts in parallel (--threads) and reports in part order: the same verdict,
# outside-volume figure and exit code with one thread as with two
for n in 1 2; do
  "$ACD" 3d "$M" --budget 6 --trim-coverage 0.002 --verify -v --threads $n > /dev/null 2> "$T/v$n.err" ||
    fail "--verify --threads $n: exit $? $(cat "$T/v$n.err")"
  grep "verified" "$T/v$n.err" > "$T/v$n.line" || fail "--verify -v --threads $n: no verdict: $(cat "$T/v$n.err")"
done
cmp -s "$T/v1.line" "$T/v2.line" || fail "--verify: threads 1 and 2 differ: $(cat "$T/v1.line" "$T/v2.line")"
# the volume outside measured exactly (each part cut by its hull's planes), not bounded
grep -q "verified: .* [0-9.e-]* of the input's volume outside the trimmed hulls (exact; limit 0.002)" "$T/v1.line" ||
  fail "verdict: $(cat "$T/v1.line")"
python3 - "$T/p.json" "$T/t.json" <<'PY' || fail "json"
import json, sys
p, t = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert "trim" not in p and all("trimmed_volume" not in q for q in p["parts"]), "untrimmed json has trim keys"
tr = t["trim"]
assert tr["coverage"] == 0.002 and tr["cuts"] > 0, tr
assert 0 < tr["trimmed_volume"] <= 0.002 * t["input_volume"] * (1 + 1e-12), tr
s = sum(q["trimmed_volume"] for q in t["parts"])
assert abs(s - tr["trimmed_volume"]) <= 1e-9 * t["input_volume"], (s, tr)
assert len(p["parts"]) == len(t["parts"])
hp = sum(q["hull_volume"] for q in p["parts"]); ht = sum(q["hull_volume"] for q in t["parts"])
assert ht < hp, (ht, hp)
for a, b in zip(p["parts"], t["parts"]):
    assert a["volume"] == b["volume"] and b["hull_volume"] <= a["hull_volume"] * (1 + 1e-12), (a, b)
# the distance bound (no part vertex farther from its trimmed hull): the parts' largest concavity
assert tr["refused_by_distance"] >= 0
assert abs(tr["distance_bound"] - max(q["concavity"] for q in t["parts"])) <= 1e-12 * t["scale"], tr
PY
grep -q "; every part within [0-9.e-]* of its trimmed hull ([0-9]* cap(s) refused by that bound)" "$T/t.txt" ||
  fail "trim line's distance bound: $(cat "$T/t.txt")"
"$ACD" eval "$M" "$T/p.obj" --json -o "$T/pe.json" > /dev/null 2>&1 || fail "eval untrimmed"
"$ACD" eval "$M" "$T/t.obj" --json -o "$T/te.json" > /dev/null 2>&1 || fail "eval trimmed"
python3 - "$T/pe.json" "$T/te.json" "$T/t.json" <<'PY' || fail "eval: trimmed union"
import json, sys
p, t, r = (json.load(open(a)) for a in sys.argv[1:4])
assert p["coverage"] > 0.9999, p["coverage"]
assert t["coverage"] >= 1 - 0.002 - 5e-4, t["coverage"]
assert t["iou"] > p["iou"], (t["iou"], p["iou"])
# acd eval (independent, sampled): the input's surface lies within the distance bound of the hulls
d = t["distance"]["mesh_to_hulls_max"] * t["diagonal"]
assert d <= r["trim"]["distance_bound"] * (1 + 1e-9), (d, r["trim"]["distance_bound"])
PY
for v in -0.001 0.02 abc nan; do
  "$ACD" 3d "$M" --budget 6 --trim-coverage "$v" > /dev/null 2> "$T/e.err"; rc=$?
  [ $rc -eq 1 ] || fail "--trim-coverage $v: exit $rc, expected 1"
done
# ChineseDragon (data/meshes): where the caps of different cuts overlap, the bound --verify used
# before (the part beyond each plane, summed: 185.21 against the limit 184.08) failed a run whose
# accounts hold (charged 183.81); the exact measure passes (172.81, docs/acd3d.md "Charges along a
# plane"). Its repaired mesh crosses itself, so a --verify failure there would be exit 2.
D="$SRC/data/meshes/ChineseDragon-10kv.off"
if [ -f "$D" ]; then
  timeout 120 "$ACD" 3d "$D" --budget 16 --trim-coverage 0.0008 --verify -v --threads 2 > /dev/null 2> "$T/cd.err" ||
    fail "ChineseDragon --trim-coverage 0.0008 --verify: exit $? $(grep -v '%' "$T/cd.err")"
  grep -q "verified: .* of the input's volume outside the trimmed hulls (exact; limit 0.0008)" "$T/cd.err" ||
    fail "ChineseDragon verdict: $(grep -v '%' "$T/cd.err")"
else
  echo "skip ChineseDragon-10kv.off: no data/meshes (bash scripts/fetch-data.sh)"
fi
"$ACD" 3d "$M" --mode surface --trim-coverage 0.001 > /dev/null 2> "$T/e.err"; rc=$?
[ $rc -eq 1 ] || fail "surface mode --trim-coverage: exit $rc, expected 1 $(cat "$T/e.err")"
grep -q "solid mode only" "$T/e.err" || fail "surface mode message: $(cat "$T/e.err")"
echo ok
