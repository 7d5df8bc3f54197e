#!/usr/bin/env python3
"""acd on large meshes: how each command scales with the triangle count.

Makes large inputs by 1-to-4 midpoint subdivision of data/meshes models (each new vertex moved along
the surface normal by a small deterministic amount, so the result is not flat-subdivided: scans are
noisy), written to /tmp/large-* (never into the repository), and measures for each size:
`acd info`, `acd info --repair`, `acd 3d` (default), `acd 3d --budget 43 --trim-coverage 0.0008`
(the armadillo's trimmed run of docs/results/3d-target.md), `acd segment`, `acd eval` (of the default
run's hulls): wall seconds, user+system CPU seconds, peak RSS, parts, and the exponent of time
against size between consecutive sizes (log(t2/t1)/log(n2/n1); n log n gives about 1.1 here).

usage: bench/bench_3d_large.py [--acd build/acd] [--model armadillo.off] [--levels 1,2,3]
                               [--commands info,repair,3d,budget,segment,eval] [--threads N]
                               [--out FILE.md] [--timeout S] [--gen-only]
Results: docs/results/3d-large.md.
"""
import argparse
import math
import os
import re
import signal
import subprocess
import sys
import time
from array import array

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AMP = 0.02  # displacement amplitude, relative to the subdivided edge's length


def read_off(path):
    with open(path) as f:
        toks = []
        for line in f:
            line = line.split('#', 1)[0].strip()
            if line:
                toks.extend(line.split())
    if not toks[0].startswith('OFF'):
        raise SystemExit(f"{path}: not OFF")
    if toks[0] != 'OFF':  # COFF, NOFF, "OFF12 ...": not in the models this uses
        raise SystemExit(f"{path}: unsupported OFF header {toks[0]}")
    i = 1
    nv, nf = int(toks[i]), int(toks[i + 1])
    i += 3
    V = array('d', (float(t) for t in toks[i:i + 3 * nv]))
    i += 3 * nv
    F = array('i')
    for _ in range(nf):
        k = int(toks[i])
        idx = [int(t) for t in toks[i + 1:i + 1 + k]]
        i += 1 + k
        for j in range(1, k - 1):  # fan a polygon
            F.extend((idx[0], idx[j], idx[j + 1]))
    return V, F


def read_obj(path):
    V, F = array('d'), array('i')
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == 'v':
                V.extend(float(x) for x in p[1:4])
            elif p[0] == 'f':
                idx = [int(x.split('/')[0]) - 1 for x in p[1:]]
                for j in range(1, len(idx) - 1):
                    F.extend((idx[0], idx[j], idx[j + 1]))
    return V, F


def subdivide(V, F):
    """One 1-to-4 midpoint subdivision; each midpoint moved along the mean of its endpoints' normals
    by AMP * edge length * h, h in [-1, 1) a hash of the edge's vertex numbers (deterministic)."""
    nv = len(V) // 3
    N = array('d', bytes(8 * 3 * nv))
    for t in range(0, len(F), 3):
        a, b, c = F[t], F[t + 1], F[t + 2]
        ax, ay, az = V[3 * a], V[3 * a + 1], V[3 * a + 2]
        ux, uy, uz = V[3 * b] - ax, V[3 * b + 1] - ay, V[3 * b + 2] - az
        vx, vy, vz = V[3 * c] - ax, V[3 * c + 1] - ay, V[3 * c + 2] - az
        nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        for k in (a, b, c):
            N[3 * k] += nx
            N[3 * k + 1] += ny
            N[3 * k + 2] += nz
    W = array('d', V)
    emap = {}
    nF = array('i')

    def mid(a, b):
        key = a * nv + b if a < b else b * nv + a
        m = emap.get(key)
        if m is not None:
            return m
        ax, ay, az = V[3 * a], V[3 * a + 1], V[3 * a + 2]
        bx, by, bz = V[3 * b], V[3 * b + 1], V[3 * b + 2]
        nx, ny, nz = N[3 * a] + N[3 * b], N[3 * a + 1] + N[3 * b + 1], N[3 * a + 2] + N[3 * b + 2]
        nl = math.sqrt(nx * nx + ny * ny + nz * nz)
        el = math.sqrt((bx - ax) ** 2 + (by - ay) ** 2 + (bz - az) ** 2)
        h = ((key * 2654435761) & 0xffffffff) / 2147483648.0 - 1.0
        s = AMP * el * h / nl if nl > 0 else 0.0
        m = len(W) // 3
        W.extend((0.5 * (ax + bx) + s * nx, 0.5 * (ay + by) + s * ny, 0.5 * (az + bz) + s * nz))
        emap[key] = m
        return m

    for t in range(0, len(F), 3):
        a, b, c = F[t], F[t + 1], F[t + 2]
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        nF.extend((a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca))
    return W, nF


