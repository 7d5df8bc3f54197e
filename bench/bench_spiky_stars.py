#!/usr/bin/env python3
"""Robustness bench for solid mode: 72 spiky stars (UV spheres whose vertex radii take a few
values, so cut planes run through vertices and along coplanar faces) decomposed at tau 0.05 with
--verify; prints how many end with a part above tau and the parts in total.

usage: bench/bench_spiky_stars.py [ACD_BINARY ...]   (default build/acd; several binaries are
compared in the same run)"""
import math
import os
import random
import subprocess
import sys
import tempfile


def star(seed):
    rnd = random.Random(seed)
    nlat, nlon = (5, 8) if seed % 3 else (7, 10)
    V = [(0.0, 0.0, 1.0)]
    for i in range(1, nlat):
        th = math.pi * i / nlat
        for j in range(nlon):
            ph = 2 * math.pi * j / nlon
            r = rnd.choice([0.3, 0.6, 1.0, 1.4]) if seed % 2 else rnd.uniform(0.2, 1.5)
            V.append((r * math.sin(th) * math.cos(ph), r * math.sin(th) * math.sin(ph), r * math.cos(th)))
    V.append((0.0, 0.0, -1.0))
    S = len(V) - 1

    def idx(i, j):
        return 1 + (i - 1) * nlon + (j % nlon)
    F = [(0, idx(1, j), idx(1, j + 1)) for j in range(nlon)]
    for i in range(1, nlat - 1):
        for j in range(nlon):
            a, b, c, d = idx(i, j), idx(i, j + 1), idx(i + 1, j), idx(i + 1, j + 1)
            F += [(a, c, d), (a, d, b)]
    F += [(S, idx(nlat - 1, j + 1), idx(nlat - 1, j)) for j in range(nlon)]
    return "OFF\n%d %d 0\n" % (len(V), len(F)) + "".join("%.17g %.17g %.17g\n" % v for v in V) + \
        "".join("3 %d %d %d\n" % t for t in F)


def main():
    bins = sys.argv[1:] or ["build/acd"]
    with tempfile.TemporaryDirectory() as d:
        files = []
        for seed in range(72):
            p = os.path.join(d, "star%d.off" % seed)
            with open(p, "w") as f:
                f.write(star(seed))
            files.append(p)
        for b in bins:
            fail = parts = 0
            for p in files:
                r = subprocess.run([b, "3d", p, "-t", "0.05", "--verify"], capture_output=True, text=True)
                if r.returncode != 0:
                    fail += 1
                line = r.stdout.split("\n")[0].split()
                parts += int(line[0]) if line and line[0].isdigit() else 0
            print("%s: %d of %d stars with a part above tau (or failing --verify), %d parts" % (b, fail, len(files), parts))


if __name__ == "__main__":
    main()
