#!/usr/bin/env python3
"""An open wavy sheet (13 x 13 vertices, z = 0.3 sin(3 pi x) sin(pi y)) as OBJ: its one hole closed
by a flat cap crosses the sheet, so solid mode cannot split the crossing part (tests/cli/3d_basic.sh,
3d_budget.sh). usage: wavy_sheet.py OUT.obj"""
import math
import sys

n = 12
with open(sys.argv[1], "w") as f:
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            f.write("v %.17g %.17g %.17g\n" % (x, y, 0.3 * math.sin(3 * math.pi * x) * math.sin(math.pi * y)))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))
