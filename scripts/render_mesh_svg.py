#!/usr/bin/env python3
"""Render meshes to one SVG picture: flat-shaded triangles, orthographic view, painter's order.

Each input is a panel, left to right. An OBJ's `o`/`g` groups get one colour each (the hulls or
parts written by `acd 3d -o/--parts` and `acd segment`); a file with no groups is drawn grey.
Pure Python (no numpy), for the pictures in README and docs/; meant for meshes up to ~100k
triangles.

OUT.png is written through rsvg-convert (Debian librsvg2-bin), smaller for large meshes.

usage: scripts/render_mesh_svg.py OUT.svg|OUT.png IN[:TITLE] [IN[:TITLE] ...]
           [--azimuth DEG] [--elevation DEG] [--size PX] [--up y|z] [--overlay MESH]
  --overlay MESH  draws MESH in light grey behind every panel's groups (e.g. the input under
                  its cage), with the groups half transparent
"""
import argparse
import gzip
import math
import subprocess
import sys

PALETTE = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
           "#9c755f", "#bab0ac", "#86bcb6", "#d37295", "#fabfd2", "#8cd17d", "#b6992d", "#499894",
           "#f1ce63", "#a0cbe8", "#ffbe7d", "#d4a6c8"]


def _open(path):
    return gzip.open(path, "rt") if path.endswith(".gz") else open(path)


def read_mesh(path):
    """Returns (vertices, [(group_index, (i, j, k))], group_names)."""
    verts, tris, groups = [], [], []
    low = path.lower().removesuffix(".gz")
    with _open(path) as f:
        if low.endswith(".off"):
            toks = []
            for line in f:
                line = line.split("#", 1)[0]
                toks.extend(line.split())
            if toks and toks[0].upper().endswith("OFF"):
                toks = toks[1:]
            nv, nf = int(toks[0]), int(toks[1])
            p = 3
            for _ in range(nv):
                verts.append(tuple(float(t) for t in toks[p:p + 3]))
                p += 3
            for _ in range(nf):
                k = int(toks[p])
                idx = [int(t) for t in toks[p + 1:p + 1 + k]]
                p += 1 + k
                for a in range(1, k - 1):
                    tris.append((0, (idx[0], idx[a], idx[a + 1])))
            groups = [""]
        else:
            g = -1
            for line in f:
                t = line.split()
                if not t:
                    continue
                if t[0] == "v":
                    verts.append((float(t[1]), float(t[2]), float(t[3])))
                elif t[0] in ("o", "g"):
                    groups.append(" ".join(t[1:]))
                    g = len(groups) - 1
                elif t[0] == "f":
                    idx = []
                    for s in t[1:]:
                        i = int(s.split("/")[0])
                        idx.append(i - 1 if i > 0 else len(verts) + i)
                    if g < 0:
                        groups.append("")
                        g = 0
                    for a in range(1, len(idx) - 1):
                        tris.append((g, (idx[0], idx[a], idx[a + 1])))
    if not groups:
        groups = [""]
    return verts, tris, groups


def view_basis(az, el, up):
    a, e = math.radians(az), math.radians(el)
    # direction from the object toward the eye, in a z-up frame
    d = (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))
    if up == "y":  # the model's y is up: swap into the z-up frame used here
        d = (d[0], d[2], -d[1])
        world_up = (0.0, 1.0, 0.0)
    else:
        world_up = (0.0, 0.0, 1.0)
    right = cross(world_up, d)
    right = normalize(right)
    upv = cross(d, right)
    return right, upv, d


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2) or 1.0
    return (a[0] / n, a[1] / n, a[2] / n)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def shade(hex_colour, k):
    r, g, b = (int(hex_colour[i:i + 2], 16) for i in (1, 3, 5))
    return "#%02x%02x%02x" % tuple(max(0, min(255, int(c * k))) for c in (r, g, b))


def project(verts, basis):
    right, upv, d = basis
    return [(dot(v, right), dot(v, upv), dot(v, d)) for v in verts]