def write_off(path, V, F):
    tmp = path + '.part'
    with open(tmp, 'w') as f:
        f.write(f"OFF\n{len(V) // 3} {len(F) // 3} 0\n")
        B = 200000
        for s in range(0, len(V), 3 * B):
            f.write(''.join('%.9g %.9g %.9g\n' % (V[i], V[i + 1], V[i + 2])
                            for i in range(s, min(len(V), s + 3 * B), 3)))
        for s in range(0, len(F), 3 * B):
            f.write(''.join('3 %d %d %d\n' % (F[i], F[i + 1], F[i + 2])
                            for i in range(s, min(len(F), s + 3 * B), 3)))
    os.replace(tmp, path)


def make_inputs(model, levels):
    """/tmp/large-MODEL-L.off for each level (cached: made once)."""
    base = os.path.splitext(os.path.basename(model))[0]
    paths = {lv: f"/tmp/large-{base}-{lv}.off" for lv in levels}
    if all(os.path.exists(p) for p in paths.values()):
        return paths
    src = os.path.join(ROOT, 'data', 'meshes', model)
    V, F = read_obj(src) if src.endswith('.obj') else read_off(src)
    for lv in range(1, max(levels) + 1):
        t0 = time.time()
        V, F = subdivide(V, F)
        if lv in paths and not os.path.exists(paths[lv]):
            write_off(paths[lv], V, F)
        print(f"# made {base} level {lv}: {len(F) // 3} triangles ({time.time() - t0:.0f} s)",
              file=sys.stderr, flush=True)
    return paths


def run(cmd, timeout):
    """(wall s, stdout, stderr, exit code) of one child; SIGINT after timeout seconds."""
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        p.send_signal(signal.SIGINT)
        out, err = p.communicate()
        err += f"\n(timeout after {timeout} s)"
    return time.monotonic() - t0, out, err, p.returncode


TIMEFMT = "@@time %e %U %S %M"


def measure(cmd, timeout):
    """wall, cpu (user + system), user, rss (MiB, peak), rc, out, err: by /usr/bin/time when it is
    there, else by the children's rusage (whose peak RSS is the largest child's so far)."""
    if os.path.exists('/usr/bin/time'):
        wall, out, err, rc = run(['/usr/bin/time', '-f', TIMEFMT] + cmd, timeout)
        m = re.search(r"@@time ([\d.]+) ([\d.]+) ([\d.]+) (\d+)", err)
        if m:
            return dict(wall=float(m.group(1)), cpu=float(m.group(2)) + float(m.group(3)),
                        user=float(m.group(2)), rss=int(m.group(4)) / 1024.0, rc=rc, out=out, err=err)
        return dict(wall=wall, cpu=float('nan'), user=float('nan'), rss=float('nan'), rc=rc, out=out, err=err)
    import resource
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall, out, err, rc = run(cmd, timeout)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return dict(wall=wall, cpu=cpu, user=r1.ru_utime - r0.ru_utime, rss=r1.ru_maxrss / 1024.0, rc=rc, out=out,
                err=err)


