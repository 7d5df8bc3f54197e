#!/usr/bin/env python3
"""Converts a CGAL Polygon_with_holes_2 text file (the operator>> format of CGAL's
Straight_skeleton_2 examples, e.g. sample_1.dat: the outer boundary's vertex count and
vertices, the number of holes, then each hole's count and vertices; blanks separate tokens)
into Lien's .poly format (one "N out" chain, then "N in" per hole, each with its order line).

usage: cgal_pwh_to_poly.py IN.dat OUT.poly [SOURCE-NOTE]

Errors name the token that is wrong. Only the Python standard library is used."""
import sys


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    toks = open(sys.argv[1]).read().split()
    pos = [0]

    def take(what):
        if pos[0] >= len(toks):
            sys.exit("%s: ends early: expected %s (token %d)" % (sys.argv[1], what, pos[0] + 1))
        t = toks[pos[0]]
        pos[0] += 1
        return t

    def count(what):
        t = take(what)
        if not t.isdigit():
            sys.exit("%s: token %d: expected %s (a count), found %r" % (sys.argv[1], pos[0], what, t))
        return int(t)

    def ring(what):
        n = count("the vertex count of " + what)
        pts = []
        for i in range(n):
            try:
                pts.append((float(take("x of %s vertex %d" % (what, i))), float(take("y of %s vertex %d" % (what, i)))))
            except ValueError:
                sys.exit("%s: token %d: %s vertex %d is not a number" % (sys.argv[1], pos[0], what, i))
        return pts

    rings = [ring("the outer boundary")]
    nholes = count("the number of holes") if pos[0] < len(toks) else 0
    for h in range(nholes):
        rings.append(ring("hole %d" % h))
    if pos[0] != len(toks):
        sys.exit("%s: %d tokens after the last hole" % (sys.argv[1], len(toks) - pos[0]))
    with open(sys.argv[2], "w") as f:
        note = sys.argv[3] if len(sys.argv) == 4 else sys.argv[1]
        f.write("# %s: %d vertices, %d holes (converted by scripts/cgal_pwh_to_poly.py)\n"
                % (note, sum(len(r) for r in rings), nholes))
        f.write("%d\n" % len(rings))
        for k, r in enumerate(rings):
            f.write("%d %s\n" % (len(r), "out" if k == 0 else "in"))
            for x, y in r:
                f.write("%r %r\n" % (x, y))
            f.write(" ".join(str(i + 1) for i in range(len(r))) + "\n")
    print("%s: %d vertices, %d holes -> %s" % (sys.argv[1], sum(len(r) for r in rings), nholes, sys.argv[2]))


if __name__ == "__main__":
    main()
