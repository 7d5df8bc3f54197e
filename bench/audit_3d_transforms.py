#!/usr/bin/env python3
"""Robustness audit of `acd 3d`, `acd segment` and `acd eval` under transformations of the input.

For each mesh and each transformation (uniform scales, rotations, a thin plate, triangle soups,
flipped faces, duplicated / overlapping / nested shells, centroid splits, T-junctions; translation
is not in here: see the far-from-origin work) a transformed copy is written and run through
  acd 3d X --verify                                  (default settings)
  acd 3d X --budget 16 --trim-coverage 0.0008 --verify
  acd segment X --verify
  acd eval X HULLS (on both 3d outputs)
recording exit code, last message line, parts, eval's concavity_max / IoU / coverage and time.
One process at a time (the machine is shared). Results: one JSON object a line in OUT/results.jsonl;
`--report` prints the markdown table comparing each transformed run with the untransformed one.

usage: bench/audit_3d_transforms.py [--acd build/acd] [--out DIR] [--meshes a.off,b.obj]
                                    [--transforms t1,t2] [--samples N] [--report]
"""
import argparse, json, math, os, random, struct, subprocess, sys, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHDIR = os.path.join(ROOT, "data", "meshes")
SMALL = ["tetrahedron.off", "cube.off", "star.off", "corner.off", "P.off", "cross.off", "tripod.off",
         "3torus.off", "hole.off", "u.off", "mpi_triang.off", "dragknob.off", "sphere.off", "pipe.off",
         "eight.off", "double-torus-example.off", "rotor.off", "anchor.off"]
# transformations that leave the solid as it is (eval scores them against the untransformed mesh)
SAME_SOLID = {"flip_all", "flip_half", "soup_obj", "t_junctions", "centroid_split"}
LARGE = ["fandisk.off", "knot1.off", "elephant.off", "camel.off", "bunny.obj", "armadillo.off"]


# ---------------------------------------------------------------------------- mesh I/O
def read_mesh(path):
    """Vertices (list of 3-tuples) and triangles (polygons fanned) of an OFF or OBJ file."""
    V, F = [], []
    with open(path) as fh:
        if path.endswith(".obj"):
            for line in fh:
                t = line.split()
                if not t:
                    continue
                if t[0] == "v":
                    V.append(tuple(float(x) for x in t[1:4]))
                elif t[0] == "f":
                    idx = [int(s.split("/")[0]) for s in t[1:]]
                    idx = [i - 1 if i > 0 else len(V) + i for i in idx]
                    for k in range(1, len(idx) - 1):
                        F.append((idx[0], idx[k], idx[k + 1]))
            return V, F
        toks = []
        for line in fh:
            line = line.split("#")[0]
            toks.extend(line.split())
        assert toks[0].endswith("OFF"), path
        nv, nf = int(toks[1]), int(toks[2])
        p = 4
        for _ in range(nv):
            V.append((float(toks[p]), float(toks[p + 1]), float(toks[p + 2])))
            p += 3
        for _ in range(nf):
            n = int(toks[p])
            idx = [int(x) for x in toks[p + 1:p + 1 + n]]
            p += 1 + n
            for k in range(1, n - 1):
                F.append((idx[0], idx[k], idx[k + 1]))
    return V, F


def write_off(path, V, F):
    with open(path, "w") as fh:
        fh.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        for v in V:
            fh.write("%r %r %r\n" % v)
        for f in F:
            fh.write("3 %d %d %d\n" % f)


def write_obj(path, V, F):
    with open(path, "w") as fh:
        for v in V:
            fh.write("v %r %r %r\n" % v)
        for f in F:
            fh.write("f %d %d %d\n" % (f[0] + 1, f[1] + 1, f[2] + 1))


def write_stl_binary(path, V, F):
    with open(path, "wb") as fh:
        fh.write(b"audit_3d_transforms binary STL".ljust(80, b" "))
        fh.write(struct.pack("<I", len(F)))
        for f in F:
            fh.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for i in f:
                fh.write(struct.pack("<3f", *V[i]))
            fh.write(b"\0\0")


# ---------------------------------------------------------------------------- transformations
def bbox(V):
    lo = [min(v[k] for v in V) for k in range(3)]
    hi = [max(v[k] for v in V) for k in range(3)]
    return lo, hi


