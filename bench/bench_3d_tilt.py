#!/usr/bin/env python3
"""Edge planes on CAD models as users have them: rotated and rounded.

Each CAD mesh of data/meshes is rotated by a few generic rotations (random unit quaternions, fixed
seeds) and written three ways: OFF with %.9g coordinates, OFF with %.6g, and binary STL (float32);
the unrotated file is run too. Each copy is decomposed by `acd 3d X -t TAU --verify` with every
binary given (e.g. main's and a branch's), one process at a time (the machine is shared), and a
markdown table prints parts, max concavity (model units, as the CLI prints it), exit code (0:
verified, 3: a part above tau, 124: timeout) and user CPU seconds, one column group per binary.

usage: bench/bench_3d_tilt.py [--acd A[,B...]] [--names base,new] [--meshes star.off,...]
                              [--taus 0.05,0.01] [--seeds 7,11,23] [--timeout 60] [--out DIR]
                              [--report]   (the table of the results already in DIR)
Results: one JSON object a line in DIR/results.jsonl (appended; --report reads them).
docs/results/3d-edgepair.md has the figures ("Rotated and rounded CAD models").
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from audit_3d_transforms import apply, read_mesh, rotation, write_stl_binary  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHDIR = os.path.join(ROOT, "data", "meshes")
# small CAD shapes run at every tau; the larger ones at the first two (they take minutes below)
SMALL = ["star.off", "cross.off", "cross_quad.off", "P.off", "u.off", "hole.off", "rotor.off"]
LARGE = ["fandisk.off", "anchor.off", "couplingdown.off"]
TAUS = [0.05, 0.01, 0.001, 0.0001]


def write_off(path, V, F, fmt):
    with open(path, "w") as fh:
        fh.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        line = " ".join([fmt] * 3) + "\n"
        for v in V:
            fh.write(line % tuple(v))
        for f in F:
            fh.write("3 %d %d %d\n" % tuple(f))


def variants(name, seeds, out):
    """(variant label, path) for the mesh as given and each rotation in each format."""
    V, F = read_mesh(os.path.join(MESHDIR, name))
    base = os.path.splitext(name)[0]
    res = [("as given", os.path.join(MESHDIR, name))]
    for seed in seeds:
        RV = apply(rotation(seed), V)
        for label, fmt in (("g9", "%.9g"), ("g6", "%.6g")):
            p = os.path.join(out, "%s_r%d_%s.off" % (base, seed, label))
            write_off(p, RV, F, fmt)
            res.append(("r%d %%.%sg" % (seed, label[1]), p))
        p = os.path.join(out, "%s_r%d_f32.stl" % (base, seed))
        write_stl_binary(p, RV, F)
        res.append(("r%d float32" % seed, p))
    return res


def run(acd, path, tau, timeout):
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    t0 = time.time()
    try:
        p = subprocess.run([acd, "3d", path, "-t", str(tau), "--verify"], capture_output=True, text=True,
                           timeout=timeout)
        rc, out = p.returncode, p.stdout
    except subprocess.TimeoutExpired:
        rc, out = 124, ""
    wall = time.time() - t0
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before
    parts, conc = None, None
    for line in out.splitlines():
        t = line.split()
        if len(t) > 4 and t[1] == "parts," and t[2] == "max" and t[3] == "concavity":
            parts, conc = int(t[0]), float(t[4])
    return {"rc": rc, "parts": parts, "conc": conc, "wall": wall, "cpu": cpu}


def cell(r):
    if r is None:
        return "- | - | - | -"
    if r["rc"] == 124:
        return "timeout | - | 124 | %.2f" % r["cpu"]
    return "%s | %s | %d | %.2f" % (r["parts"], "%.3g" % r["conc"] if r["conc"] is not None else "-", r["rc"],
                                    r["cpu"])


def report(rows, names):
    hdr = "| mesh | copy | tau |" + "".join(" %s parts | %s max conc | %s rc | %s cpu |" % (n, n, n, n) for n in names)
    print(hdr)
    print("|" + "---|" * (3 + 4 * len(names)))
    for r in rows:
        print("| %s | %s | %g | %s |" % (r["mesh"], r["copy"], r["tau"], " | ".join(cell(r["runs"].get(n)) for n in names)))
    # summary: parts per mesh and tau over the rotated copies, per binary
    print()
    print("| mesh | tau | copies |" + "".join(" %s: parts (min-max), sum |" % n for n in names))
    print("|" + "---|" * (3 + len(names)))
    keys = []
    for r in rows:
        k = (r["mesh"], r["tau"])
        if k not in keys:
            keys.append(k)
    for k in keys:
        rs = [r for r in rows if (r["mesh"], r["tau"]) == k and r["copy"] != "as given"]
        cells = []
        for n in names:
            ps = [r["runs"][n]["parts"] for r in rs if n in r["runs"] and r["runs"][n]["parts"] is not None]
            to = sum(1 for r in rs if n in r["runs"] and r["runs"][n]["rc"] == 124)
            cells.append("%s-%s, %d%s" % (min(ps), max(ps), sum(ps), " (+%d timeouts)" % to if to else "")
                         if ps else "-")
        print("| %s | %g | %d | %s |" % (k[0], k[1], len(rs), " | ".join(cells)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--acd", default=os.path.join(ROOT, "build", "acd"))
    ap.add_argument("--names", default="")
    ap.add_argument("--meshes", default=",".join(SMALL + LARGE))
    ap.add_argument("--taus", default="")
    ap.add_argument("--seeds", default="7,11,23")
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--out", default="/tmp/bench_3d_tilt")
    ap.add_argument("--report", action="store_true")
    a = ap.parse_args()
    acds = a.acd.split(",")
    names = a.names.split(",") if a.names else ["acd%d" % i for i in range(len(acds))]
    assert len(names) == len(acds), "--names: one name per binary"
    os.makedirs(a.out, exist_ok=True)
    res = os.path.join(a.out, "results.jsonl")
    if a.report:
        rows = [json.loads(l) for l in open(res)]
        names = []
        for r in rows:
            names += [n for n in r["runs"] if n not in names]
        report(rows, names)
        return
    seeds = [int(s) for s in a.seeds.split(",") if s]
    rows = []
    for name in a.meshes.split(","):
        taus = [float(t) for t in a.taus.split(",")] if a.taus else (TAUS if name in SMALL else TAUS[:2])
        for copy, path in variants(name, seeds, a.out):
            for tau in taus:
                row = {"mesh": name, "copy": copy, "tau": tau, "runs": {}}
                for n, acd in zip(names, acds):  # each binary in turn, same minute
                    row["runs"][n] = run(acd, path, tau, a.timeout)
                rows.append(row)
                with open(res, "a") as fh:
                    fh.write(json.dumps(row) + "\n")
                print("%s %s %g: %s" % (name, copy, tau, "; ".join("%s %s" % (n, cell(row["runs"][n])) for n in names)),
                      file=sys.stderr, flush=True)
    report(rows, names)


if __name__ == "__main__":
    main()
