#!/usr/bin/env python3
"""Writes the outline of one glyph of a TrueType font as a polygon with holes in Lien's .poly
format (e.g. DejaVu Sans 'B', '8', '@': letters with holes).

usage: ttf_glyph_to_poly.py FONT.ttf CHAR OUT.poly [TOLERANCE]

Reads the font's own tables with the Python standard library (no FreeType): head (units per em,
loca format), maxp, cmap (a Unicode subtable of format 4), loca and glyf (simple glyphs only:
composite glyphs are refused with a message). Quadratic B-spline contours are made of on-curve
and off-curve points, with an implied on-curve point halfway between two consecutive off-curve
points; each quadratic arc P0 P1 P2 is flattened into n = ceil(sqrt(|P0 - 2 P1 + P2| / (4 tol)))
chords, which keeps the polyline within tol of the curve (the second derivative of the arc is
2 (P0 - 2 P1 + P2), so a chord over a parameter step 1/n deviates at most |P0 - 2 P1 + P2| / (4 n^2)).
tol is TOLERANCE (default 0.001) times the em size. Coordinates are font units (y up).

Contours are classified by nesting, not by their direction: a contour inside an even number of
other contours is an outer boundary, inside an odd number a hole of the smallest outer contour
that contains it (TrueType draws outer contours clockwise, holes counterclockwise; the .poly
reader normalizes orientation anyway). Several outer contours give several polygons."""
import math
import struct
import sys


def tables(data):
    num = struct.unpack(">H", data[4:6])[0]
    out = {}
    for i in range(num):
        tag, _, off, length = struct.unpack(">4sIII", data[12 + 16 * i:28 + 16 * i])
        out[tag.decode("latin-1")] = (off, length)
    return out


def cmap_lookup(data, tab, code):
    off = tab["cmap"][0]
    n = struct.unpack(">H", data[off + 2:off + 4])[0]
    for i in range(n):
        pid, eid, sub = struct.unpack(">HHI", data[off + 4 + 8 * i:off + 12 + 8 * i])
        if (pid, eid) not in ((3, 1), (0, 3), (0, 4), (3, 10)):
            continue
        s = off + sub
        if struct.unpack(">H", data[s:s + 2])[0] != 4:
            continue
        segx2 = struct.unpack(">H", data[s + 6:s + 8])[0]
        seg = segx2 // 2
        ends = struct.unpack(">%dH" % seg, data[s + 14:s + 14 + segx2])
        starts_off = s + 16 + segx2
        starts = struct.unpack(">%dH" % seg, data[starts_off:starts_off + segx2])
        deltas = struct.unpack(">%dh" % seg, data[starts_off + segx2:starts_off + 2 * segx2])
        ro_off = starts_off + 2 * segx2
        ranges = struct.unpack(">%dH" % seg, data[ro_off:ro_off + segx2])
        for k in range(seg):
            if starts[k] <= code <= ends[k]:
                if ranges[k] == 0:
                    return (code + deltas[k]) & 0xFFFF
                a = ro_off + 2 * k + ranges[k] + 2 * (code - starts[k])
                g = struct.unpack(">H", data[a:a + 2])[0]
                return (g + deltas[k]) & 0xFFFF if g else 0
        return 0
    sys.exit("no Unicode cmap subtable of format 4 in the font")


def glyph_contours(data, tab, gid):
    head = tab["head"][0]
    upem = struct.unpack(">H", data[head + 18:head + 20])[0]
    locfmt = struct.unpack(">h", data[head + 50:head + 52])[0]
    loca = tab["loca"][0]
    if locfmt == 0:
        g0, g1 = (2 * v for v in struct.unpack(">HH", data[loca + 2 * gid:loca + 2 * gid + 4]))
    else:
        g0, g1 = struct.unpack(">II", data[loca + 4 * gid:loca + 4 * gid + 8])
    if g0 == g1:
        return upem, []
    g = tab["glyf"][0] + g0
    ncont = struct.unpack(">h", data[g:g + 2])[0]
    if ncont < 0:
        sys.exit("glyph %d is a composite glyph (not supported)" % gid)
    p = g + 10
    ends = struct.unpack(">%dH" % ncont, data[p:p + 2 * ncont])
    p += 2 * ncont
    ilen = struct.unpack(">H", data[p:p + 2])[0]
    p += 2 + ilen
    npts = ends[-1] + 1 if ncont else 0
    flags = []
    while len(flags) < npts:
        f = data[p]
        p += 1
        flags.append(f)
        if f & 8:
            r = data[p]
            p += 1
            flags.extend([f] * r)
    flags = flags[:npts]

    def coords(short_bit, same_bit):
        nonlocal p
        vals, v = [], 0
        for f in flags:
            if f & short_bit:
                d = data[p]
                p += 1
                v += d if f & same_bit else -d
            elif not f & same_bit:
                v += struct.unpack(">h", data[p:p + 2])[0]
                p += 2
            vals.append(v)
        return vals

    xs = coords(2, 16)
    ys = coords(4, 32)
    contours, start = [], 0
    for e in ends:
        contours.append([(xs[i], ys[i], bool(flags[i] & 1)) for i in range(start, e + 1)])
        start = e + 1
    return upem, contours