def panel_triangles(mesh, basis, colour_of, light, opacity):
    verts, tris, _ = mesh
    P = project(verts, basis)
    out = []
    for g, (i, j, k) in tris:
        a, b, c = verts[i], verts[j], verts[k]
        n = normalize(cross((b[0] - a[0], b[1] - a[1], b[2] - a[2]), (c[0] - a[0], c[1] - a[1], c[2] - a[2])))
        facing = dot(n, basis[2])
        if facing <= 0 and opacity >= 1:
            continue  # back face of a closed, outward-oriented mesh
        lum = 0.35 + 0.65 * abs(dot(n, light))
        depth = (P[i][2] + P[j][2] + P[k][2]) / 3
        out.append((depth, (P[i], P[j], P[k]), shade(colour_of(g), lum), opacity))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("inputs", nargs="+")
    ap.add_argument("--azimuth", type=float, default=-60)
    ap.add_argument("--elevation", type=float, default=20)
    ap.add_argument("--size", type=int, default=360)
    ap.add_argument("--up", choices=("y", "z"), default="y")
    ap.add_argument("--overlay")
    args = ap.parse_args()
    basis = view_basis(args.azimuth, args.elevation, args.up)
    light = normalize((basis[0][0] * 0.4 + basis[1][0] * 0.6 + basis[2][0],
                       basis[0][1] * 0.4 + basis[1][1] * 0.6 + basis[2][1],
                       basis[0][2] * 0.4 + basis[1][2] * 0.6 + basis[2][2]))
    overlay = read_mesh(args.overlay) if args.overlay else None
    panels = []
    for spec in args.inputs:
        path, _, title = spec.partition(":")
        mesh = read_mesh(path)
        ngroups = len(mesh[2])
        colour = (lambda g: "#b0b0b0") if ngroups <= 1 else (lambda g: PALETTE[g % len(PALETTE)])
        tris = []
        if overlay:
            tris += panel_triangles(overlay, basis, lambda g: "#c8c8c8", light, 1.0)
        tris += panel_triangles(mesh, basis, colour, light, 0.55 if overlay else 1.0)
        panels.append((title or path.split("/")[-1], tris))
    # one scale for every panel, from all projected points
    xs = [p[0] for _, t in panels for _, tri, _, _ in t for p in tri]
    ys = [p[1] for _, t in panels for _, tri, _, _ in t for p in tri]
    if not xs:
        sys.exit("render_mesh_svg: nothing to draw")
    w = max(xs) - min(xs)
    h = max(ys) - min(ys)
    s = (args.size - 20) / max(w, h, 1e-300)
    pw, ph = args.size, int(h * s) + 40
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">'
           % (pw * len(panels), ph, pw * len(panels), ph),
           '<rect width="100%" height="100%" fill="white"/>']
    for pi, (title, tris) in enumerate(panels):
        ox = pi * pw + 10 + (args.size - 20 - w * s) / 2
        out.append('<g stroke-width="0.3" stroke-linejoin="round">')
        for depth, tri, col, op in sorted(tris, key=lambda t: t[0]):
            pts = " ".join("%.1f,%.1f" % (ox + (p[0] - min(xs)) * s, 10 + (max(ys) - p[1]) * s) for p in tri)
            extra = ' fill-opacity="%.2f"' % op if op < 1 else ""
            out.append('<polygon points="%s" fill="%s" stroke="%s"%s/>' % (pts, col, col, extra))
        out.append("</g>")
        out.append('<text x="%d" y="%d" font-family="sans-serif" font-size="14" text-anchor="middle">%s</text>'
                   % (pi * pw + pw // 2, ph - 10, title.replace("&", "&amp;").replace("<", "&lt;")))
    out.append("</svg>")
    svg = "\n".join(out) + "\n"
    if args.out.endswith(".png"):
        try:
            subprocess.run(["rsvg-convert", "-o", args.out], input=svg.encode(), check=True)
        except FileNotFoundError:
            sys.exit("render_mesh_svg: PNG output needs rsvg-convert (apt-get install librsvg2-bin)")
    else:
        with open(args.out, "w") as f:
            f.write(svg)


if __name__ == "__main__":
    main()