def count_hulls(path):
    if not os.path.exists(path):
        return None
    n = 0
    with open(path) as f:
        for line in f:
            if line.startswith('o ') or line.startswith('g '):
                n += 1
    return n


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--acd', default=os.path.join(ROOT, 'build', 'acd'))
    ap.add_argument('--model', default='armadillo.off')
    ap.add_argument('--levels', default='1,2,3', help='subdivision levels (each x4 triangles); 0: the model')
    ap.add_argument('--commands', default='info,repair,3d,budget,segment,eval')
    ap.add_argument('--threads', default=None, help='--threads for acd 3d and acd segment (default: theirs)')
    ap.add_argument('--timeout', type=float, default=3600)
    ap.add_argument('--out', default=None, help='also write the table to this file')
    ap.add_argument('--gen-only', action='store_true')
    a = ap.parse_args()
    levels = [int(x) for x in a.levels.split(',')]
    paths = make_inputs(a.model, [lv for lv in levels if lv > 0])
    if 0 in levels:
        paths[0] = os.path.join(ROOT, 'data', 'meshes', a.model)
    if a.gen_only:
        for lv in levels:
            print(paths[lv])
        return
    cmds = a.commands.split(',')
    thr = ['--threads', a.threads] if a.threads else []
    tmp = f"/tmp/large-run-{os.getpid()}"
    os.makedirs(tmp, exist_ok=True)
    rows = []  # (command, level, triangles, result)
    tris = {}
    for lv in levels:
        if paths[lv].endswith('.off'):
            with open(paths[lv]) as f:
                f.readline()
                tris[lv] = int(f.readline().split()[1])
        else:
            V, F = read_obj(paths[lv])
            tris[lv] = len(F) // 3
    for lv in levels:
        p = paths[lv]
        hulls = f"{tmp}/d{lv}.obj"
        for c in cmds:
            if c == 'info':
                cmd = [a.acd, 'info', p]
            elif c == 'repair':
                cmd = [a.acd, 'info', p, '--repair', f"{tmp}/r{lv}.off"]
            elif c == '3d':
                cmd = [a.acd, '3d', p, '-o', hulls] + thr
            elif c == 'budget':
                cmd = [a.acd, '3d', p, '--budget', '43', '--trim-coverage', '0.0008', '-o', f"{tmp}/b{lv}.obj"] + thr
            elif c == 'segment':
                cmd = [a.acd, 'segment', p, '-o', f"{tmp}/s{lv}.obj"] + thr
            elif c == 'eval':
                if not os.path.exists(hulls):
                    continue
                cmd = [a.acd, 'eval', p, hulls]
            else:
                raise SystemExit(f"unknown command {c}")
            r = measure(cmd, a.timeout)
            parts = None
            if c in ('3d', 'budget', 'segment'):
                parts = count_hulls(cmd[cmd.index('-o') + 1])
                if r['rc'] != 0:
                    parts = None
            extra = ''
            if c == 'eval':
                m = re.search(r"IoU\D*([\d.]+)", r['out'])
                extra = f"IoU {m.group(1)}" if m else ''
            r.update(parts=parts, extra=extra)
            rows.append((c, lv, tris[lv], r))
            print(f"# {c} {tris[lv]}: wall {r['wall']:.2f} cpu {r['cpu']:.2f} rss {r['rss']:.0f} MiB "
                  f"rc {r['rc']} parts {parts} {extra}", file=sys.stderr, flush=True)
            if r['rc'] != 0:
                print(r['err'][-2000:], file=sys.stderr)
    lines = [f"| command | triangles | wall s | CPU s | peak RSS MiB | parts | CPU exponent | note |",
             "|---|---:|---:|---:|---:|---:|---:|---|"]
    for c in cmds:
        prev = None
        for (cc, lv, n, r) in rows:
            if cc != c:
                continue
            ex = ''
            if prev and prev[1]['cpu'] > 0.05 and r['cpu'] > 0:
                ex = '%.2f' % (math.log(r['cpu'] / prev[1]['cpu']) / math.log(n / prev[0]))
            note = r['extra'] + ('' if r['rc'] == 0 else f" exit {r['rc']}")
            lines.append(f"| {c} | {n:,} | {r['wall']:.2f} | {r['cpu']:.2f} | {r['rss']:.0f} | "
                         f"{'' if r['parts'] is None else r['parts']} | {ex} | {note} |")
            prev = (n, r)
    table = '\n'.join(lines)
    print(table)
    if a.out:
        with open(a.out, 'w') as f:
            f.write(table + '\n')


if __name__ == '__main__':
    main()
