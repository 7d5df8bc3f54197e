#!/usr/bin/env bash
# Cages (acd segment --cage; docs/corise.md "Cages"): figures on CGAL's elephant and camel
# (data/meshes, scripts/fetch-data.sh) for a few vertex budgets, and the picture
# docs/img/corise-cage-elephant.png (the mesh coloured by part inside the translucent cage).
#
# The picture is drawn by the small z-buffer rasterizer below (Python standard library only:
# orthographic view, flat Lambert shading, 2x2 supersampling, PNG written with zlib): the mesh's
# faces coloured by their .seg label, the cage's nearest surface blended over them at 35 %, and the
# cage's crease edges (dihedral angle over 20 degrees) drawn where the cage's own depth shows them.
#
# usage: bench/bench_corise_cage.sh [BUILD_DIR] [--no-picture]
set -uo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
PIC=1
[ "${2:-}" = "--no-picture" ] && PIC=0
ACD=$B/acd
M=data/meshes
[ -x "$ACD" ] || { echo "bench_corise_cage: build first ($ACD missing)"; exit 1; }
[ -d "$M" ] || { echo "bench_corise_cage: no $M; run scripts/fetch-data.sh; skipped"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT

echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); $(nproc) cores, $(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'); load $(cut -d' ' -f1 /proc/loadavg)"
echo "| mesh | faces | parts | budget N | offset | corners chosen | corners unioned | cage vertices | cage triangles | cage / mesh volume | outside / checked vertices | cage seconds |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for m in elephant camel; do
  f=$M/$m.off
  [ -f "$f" ] || { echo "bench_corise_cage: $f missing, skipped"; continue; }
  for n in 32 12 0; do
    "$ACD" segment "$f" --seg "$T/$m.seg" --cage "$T/$m-$n.obj" --cage-vertices "$n" -v > "$T/out.txt" 2> "$T/err.txt" ||
      { echo "bench_corise_cage: $m N=$n failed: $(tail -1 "$T/err.txt")"; continue; }
    python3 - "$m" "$n" "$f" "$T/out.txt" "$T/err.txt" <<'EOF'
import re, sys
m, n, f, out, err = sys.argv[1:6]
txt = open(out).read() + open(err).read()
parts = re.search(r"(\d+) parts", txt).group(1)
c = re.search(r"cage: (\d+) hulls \((\d+) corners chosen, (\d+) after quantization\), (\d+) vertices, (\d+) triangles, "
              r"volume/mesh ([0-9.]+), (\d+) of (\d+) vertices outside, ([0-9.]+) s", txt)
faces = open(f).read().split()[2]
print("| %s | %s | %s | %s | 0.01 | %s | %s | %s | %s | %.3f | %s / %s | %s |" % (
    m, faces, parts, n if n != "0" else "none", c.group(2), c.group(3), c.group(4), c.group(5), float(c.group(6)),
    c.group(7), c.group(8), c.group(9)))
EOF
  done
done

[ $PIC = 1 ] || exit 0
[ -f "$T/elephant.seg" ] && [ -f "$T/elephant-32.obj" ] || { echo "bench_corise_cage: no elephant run, no picture"; exit 0; }
python3 - "$M/elephant.off" "$T/elephant.seg" "$T/elephant-32.obj" docs/img/corise-cage-elephant.png <<'EOF'
import math, struct, sys, zlib

def read_off(path):
    t = [w for line in open(path) for w in line.split('#')[0].split()]
    nv, nf = int(t[1]), int(t[2])
    V = [tuple(float(x) for x in t[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
    F, k = [], 4 + 3 * nv
    if t[0] == 'COFF':  # per-vertex colours: 7 numbers per vertex
        V = [tuple(float(x) for x in t[4 + 7 * i:7 + 7 * i]) for i in range(nv)]
        k = 4 + 7 * nv
    for _ in range(nf):
        c = int(t[k]); idx = [int(x) for x in t[k + 1:k + 1 + c]]; k += 1 + c
        F += [(idx[0], idx[j], idx[j + 1]) for j in range(1, c - 1)]
    return V, F

def read_obj(path):
    V, F = [], []
    for line in open(path):
        w = line.split()
        if not w: continue
        if w[0] == 'v': V.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == 'f':
            idx = [int(x.split('/')[0]) - 1 for x in w[1:]]
            F += [(idx[0], idx[j], idx[j + 1]) for j in range(1, len(idx) - 1)]
    return V, F

mesh_path, seg_path, cage_path, png_path = sys.argv[1:5]
MV, MF = read_off(mesh_path)
labels = [int(x) for x in open(seg_path).read().split()]
CV, CF = read_obj(cage_path)

# view: rotate about the vertical (y) axis by YAW, then tilt by PITCH; orthographic along -z
UP = (0, 1, 2)  # CGAL's elephant: y up
YAW, PITCH = math.radians(-30), math.radians(-15)
cy, sy, cp, sp = math.cos(YAW), math.sin(YAW), math.cos(PITCH), math.sin(PITCH)
def view(p):
    x, y, z = p[UP[0]], p[UP[1]], p[UP[2]]  # the mesh's axes as (right, up, towards the viewer)
    x, z = cy * x + sy * z, -sy * x + cy * z
    y, z = cp * y - sp * z, sp * y + cp * z
    return (x, y, z)
MV = [view(p) for p in MV]
CV = [view(p) for p in CV]
xs = [p[0] for p in CV]; ys = [p[1] for p in CV]
W, H, S = 640, 440, 2  # output size and supersampling
w, h = W * S, H * S
span = max((max(xs) - min(xs)) / (0.94 * w), (max(ys) - min(ys)) / (0.94 * h))
ox, oy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
def scr(p):
    return ((p[0] - ox) / span + w / 2, h / 2 - (p[1] - oy) / span, p[2])

LIGHT = (0.35, 0.55, 0.76)
def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]; v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    l = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / l for x in n)

def raster(V, F, shade, zbuf, cbuf, cull):
    P = [scr(p) for p in V]
    for fi, (i, j, k) in enumerate(F):
        a, b, c = P[i], P[j], P[k]
        area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if area == 0 or (cull and area > 0): continue  # screen y points down: front faces have area < 0
        col = shade(fi, V[i], V[j], V[k])
        x0 = max(int(min(a[0], b[0], c[0])), 0); x1 = min(int(max(a[0], b[0], c[0])) + 1, w - 1)
        y0 = max(int(min(a[1], b[1], c[1])), 0); y1 = min(int(max(a[1], b[1], c[1])) + 1, h - 1)
        for y in range(y0, y1 + 1):
            py = y + 0.5
            for x in range(x0, x1 + 1):
                px = x + 0.5
                l0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area
                l1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area
                l2 = 1 - l0 - l1
                if l0 < 0 or l1 < 0 or l2 < 0: continue
                z = l0 * a[2] + l1 * b[2] + l2 * c[2]
                o = y * w + x
                if z > zbuf[o]:
                    zbuf[o] = z; cbuf[o] = col

PALETTE = [(228, 26, 28), (55, 126, 184), (77, 175, 74), (152, 78, 163), (255, 127, 0), (200, 180, 40),
           (166, 86, 40), (247, 129, 191), (102, 194, 165), (141, 160, 203), (231, 138, 195), (166, 216, 84)]
def mesh_shade(fi, a, b, c):
    n = normal(a, b, c)
    d = abs(sum(n[i] * LIGHT[i] for i in range(3)))
    base = PALETTE[labels[fi] % len(PALETTE)]
    return tuple(min(255, int(v * (0.35 + 0.65 * d))) for v in base)
def cage_shade(fi, a, b, c):
    n = normal(a, b, c)
    d = abs(sum(n[i] * LIGHT[i] for i in range(3)))
    return (int(90 + 80 * d), int(140 + 70 * d), int(200 + 55 * d))

NEG = -1e300
mz, mc = [NEG] * (w * h), [(255, 255, 255)] * (w * h)
raster(MV, MF, mesh_shade, mz, mc, False)
cz, cc = [NEG] * (w * h), [None] * (w * h)
raster(CV, CF, cage_shade, cz, cc, True)
ALPHA = 0.35
img = [c if cc[o] is None else tuple(int((1 - ALPHA) * c[i] + ALPHA * cc[o][i]) for i in range(3))
       for o, c in enumerate(mc)]

# cage crease edges, where the cage's own depth shows them
edges = {}
for fi, f in enumerate(CF):
    for k in range(3):
        u, v = f[k], f[(k + 1) % 3]
        edges.setdefault((min(u, v), max(u, v)), []).append(fi)
CN = [normal(CV[i], CV[j], CV[k]) for (i, j, k) in CF]
P = [scr(p) for p in CV]
zspan = (max(p[2] for p in P) - min(p[2] for p in P)) or 1.0
for (u, v), fs in edges.items():
    if len(fs) == 2 and sum(CN[fs[0]][i] * CN[fs[1]][i] for i in range(3)) > math.cos(math.radians(20)): continue
    a, b = P[u], P[v]
    steps = int(max(abs(b[0] - a[0]), abs(b[1] - a[1]))) + 1
    for s in range(steps + 1):
        t = s / steps
        x, y, z = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])
        for dx in (0, 1):
            for dy in (0, 1):
                xi, yi = int(x) + dx - 1, int(y) + dy - 1
                if 0 <= xi < w and 0 <= yi < h:
                    o = yi * w + xi
                    if cz[o] != NEG and z >= cz[o] - 0.01 * zspan:
                        img[o] = (30, 60, 120)

# downsample S x S and write the PNG
rows = []
for Y in range(H):
    row = bytearray([0])
    for X in range(W):
        acc = [0, 0, 0]
        for dy in range(S):
            for dx in range(S):
                p = img[(Y * S + dy) * w + X * S + dx]
                for i in range(3): acc[i] += p[i]
        row += bytes(v // (S * S) for v in acc)
    rows.append(bytes(row))
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0)) + \
      chunk(b'IDAT', zlib.compress(b''.join(rows), 9)) + chunk(b'IEND', b'')
open(png_path, 'wb').write(png)
print("bench_corise_cage: wrote %s (%d x %d; mesh %d faces, cage %d triangles)" % (png_path, W, H, len(MF), len(CF)))
EOF
