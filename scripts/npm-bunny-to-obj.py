#!/usr/bin/env python3
"""Converts the npm package `bunny` (index.js: exports.positions=[[x,y,z],...] and
exports.cells=[[i,j,k],...], 0-based) to a Wavefront OBJ file. Usage: npm-bunny-to-obj.py INDEX_JS OUT_OBJ"""
import json
import re
import sys


def main():
    src, out = sys.argv[1], sys.argv[2]
    text = open(src, encoding="utf-8").read()
    arrays = {}
    for m in re.finditer(r"exports\.(positions|cells)\s*=\s*", text):
        dec = json.JSONDecoder()
        arrays[m.group(1)], _ = dec.raw_decode(text, m.end())
    if "positions" not in arrays or "cells" not in arrays:
        sys.exit("npm-bunny-to-obj: %s has no exports.positions / exports.cells" % src)
    pos, cells = arrays["positions"], arrays["cells"]
    with open(out, "w", encoding="ascii") as f:
        f.write("# Stanford bunny, from the npm package 'bunny' (public domain), converted by scripts/npm-bunny-to-obj.py\n")
        for p in pos:
            f.write("v %r %r %r\n" % (float(p[0]), float(p[1]), float(p[2])))
        for c in cells:
            f.write("f %s\n" % " ".join(str(int(i) + 1) for i in c))
    print("npm-bunny-to-obj: %d vertices, %d faces -> %s" % (len(pos), len(cells), out))


if __name__ == "__main__":
    main()
