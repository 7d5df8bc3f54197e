#!/usr/bin/env python3
"""Extracts one country from a world-atlas TopoJSON file (npm package `world-atlas`, Natural Earth
data) as a GeoJSON Feature holding its largest polygon with its holes.

usage: world_atlas_extract.py COUNTRIES.json NAME OUT.geojson

TopoJSON (https://github.com/topojson/topojson-specification): a geometry's rings are lists of
arc indices; arc i is stored delta-encoded in quantized integer coordinates, decoded as
x = translate + scale * cumulative sum; index ~i (= -i-1) means arc i reversed. Consecutive arcs
of a ring share their end point, which is kept once. Only the Python standard library is used."""
import json
import os
import sys


def decode_arcs(topo):
    tr = topo.get("transform")
    arcs = []
    for arc in topo["arcs"]:
        pts, x, y = [], 0, 0
        for p in arc:
            if tr:
                x += p[0]
                y += p[1]
                pts.append((x * tr["scale"][0] + tr["translate"][0], y * tr["scale"][1] + tr["translate"][1]))
            else:
                pts.append((p[0], p[1]))
        arcs.append(pts)
    return arcs


def ring(arcs, indices):
    out = []
    for k, i in enumerate(indices):
        pts = arcs[i] if i >= 0 else list(reversed(arcs[~i]))
        out.extend(pts if k == 0 else pts[1:])
    return [(round(x, 7), round(y, 7)) for x, y in out]


def area(r):
    return 0.5 * sum(r[i][0] * r[(i + 1) % len(r)][1] - r[(i + 1) % len(r)][0] * r[i][1] for i in range(len(r)))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    topo = json.load(open(sys.argv[1]))
    arcs = decode_arcs(topo)
    geoms = [g for g in topo["objects"]["countries"]["geometries"] if g.get("properties", {}).get("name") == sys.argv[2]]
    if not geoms:
        sys.exit("no country named %r" % sys.argv[2])
    g = geoms[0]
    polys = g["arcs"] if g["type"] == "MultiPolygon" else [g["arcs"]]
    rings = [[ring(arcs, r) for r in poly] for poly in polys]
    best = max(rings, key=lambda p: abs(area(p[0])))
    coords = []
    for k, r in enumerate(best):
        # RFC 7946: exterior counterclockwise, holes clockwise; closed rings
        if (area(r) > 0) != (k == 0):
            r = list(reversed(r))
        if r[0] != r[-1]:
            r = r + [r[0]]
        coords.append([list(p) for p in r])
    feature = {
        "type": "Feature",
        "properties": {
            "name": sys.argv[2],
            "source": "Natural Earth admin 0 countries, %s (public domain), via the npm package world-atlas "
                      "(ISC licence)" % os.path.basename(sys.argv[1]),
            "holes": len(coords) - 1,
        },
        "geometry": {"type": "Polygon", "coordinates": coords},
    }
    with open(sys.argv[3], "w") as f:
        json.dump(feature, f, separators=(",", ":"))
        f.write("\n")
    print("%s: %d rings, %d vertices -> %s" % (sys.argv[2], len(coords), sum(len(r) - 1 for r in coords), sys.argv[3]))


if __name__ == "__main__":
    main()