def scaled(V, s):
    return [(x * s, y * s, z * s) for x, y, z in V]


def rotation(seed=7):
    """A rotation matrix from a random unit quaternion (fixed seed: not axis-aligned)."""
    r = random.Random(seed)
    q = [r.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def apply(M, V):
    return [tuple(M[i][0] * v[0] + M[i][1] * v[1] + M[i][2] * v[2] for i in range(3)) for v in V]


def flipped(F):
    return [(a, c, b) for a, b, c in F]


def soup(V, F, seed=3):
    r = random.Random(seed)
    order = list(range(len(F)))
    r.shuffle(order)
    SV = []
    for t in order:
        for i in F[t]:
            SV.append(V[i])
    perm = list(range(len(SV)))
    r.shuffle(perm)  # new position of each soup vertex
    NV = [None] * len(SV)
    for old, new in enumerate(perm):
        NV[new] = SV[old]
    NF = [(perm[3 * k], perm[3 * k + 1], perm[3 * k + 2]) for k in range(len(order))]
    return NV, NF


def centroid_split(V, F):
    NV, NF = list(V), []
    for a, b, c in F:
        g = tuple((V[a][k] + V[b][k] + V[c][k]) / 3.0 for k in range(3))
        NV.append(g)
        m = len(NV) - 1
        NF += [(a, b, m), (b, c, m), (c, a, m)]
    return NV, NF


def t_junctions(V, F, count):
    """Splits `count` edges at their midpoint in one of their two triangles only."""
    NV, NF = list(V), list(F)
    used = set()
    done = 0
    step = max(1, len(F) // max(1, count))
    for t in range(0, len(F), step):
        if done >= count:
            break
        a, b, c = F[t]
        if frozenset((a, b)) in used:
            continue
        used.add(frozenset((a, b)))
        NV.append(tuple((V[a][k] + V[b][k]) / 2.0 for k in range(3)))
        m = len(NV) - 1
        NF[t] = (a, m, c)
        NF.append((m, b, c))
        done += 1
    return NV, NF


def two_shells(V, F, offset):
    n = len(V)
    return V + [(x + offset[0], y + offset[1], z + offset[2]) for x, y, z in V], \
        F + [(a + n, b + n, c + n) for a, b, c in F]


def in_box(V, F, inward):
    """The mesh as a cavity in a box 1.2 times its bounding box (inner shell inward or not)."""
    lo, hi = bbox(V)
    c = [(lo[k] + hi[k]) / 2 for k in range(3)]
    h = [(hi[k] - lo[k]) * 0.6 for k in range(3)]
    n = len(V)
    B = [(c[0] + sx * h[0], c[1] + sy * h[1], c[2] + sz * h[2])
         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    # cube corners index = 4*ix + 2*iy + iz, faces outward
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    BF = []
    for a, b, cc, d in quads:
        BF += [(a + n, b + n, cc + n), (a + n, cc + n, d + n)]
    inner = flipped(F) if inward else list(F)
    return V + B, inner + BF


def transforms(V, F, name):
    """name -> (kind, writer, vertices, faces, note); kind 'same' means quality must match."""
    lo, hi = bbox(V)
    ext = [hi[k] - lo[k] for k in range(3)]
    amax = max(max(abs(c) for c in v) for v in V)
    R = rotation()
    out = {}
    out["orig"] = ("off", V, F)
    for s in ("1e-9", "1e-3", "1e3", "1e9"):
        out["scale" + s] = ("off", scaled(V, float(s)), F)
    for e in (-30, 30):  # exact scales: every decision relative to the scale must come out the same
        out["scale2^%d" % e] = ("off", scaled(V, 2.0 ** e), F)
    # near the reader's limit ACD_COORD_MAX = 1e60: the largest coordinate just under / over it
    out["scale_to_0.5e60"] = ("off", scaled(V, 0.5e60 / amax), F)
    out["scale_to_2e60"] = ("off", scaled(V, 2e60 / amax), F)
    out["rotate"] = ("off", apply(R, V), F)
    S = [[1, 0, 0], [0, 1e-3, 0], [0, 0, 1]]
    out["rotate_plate"] = ("off", apply(R, apply(S, apply(R, V))), F)  # a thin plate, not axis-aligned
    sv, sf = soup(V, F)
    out["soup_stl"] = ("stl", sv, sf)
    out["soup_obj"] = ("obj", sv, sf)
    out["flip_all"] = ("off", V, flipped(F))
    out["flip_half"] = ("off", V, [(a, c, b) if k % 2 else (a, b, c) for k, (a, b, c) in enumerate(F)])
    out["twice"] = ("off",) + two_shells(V, F, (0.0, 0.0, 0.0))
    out["overlap_half"] = ("off",) + two_shells(V, F, (ext[0] / 2, 0.0, 0.0))
    out["cavity_inward"] = ("off",) + in_box(V, F, True)
    out["cavity_outward"] = ("off",) + in_box(V, F, False)
    out["centroid_split"] = ("off",) + centroid_split(V, F)
    out["t_junctions"] = ("off",) + t_junctions(V, F, max(1, len(F) // 50))
    return out


# ---------------------------------------------------------------------------- runs
def run(cmd, timeout):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        rc, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        rc, out, err = "timeout", "", ""
    dt = time.time() - t0
    msg = ""
    for line in (err.splitlines() + out.splitlines()):
        if "acd " in line and (":" in line) and ("error" in line.lower() or "invalid" in line.lower()
                                                 or "refus" in line.lower() or "verify" in line.lower()
                                                 or "fail" in line.lower() or "warning" in line.lower()):
            msg = line.strip()
            break
    if not msg and rc != 0 and err.strip():
        msg = err.strip().splitlines()[-1]
    return rc, out, err, dt, msg[:300]


def eval_hulls(acd, mesh, hulls, samples, timeout):
    """acd eval's figures of hulls against mesh; samples None: acd eval's default sample counts."""
    if not os.path.exists(hulls):
        return None
    counts = [] if samples is None else ["--samples", str(samples), "--surface-samples", str(samples // 4)]
    rc, out, err, dt, msg = run([acd, "eval", mesh, hulls, "--json"] + counts, timeout)
    if rc != 0:
        return {"rc": rc, "msg": msg}
    d = json.loads(out)
    return {"rc": 0, "iou": d.get("iou"), "coverage": d.get("coverage"),
            "concavity_max": d.get("concavity_max"), "parts": d.get("parts")}


def parts_of(jpath):
    try:
        with open(jpath) as fh:
            d = json.load(fh)
        p = d.get("parts")
        return len(p) if isinstance(p, list) else p
    except Exception:
        return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--acd", default=os.path.join(ROOT, "build", "acd"))
    ap.add_argument("--out", default="/tmp/audit3d-sweep")
    ap.add_argument("--meshes", default=",".join(SMALL + LARGE))
    ap.add_argument("--transforms", default="")
    ap.add_argument("--samples", type=int, default=200000)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--tag", default="")
    ap.add_argument("--report", action="store_true")
    ap.add_argument("--compare", nargs=2, metavar=("BEFORE_TAG", "AFTER_TAG"),
                    help="a before/after table of two tagged runs (rows of the after run)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    res = os.path.join(a.out, "results%s.jsonl" % a.tag)
    if a.report:
        report(res)
        return
    if a.compare:
        compare(os.path.join(a.out, "results%s.jsonl" % a.compare[0]), os.path.join(a.out, "results%s.jsonl" % a.compare[1]))
        return
    want = set(a.transforms.split(",")) if a.transforms else None
    for mname in a.meshes.split(","):
        V, F = read_mesh(os.path.join(MESHDIR, mname))
        base = os.path.splitext(mname)[0]
        ref = os.path.join(a.out, "%s.reference.off" % base)
        write_off(ref, V, F)
        for tname, (fmt, TV, TF) in transforms(V, F, base).items():
            if want and tname not in want:
                continue
            path = os.path.join(a.out, "%s.%s.%s" % (base, tname, fmt))
            {"off": write_off, "obj": write_obj, "stl": write_stl_binary}[fmt](path, TV, TF)
            rec = {"mesh": mname, "transform": tname, "faces": len(TF)}
            for key, extra in (("default", []), ("budget", ["--budget", "16", "--trim-coverage", "0.0008"])):
                hulls = path + ".%s.hulls.obj" % key
                jpath = path + ".%s.json" % key
                for f in (hulls, jpath):
                    if os.path.exists(f):
                        os.remove(f)
                rc, out, err, dt, msg = run([a.acd, "3d", path, "--verify", "--threads", "1", "-o", hulls,
                                             "--json", jpath] + extra, a.timeout)
                r = {"rc": rc, "msg": msg, "seconds": round(dt, 2), "parts": parts_of(jpath) if rc == 0 else None}
                if rc in (0, 3):
                    # the same solid written otherwise (faces reversed, a soup, split faces): scored
                    # against the untransformed mesh, as eval needs a consistently oriented surface
                    r["eval"] = eval_hulls(a.acd, ref if tname in SAME_SOLID else path, hulls, a.samples, a.timeout)
                rec[key] = r
            jpath = path + ".seg.json"
            rc, out, err, dt, msg = run([a.acd, "segment", path, "--verify", "--json", jpath], a.timeout)
            rec["segment"] = {"rc": rc, "msg": msg, "seconds": round(dt, 2),
                              "parts": parts_of(jpath) if rc == 0 else None}
            with open(res, "a") as fh:
                fh.write(json.dumps(rec) + "\n")
            short = lambda r: "%s/%s" % (r["rc"], r.get("parts"))
            print("%-26s %-16s 3d %-8s budget %-8s segment %-8s %s" % (
                mname, tname, short(rec["default"]), short(rec["budget"]), short(rec["segment"]),
                (rec["default"]["msg"] or rec["budget"]["msg"] or rec["segment"]["msg"])[:110]), flush=True)
            for f in os.listdir(a.out):
                if f.startswith("%s.%s." % (base, tname)) and not f.endswith(".json") and "reference" not in f:
                    os.remove(os.path.join(a.out, f))


def report(res):
    recs = [json.loads(l) for l in open(res)]
    orig = {r["mesh"]: r for r in recs if r["transform"] == "orig"}

    def cell(r, o):
        if r is None:
            return "-"
        s = str(r["rc"])
        if r.get("parts") is not None:
            s += " %sp" % r["parts"]
        e = r.get("eval")
        if e and e.get("rc") == 0:
            s += " c%.4f i%.3f v%.4f" % (e["concavity_max"], e["iou"], e["coverage"])
            oe = o.get("eval") if o else None
            if oe and oe.get("rc") == 0:
                if e["iou"] < oe["iou"] - 0.02 or e["coverage"] < oe["coverage"] - 0.002 or \
                        e["concavity_max"] > 1.25 * oe["concavity_max"] + 1e-3:
                    s += " **DROP**"
        return s

    print("| mesh | transform | 3d default: rc parts c(oncavity_max) i(oU) v(coverage) | 3d --budget 16 --trim-coverage 0.0008 | segment | message |")
    print("|---|---|---|---|---|---|")
    for r in recs:
        o = orig.get(r["mesh"], {})
        msg = r["default"]["msg"] or r["budget"]["msg"] or r["segment"]["msg"]
        print("| %s | %s | %s | %s | %s | %s |" % (
            r["mesh"], r["transform"], cell(r["default"], o.get("default")), cell(r["budget"], o.get("budget")),
            cell(r["segment"], None), msg.replace("|", "/")[:160]))


def compare(before, after):
    """Markdown rows: each (mesh, transform) of the after run next to the before run's."""
    def load(path):
        d = {}
        if os.path.exists(path):
            for l in open(path):
                r = json.loads(l)
                d[(r["mesh"], r["transform"])] = r  # the last run of a pair wins
        return d
    B, A = load(before), load(after)

    def cell(r):
        if r is None:
            return "-"
        s = "%s" % r["rc"]
        if r.get("parts") is not None:
            s += " %sp" % r["parts"]
        e = r.get("eval")
        if e and e.get("rc") == 0:
            s += " i%.3f c%.4f" % (e["iou"], e["concavity_max"])
        return s

    print("| mesh | transform | 3d before | 3d after | --budget 16 --trim-coverage 0.0008 before | after "
          "| segment before | after | message (after) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key, r in A.items():
        b = B.get(key)
        msg = r["default"]["msg"] or r["budget"]["msg"] or r["segment"]["msg"]
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            key[0], key[1], cell(b and b["default"]), cell(r["default"]), cell(b and b["budget"]),
            cell(r["budget"]), cell(b and b["segment"]), cell(r["segment"]), msg.replace("|", "/")[:110]))


if __name__ == "__main__":
    main()