def flatten(contour, tol):
    pts = contour
    n = len(pts)
    # start at an on-curve point (or the implied one between the first two off-curve points)
    k0 = next((i for i in range(n) if pts[i][2]), None)
    if k0 is None:
        a, b = pts[0], pts[1]
        pts = [((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, True)] + pts[1:] + [pts[0]]
        n = len(pts)
        k0 = 0
    seq = pts[k0:] + pts[:k0]
    out = [(float(seq[0][0]), float(seq[0][1]))]
    cur = out[0]
    i = 1
    ctrl = None
    while i <= n:
        q = seq[i % n]
        if q[2]:
            end = (float(q[0]), float(q[1]))
            if ctrl is None:
                out.append(end)
            else:
                quad(out, cur, ctrl, end, tol)
                ctrl = None
            cur = end
        else:
            c = (float(q[0]), float(q[1]))
            if ctrl is not None:
                mid = ((ctrl[0] + c[0]) / 2, (ctrl[1] + c[1]) / 2)
                quad(out, cur, ctrl, mid, tol)
                cur = mid
            ctrl = c
        i += 1
    if ctrl is not None:
        quad(out, cur, ctrl, out[0], tol)
    # drop the closing repeat and consecutive repeats
    ring = []
    for p in out:
        if not ring or ring[-1] != p:
            ring.append(p)
    while len(ring) > 1 and ring[-1] == ring[0]:
        ring.pop()
    return ring


def quad(out, p0, p1, p2, tol):
    d = math.hypot(p0[0] - 2 * p1[0] + p2[0], p0[1] - 2 * p1[1] + p2[1])
    n = max(1, math.ceil(math.sqrt(d / (4 * tol))))
    for k in range(1, n + 1):
        t = k / n
        a, b, c = (1 - t) ** 2, 2 * t * (1 - t), t * t
        out.append((a * p0[0] + b * p1[0] + c * p2[0], a * p0[1] + b * p1[1] + c * p2[1]))


def area(r):
    return 0.5 * sum(r[i][0] * r[(i + 1) % len(r)][1] - r[(i + 1) % len(r)][0] * r[i][1] for i in range(len(r)))


def inside(pt, r):
    x, y = pt
    c = False
    for i in range(len(r)):
        (x1, y1), (x2, y2) = r[i], r[(i + 1) % len(r)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    data = open(sys.argv[1], "rb").read()
    ch = sys.argv[2]
    if len(ch) != 1:
        sys.exit("CHAR must be one character, got %r" % ch)
    rel = float(sys.argv[4]) if len(sys.argv) == 5 else 0.001
    tab = tables(data)
    for t in ("head", "cmap", "loca", "glyf"):
        if t not in tab:
            sys.exit("%s: no '%s' table (not a TrueType-outline font?)" % (sys.argv[1], t))
    gid = cmap_lookup(data, tab, ord(ch))
    if gid == 0:
        sys.exit("%s: no glyph for %r" % (sys.argv[1], ch))
    upem, contours = glyph_contours(data, tab, gid)
    tol = rel * upem
    rings = [flatten(c, tol) for c in contours]
    rings = [r for r in rings if len(r) >= 3 and area(r) != 0]
    depth = [sum(1 for j, s in enumerate(rings) if j != i and inside(r[0], s)) for i, r in enumerate(rings)]
    outers = [i for i in range(len(rings)) if depth[i] % 2 == 0]
    holes = {i: [] for i in outers}
    for i in range(len(rings)):
        if depth[i] % 2 == 1:
            owners = [o for o in outers if inside(rings[i][0], rings[o])]
            owner = min(owners, key=lambda o: abs(area(rings[o])))
            holes[owner].append(i)
    chains = []
    for o in outers:
        chains.append(("out", rings[o]))
        chains.extend(("in", rings[h]) for h in holes[o])
    with open(sys.argv[3], "w") as f:
        f.write("# glyph %r (U+%04X, glyph %d) of %s, %d units per em, flattened within %g em "
                "(scripts/ttf_glyph_to_poly.py): %d polygon(s), %d hole(s), %d vertices\n"
                % (ch, ord(ch), gid, sys.argv[1].split("/")[-1], upem, rel, len(outers),
                   len(rings) - len(outers), sum(len(r) for r in rings)))
        f.write("%d\n" % len(chains))
        for kind, r in chains:
            f.write("%d %s\n" % (len(r), kind))
            for x, y in r:
                f.write("%.10g %.10g\n" % (x, y))
            f.write(" ".join(str(i + 1) for i in range(len(r))) + "\n")
    print("%r: %d polygon(s), %d hole(s), %d vertices -> %s" % (ch, len(outers), len(rings) - len(outers),
                                                              sum(len(r) for r in rings), sys.argv[3]))


if __name__ == "__main__":
    main()
