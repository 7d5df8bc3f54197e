#!/usr/bin/env python3
"""Parts left above tau after a one-rounding perturbation: `acd 3d --verify` (default settings and
`--budget 16 --trim-coverage 0.0008`, `--threads 1`) on CAD meshes under non-exact scales, rotations,
soups and face shuffles. Lighter than bench/audit_3d_transforms.py (whose mesh I/O and transformations
it uses): no segment, no eval. One JSON line per (mesh, transformation) in OUT/TAG.jsonl, with exit
code, part count and the --verify message of each pipeline; `--compare BEFORE AFTER` prints the exits
!= 0 of both and the runs whose exit or part count changed. docs/results/3d-robustness.md.

usage: bench/audit_3d_stuck.py --acd BIN --tag T [--set 1|2] [--meshes a.off,b.off] [--out DIR]
       bench/audit_3d_stuck.py --compare BEFORE_TAG AFTER_TAG [--out DIR]
"""
import argparse, json, os, random, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import audit_3d_transforms as A  # noqa: E402

CAD = ["rotor.off", "rotor_small.off", "anchor.off", "fandisk.off", "double-torus-example.off", "eight.off",
       "star.off", "P.off", "cross.off", "tripod.off", "u.off", "hole.off", "3torus.off", "dragknob.off",
       "mpi_triang.off", "double-torus-3-holes.off", "pinion_small.off", "joint.off", "part.off", "spool.off",
       "blade.off", "couplingdown.off", "cheese.off", "beam.off"]


def shuffled(F, seed):
    r = random.Random(seed)
    G = list(F)
    r.shuffle(G)
    return G


def transforms(V, F, which):
    amax = max(max(abs(c) for c in v) for v in V)
    if which == "1":
        T = {"orig": ("off", V, F), "scale1e-3": ("off", A.scaled(V, 1e-3), F),
             "scale1e9": ("off", A.scaled(V, 1e9), F), "scale0.85": ("off", A.scaled(V, 0.851262377128435), F),
             "scale_to_0.5e60": ("off", A.scaled(V, 0.5e60 / amax), F), "rotate": ("off", A.apply(A.rotation(), V), F)}
        sv, sf = A.soup(V, F)
        seeds = (1, 2)
    else:
        T = {"scale0.3": ("off", A.scaled(V, 0.3), F), "scale3.7": ("off", A.scaled(V, 3.7), F),
             "scale1e-5": ("off", A.scaled(V, 1e-5), F), "rotate2": ("off", A.apply(A.rotation(2), V), F),
             "rotate3": ("off", A.apply(A.rotation(3), V), F)}
        sv, sf = A.soup(V, F, 5)
        seeds = (3, 4)
    T["soup_stl"] = ("stl", sv, sf)
    T["soup_obj"] = ("obj", sv, sf)
    for s in seeds:
        T["shuffle%d" % s] = ("off", V, shuffled(F, s))
    return T


def run(a):
    os.makedirs(a.out, exist_ok=True)
    work = os.path.join(a.out, "work-" + a.tag)
    os.makedirs(work, exist_ok=True)
    res = open(os.path.join(a.out, a.tag + ".jsonl"), "a")
    for m in a.meshes.split(","):
        V, F = A.read_mesh(os.path.join(A.MESHDIR, m))
        for tn, (fmt, TV, TF) in transforms(V, F, a.set).items():
            p = os.path.join(work, "%s.%s.%s" % (m.rsplit(".", 1)[0], tn, fmt))
            {"off": A.write_off, "obj": A.write_obj, "stl": A.write_stl_binary}[fmt](p, TV, TF)
            rec = {"mesh": m, "t": tn}
            for key, extra in (("default", []), ("budget", ["--budget", "16", "--trim-coverage", "0.0008"])):
                t0 = time.time()
                try:
                    pr = subprocess.run([a.acd, "3d", p, "--verify", "--threads", "1", "-o", p + ".hull.obj",
                                         "--json", p + ".json"] + extra, capture_output=True, text=True,
                                        timeout=a.timeout)
                    rc, err = pr.returncode, pr.stderr
                except subprocess.TimeoutExpired:
                    rc, err = "timeout", ""
                parts = None
                try:
                    parts = len(json.load(open(p + ".json"))["parts"])
                except Exception:
                    pass
                msg = [l for l in err.splitlines() if "verif" in l or "error" in l.lower()]
                rec[key] = {"rc": rc, "parts": parts, "msg": (msg[-1] if msg else "")[:200],
                            "s": round(time.time() - t0, 2)}
            for f in os.listdir(work):
                os.remove(os.path.join(work, f))
            res.write(json.dumps(rec) + "\n")
            res.flush()
            print("%-28s %-16s default %s/%s  budget %s/%s %s" % (
                m, tn, rec["default"]["rc"], rec["default"]["parts"], rec["budget"]["rc"], rec["budget"]["parts"],
                rec["default"]["msg"] or rec["budget"]["msg"]), flush=True)


def compare(a):
    def load(tag):
        return {(r["mesh"], r["t"]): r for r in map(json.loads, open(os.path.join(a.out, tag + ".jsonl")))}
    B, N = load(a.compare[0]), load(a.compare[1])
    keys = [k for k in N if k in B]
    for key in ("default", "budget"):
        print("%s: %d runs, exit != 0: before %d, after %d" % (
            key, len(keys), sum(B[k][key]["rc"] != 0 for k in keys), sum(N[k][key]["rc"] != 0 for k in keys)))
    for k in keys:
        for key in ("default", "budget"):
            b, n = B[k][key], N[k][key]
            if (b["rc"], b["parts"]) != (n["rc"], n["parts"]) or n["rc"] != 0:
                print("  %s %s %s: exit %s, %s parts -> exit %s, %s parts %s" % (
                    k[0], k[1], key, b["rc"], b["parts"], n["rc"], n["parts"], n["msg"] or b["msg"]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--acd", default=os.path.join(A.ROOT, "build", "acd"))
    ap.add_argument("--out", default="/tmp/audit3d-stuck")
    ap.add_argument("--tag", default="run")
    ap.add_argument("--set", default="1", choices=("1", "2"))
    ap.add_argument("--meshes", default=",".join(CAD))
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--compare", nargs=2, metavar=("BEFORE_TAG", "AFTER_TAG"))
    a = ap.parse_args()
    if a.compare:
        compare(a)
    else:
        run(a)


if __name__ == "__main__":
    main()
