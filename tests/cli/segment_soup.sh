#!/usr/bin/env bash
# acd segment on a triangle soup (every face its own three vertices, as OBJ exporters write meshes
# split at texture seams): the vertices at the same coordinates are merged, with a notice, so the
# committed torus segments as it does when indexed (bench/audit_3d_transforms.py found one part per
# face: 72 parts for its 72 quads, --verify passing). Labels stay in the file's face order.
. "$(dirname "$0")/lib.sh"
M="$SRC/tests/data/meshes/torus.off"
python3 - "$M" "$T/soup.obj" <<'PY' || fail "soup writer"
import sys
tok = [t for line in open(sys.argv[1]) for t in line.split("#")[0].split()]
nv, nf = int(tok[1]), int(tok[2])
V = [tok[4 + 3 * i:7 + 3 * i] for i in range(nv)]
p = 4 + 3 * nv
with open(sys.argv[2], "w") as f:
    for _ in range(nf):
        n = int(tok[p]); idx = tok[p + 1:p + 1 + n]; p += 1 + n
        for i in idx:
            f.write("v %s %s %s\n" % tuple(V[int(i)]))
        f.write("f %s\n" % " ".join(str(-n + k) for k in range(n)))
PY
"$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --seg "$T/a.seg" --verify > "$T/a.txt" 2>&1 || fail "indexed: exit $?"
"$ACD" segment "$T/soup.obj" -t 0.2 --clamp-hull-depth 0 --seg "$T/b.seg" --verify > "$T/b.txt" 2> "$T/b.err" ||
  fail "soup: exit $? $(cat "$T/b.err")"
a=$(awk '{print $1}' "$T/a.txt" | head -1); b=$(awk '{print $1}' "$T/b.txt" | head -1)
[ "$a" = "$b" ] || fail "soup gave $b parts, the indexed torus $a"
grep -q "vertices at the same coordinates as others merged" "$T/b.err" || fail "soup notice: $(cat "$T/b.err")"
[ "$(wc -l < "$T/b.seg")" = 144 ] || fail "soup .seg lines"
# an indexed mesh gets no notice
grep -q "merged" "$T/a.txt" && fail "notice on an indexed mesh"
# the torus twice, coincident, each copy closed with its own vertices: not welded (welding made
# every edge carry four faces: fandisk twice went from 24 parts to 7), two copies' parts
python3 - "$M" "$T/twice.off" <<'PY' || fail "twice writer"
import sys
tok = [t for line in open(sys.argv[1]) for t in line.split("#")[0].split()]
nv, nf = int(tok[1]), int(tok[2])
V = [" ".join(tok[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
F, p = [], 4 + 3 * nv
for _ in range(nf):
    n = int(tok[p]); F.append([int(x) for x in tok[p + 1:p + 1 + n]]); p += 1 + n
out = ["OFF", "%d %d 0" % (2 * nv, 2 * nf)] + V + V
out += ["%d %s" % (len(f), " ".join(str(i + c * nv) for i in f)) for c in (0, 1) for f in F]
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
"$ACD" segment "$T/twice.off" -t 0.2 --clamp-hull-depth 0 > "$T/c.txt" 2> "$T/c.err" || fail "twice: exit $?"
grep -q "merged" "$T/c.err" && fail "twice: welded: $(cat "$T/c.err")"
c=$(awk '{print $1}' "$T/c.txt" | head -1)
[ "$c" = $((2 * a)) ] || fail "twice gave $c parts, expected $((2 * a))"
echo ok
