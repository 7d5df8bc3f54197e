#!/usr/bin/env bash
# acd 3d under exact uniform scales (powers of 2: every coordinate scaled without rounding): tau is
# relative and every tolerance scales with the input, so the hulls must be the unscaled run's
# hulls scaled, bit for bit, for the default pipeline and for --budget with --trim-coverage,
# at 2^-190 (1e-57), 2^-150 (1e-45) and at 2^183 (1e55, under ACD_COORD_MAX 1e60). At 2^183 the plane cut's
# rounding scale (a product of three squared lengths: the size to the sixth power) overflowed
# and the budget pass found no cut at all: one part, --verify failing (bench/audit_3d_transforms.py).
. "$(dirname "$0")/lib.sh"
for m in torus sliver_part; do
  for e in -190 -150 183; do
    python3 - "$SRC/tests/data/meshes/$m.off" "$T/s.off" "$e" <<'PY' || fail "scale writer"
import sys
tok = [t for line in open(sys.argv[1]) for t in line.split("#")[0].split()]
nv, nf = int(tok[1]), int(tok[2])
f = 2.0 ** int(sys.argv[3])
out = ["OFF", "%d %d 0" % (nv, nf)]
out += ["%r %r %r" % tuple(float(x) * f for x in tok[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
p = 4 + 3 * nv
for _ in range(nf):
    n = int(tok[p]); out.append(" ".join(tok[p:p + 1 + n])); p += 1 + n
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
    for opts in "-t 0.05" "--budget 8 --trim-coverage 0.0008"; do
      "$ACD" 3d "$SRC/tests/data/meshes/$m.off" $opts --verify -o "$T/a.obj" > /dev/null 2> "$T/a.err" ||
        fail "$m $opts: exit $? $(cat "$T/a.err")"
      "$ACD" 3d "$T/s.off" $opts --verify -o "$T/b.obj" > /dev/null 2> "$T/b.err" ||
        fail "$m x 2^$e $opts: exit $? $(cat "$T/b.err")"
      python3 - "$T/a.obj" "$T/b.obj" "$e" <<'PY' || fail "$m x 2^$e $opts: hulls are not the unscaled ones scaled"
import sys
a = [l.split() for l in open(sys.argv[1])]
b = [l.split() for l in open(sys.argv[2])]
f = 2.0 ** int(sys.argv[3])
assert len(a) == len(b), (len(a), len(b))
for x, y in zip(a, b):
    assert x[0] == y[0], (x, y)
    if x[0] == "v":
        assert [float(u) * f for u in x[1:]] == [float(u) for u in y[1:]], (x, y)
    else:
        assert x == y, (x, y)
PY
    done
  done
done
# below ACD_EXTENT_MIN (1e-60, core/tolerance.h) the products of differences leave the normal doubles: the
# CGAL star scaled by 2^-266 gave 25 parts instead of 11 (exit 0), and below ~1e-103 the volume
# underflowed to 0 ("flat or oriented inward"). Refused, exit 2, naming the size
python3 - "$SRC/tests/data/meshes/torus.off" "$T/tiny.off" <<'PY' || fail "tiny writer"
import sys
tok = [t for line in open(sys.argv[1]) for t in line.split("#")[0].split()]
nv, nf = int(tok[1]), int(tok[2])
out = ["OFF", "%d %d 0" % (nv, nf)] + ["%r %r %r" % tuple(float(x) * 2.0 ** -266 for x in tok[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
p = 4 + 3 * nv
for _ in range(nf):
    n = int(tok[p]); out.append(" ".join(tok[p:p + 1 + n])); p += 1 + n
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
for cmd in 3d segment; do
  "$ACD" $cmd "$T/tiny.off" > /dev/null 2> "$T/tiny.err"; rc=$?
  [ $rc = 2 ] || fail "$cmd on a model of size 1e-80: exit $rc, expected 2"
  grep -q "the model's size (largest bounding-box extent .*) is below the supported 1e-60" "$T/tiny.err" ||
    fail "$cmd tiny message: $(cat "$T/tiny.err")"
done
echo ok
