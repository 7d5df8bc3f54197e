#!/usr/bin/env bash
# acd segment on a mesh with every face reversed (inside out) and with every other face reversed:
# the faces are flipped back (notice on stderr) and the labels are the correctly oriented mesh's,
# face for face. Before, valleys and ridges swapped (bench/audit_3d_transforms.py: mpi_triang with
# all faces reversed gave 3 parts, one unresolved, --verify failing).
. "$(dirname "$0")/lib.sh"
M="$SRC/tests/data/meshes/torus.off"
# the torus's quads split into triangles (same diagonals in every file), as is and reversed
python3 - "$M" "$T" <<'PY' || fail "writer"
import sys
lines = [l for l in open(sys.argv[1]) if not l.lstrip().startswith("#")]
tok = " ".join(lines).split()
nv, nf = int(tok[1]), int(tok[2])
V = [" ".join(tok[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
F = []
p = 4 + 3 * nv
for k in range(nf):
    n = int(tok[p]); idx = tok[p + 1:p + 1 + n]; p += 1 + n
    F += [(idx[0], idx[j], idx[j + 1]) for j in range(1, n - 1)]
for name, flip in (("tri", lambda k: False), ("all", lambda k: True), ("half", lambda k: k % 2 == 1)):
    out = ["OFF", "%d %d 0" % (nv, len(F))] + V
    out += ["3 %s %s %s" % ((a, c, b) if flip(k) else (a, b, c)) for k, (a, b, c) in enumerate(F)]
    open("%s/%s.off" % (sys.argv[2], name), "w").write("\n".join(out) + "\n")
PY
M="$T/tri.off"
"$ACD" segment "$M" -t 0.2 --clamp-hull-depth 0 --seg "$T/a.seg" --verify > /dev/null 2> "$T/a.err" || fail "torus: exit $?"
grep -q "flipped" "$T/a.err" && fail "notice on an oriented mesh: $(cat "$T/a.err")"
for mode in all half; do
  "$ACD" segment "$T/$mode.off" -t 0.2 --clamp-hull-depth 0 --seg "$T/$mode.seg" --verify > /dev/null 2> "$T/$mode.err" ||
    fail "$mode reversed: exit $? $(cat "$T/$mode.err")"
  cmp -s "$T/a.seg" "$T/$mode.seg" || fail "$mode reversed: labels differ from the oriented torus's"
done
grep -q "144 of 144 faces flipped .* (it was inside out)" "$T/all.err" || fail "inside-out notice: $(cat "$T/all.err")"
grep -q "faces flipped .* (it was not consistently oriented)" "$T/half.err" || fail "half notice: $(cat "$T/half.err")"
echo ok
