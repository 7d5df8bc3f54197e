#!/usr/bin/env python3
"""Robustness sweep of acd 2d --verify far from the origin and scaled (docs/results/2d-far.md).

usage: bench_2d_far.py ACD XFORM SHARED_DATA REPO_DATA_2D OUT.csv GENDIR
  ACD: the acd executable; XFORM: build/bench/bench_2d_far_xform; SHARED_DATA: ../shared/data;
  REPO_DATA_2D: data/2d; GENDIR: where the transformed inputs go (reused if present).
Every polygon of polygons-lien, data/2d/cgal, data/2d/glyphs and four countries of
world-atlas/countries-50m, as is, translated by 1e4..1e10 x its extent, scaled by 1e-6 and 1e6
(tau and notch tolerance scaled with it); every measure at tau 0.05 and 0, and --exact hm, mcd
(mcd below 1500 vertices). Appends to OUT.csv (resumes); 2 runs at a time.
bench_2d_far.py --summary OUT.csv prints the pass / refused / fail table."""
import csv, collections, glob, os, subprocess, sys, concurrent.futures as cf

def summary(path):
    rows = list(csv.DictReader(open(path)))
    def cls(r):
        if r['rc'] == '0': return 'pass'
        if r['rc'] == '2' and 'unsupported' in r['msg']: return 'n/a'
        if r['rc'] == '2': return 'refused'
        if r['rc'] == '3': return 'FAIL'
        return 'other:' + r['rc']
    tab = collections.defaultdict(collections.Counter)
    for r in rows:
        tab[(r['xform'], 'exact' if r['measure'].startswith('exact') else 'acd')][cls(r)] += 1
    print('| transform | ACD runs: pass / refused / fail | exact (hm, mcd) runs: pass / refused / fail |')
    print('|---|---|---|')
    for x in ['id', 'off1e4', 'off1e6', 'off1e8', 'off1e10', 'sc1e-6', 'sc1e6']:
        a, e = tab[(x, 'acd')], tab[(x, 'exact')]
        print(f"| {x} | {a['pass']} / {a['refused']} / {a['FAIL']} | {e['pass']} / {e['refused']} / {e['FAIL']} |")
    print('total', dict(collections.Counter(cls(r) for r in rows)))

if sys.argv[1] == '--summary':
    summary(sys.argv[2]); sys.exit(0)
ACD, XF, SHARED, D2, OUT, G = sys.argv[1:7]
os.makedirs(G, exist_ok=True)
files = sorted(f for f in glob.glob(SHARED + '/polygons-lien/*.poly'))
files += sorted(glob.glob(D2 + '/cgal/*.poly')) + sorted(glob.glob(D2 + '/glyphs/*.poly'))
files = [(f, None) for f in files]
files += [(D2 + '/world-atlas/countries-50m.json', 'name=' + c) for c in ['South Africa', 'Italy', 'Norway', 'Chile']]
xforms = [('id', 'off', 0.0), ('off1e4', 'off', 1e4), ('off1e6', 'off', 1e6), ('off1e8', 'off', 1e8),
          ('off1e10', 'off', 1e10), ('sc1e-6', 'scale', 1e-6), ('sc1e6', 'scale', 1e6)]
jobs = []
for f, feat in files:
    base = os.path.splitext(os.path.basename(f))[0] if not feat else feat[5:].replace(' ', '_')
    for name, mode, k in xforms:
        out = f'{G}/{base}__{name}.poly'
        if not os.path.exists(out):
            r = subprocess.run([XF, f, out, mode, repr(k)] + ([feat] if feat else []), capture_output=True, text=True)
            if r.returncode:
                print('xform', f, name, r.stderr.strip()); continue
        s = k if mode == 'scale' else 1.0
        for m in ['sl', 'sp', 'h1', 'h2']:
            for tau in [0.05, 0.0]:
                args = [ACD, '2d', out, '-m', m, '-t', repr(tau * s), '--notch-eps', repr(1e-5 * s * s), '--verify']
                jobs.append((base, name, m, repr(tau), args))
        nv = sum(1 for _ in open(out)) if mode else 0
        for ex in (['hm', 'mcd'] if nv < 1500 else ['hm']):
            jobs.append((base, name, 'exact-' + ex, '-', [ACD, '2d', out, '--exact', ex, '--verify']))
def run(j):
    base, name, m, tau, args = j
    try:
        r = subprocess.run(args, capture_output=True, text=True, timeout=300)
        rc, msg = r.returncode, (r.stderr.strip().splitlines() or [''])[-1][:300]
    except subprocess.TimeoutExpired:
        rc, msg = 'timeout', ''
    return (base, name, m, tau, rc, msg)
done = set()
if os.path.exists(OUT):
    for r in csv.DictReader(open(OUT)):
        done.add((r['file'], r['xform'], r['measure'], r['tau']))
jobs = [j for j in jobs if j[:4] not in done]
print(len(jobs), 'jobs to run')
new = not os.path.exists(OUT)
with cf.ThreadPoolExecutor(2) as ex, open(OUT, 'a', newline='') as fo:
    w = csv.writer(fo)
    if new: w.writerow(['file', 'xform', 'measure', 'tau', 'rc', 'msg'])
    for row in ex.map(run, jobs):
        w.writerow(row); fo.flush()
