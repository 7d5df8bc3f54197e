#!/usr/bin/env python3
"""subdivide_off.py IN.off LEVELS OUT.off: every triangle split in four at its edges' midpoints,
LEVELS times (x4 the triangles per level; the same surface, a finer triangulation; each edge's
midpoint made once, so a closed mesh stays closed). Triangles only (OFF faces of three vertices).
Used to check that acd 3d --budget does not depend on the triangulation (docs/acd3d.md
"Triangulation density": data/meshes/bunny00.off at levels 1 and 2, x4 and x16)."""
import sys


def read_off(path):
    t = open(path).read().split()
    if not t or t[0] != "OFF":
        sys.exit("subdivide_off: %s is not an OFF file" % path)
    nv, nf = int(t[1]), int(t[2])
    i = 4
    V = [tuple(map(float, t[i + 3 * k:i + 3 * k + 3])) for k in range(nv)]
    i += 3 * nv
    F = []
    for _ in range(nf):
        n = int(t[i])
        if n != 3:
            sys.exit("subdivide_off: a face of %d vertices (triangles only)" % n)
        F.append(tuple(int(x) for x in t[i + 1:i + 1 + n]))
        i += 1 + n
    return V, F


def subdivide(V, F):
    V = list(V)
    mid = {}

    def m(a, b):
        k = (min(a, b), max(a, b))
        if k not in mid:
            mid[k] = len(V)
            V.append(tuple((V[a][j] + V[b][j]) / 2 for j in range(3)))
        return mid[k]

    G = []
    for a, b, c in F:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        G += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return V, G


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: subdivide_off.py IN.off LEVELS OUT.off")
    V, F = read_off(sys.argv[1])
    for _ in range(int(sys.argv[2])):
        V, F = subdivide(V, F)
    with open(sys.argv[3], "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        f.write("".join("%.17g %.17g %.17g\n" % v for v in V))
        f.write("".join("3 %d %d %d\n" % t for t in F))


if __name__ == "__main__":
    main()
