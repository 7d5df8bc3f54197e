#!/usr/bin/env python3
"""Audit of acd 3d on the OpenSCAD examples (scripts/fetch-openscad.sh): per STL file, `acd info`'s
components, then `acd 3d` default and `--budget 16 --trim-coverage 0.0008`, both with --verify,
their exit code, parts, the parts holding more than one body (edge-connected component after welding
equal coordinates) and `acd eval`'s IoU and concavity_max, as a markdown table on stdout.

usage: bench/audit_3d_openscad.py ACD [--dir data/meshes/openscad] [--base ACD_BASE] [--timeout S]
With --base, every run is repeated with that binary and its figures are shown beside.
"""
import argparse, glob, os, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import audit_3d_transforms as A  # noqa: E402


def bodies_per_part(obj):
    """[components] per 'o'/'g' group of an OBJ, vertices welded by their text."""
    verts, groups, cur = [], {}, None
    order = []
    with open(obj) as f:
        for line in f:
            s = line.split()
            if not s:
                continue
            if s[0] == 'v':
                verts.append(tuple(s[1:4]))
            elif s[0] in ('o', 'g'):
                cur = s[1]
                groups[cur] = []
                order.append(cur)
            elif s[0] == 'f':
                if cur not in groups:
                    groups[cur] = []
                    order.append(cur)
                groups[cur].append([verts[int(x.split('/')[0]) - 1] for x in s[1:]])
    out = []
    for g in order:
        parent = {}

        def find(x):
            while parent.setdefault(x, x) != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x
        for face in groups[g]:
            for i in range(len(face)):
                a, b = find(face[i]), find(face[(i + 1) % len(face)])
                if a != b:
                    parent[a] = b
        out.append(len({find(v) for face in groups[g] for v in face}))
    return out


def run(acd, stl, args, tmp, timeout):
    hulls, parts = os.path.join(tmp, 'h.obj'), os.path.join(tmp, 'p.obj')
    for p in (hulls, parts):
        if os.path.exists(p):
            os.remove(p)
    rc, out, err, sec, msg = A.run([acd, '3d', stl] + args + ['--verify', '-o', hulls, '--parts', parts], timeout)
    res = {'rc': rc, 'sec': sec, 'parts': '', 'multi': '', 'iou': '', 'cmax': ''}
    if rc == 0 and os.path.exists(parts):
        bp = bodies_per_part(parts)
        res['parts'] = len(bp)
        res['multi'] = sum(1 for c in bp if c > 1)
        e = A.eval_hulls(acd, stl, hulls, None, timeout)
        if e and e['rc'] == 0:
            res['iou'] = '%.6f' % e['iou']
            res['cmax'] = '%.6g' % e['concavity_max']
    elif rc != 0:
        res['err'] = (err.strip().splitlines() or [''])[-1][:120]  # the error itself: the last line
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('acd')
    ap.add_argument('--dir', default='data/meshes/openscad')
    ap.add_argument('--base')
    ap.add_argument('--timeout', type=float, default=300)
    a = ap.parse_args()
    files = sorted(glob.glob(os.path.join(a.dir, '*.stl')))
    if not files:
        sys.exit('audit_3d_openscad: no STL files in %s (run scripts/fetch-openscad.sh)' % a.dir)
    cfgs = [('default', []), ('budget', ['--budget', '16', '--trim-coverage', '0.0008'])]
    bins = [('new', a.acd)] + ([('base', a.base)] if a.base else [])
    head = ['file', 'triangles', 'bodies', 'setting']
    for tag, _ in bins:
        head += [tag + ': exit', 'parts', 'multi-body parts', 'IoU', 'concavity_max', 's']
    print('| ' + ' | '.join(head) + ' |')
    print('|' + '---|' * len(head))
    with tempfile.TemporaryDirectory() as tmp:
        for stl in files:
            info = subprocess.run([a.acd, 'info', stl], capture_output=True, text=True).stdout
            tri = comp = ''
            for line in info.splitlines():
                s = line.split()
                if s[:1] == ['faces']:
                    tri = s[1]
                if s[:1] == ['components']:
                    comp = s[1]
            for cname, cargs in cfgs:
                row = [os.path.basename(stl), tri, comp, cname]
                for tag, b in bins:
                    r = run(b, stl, cargs, tmp, a.timeout)
                    row += [str(r['rc']) + (' (' + r['err'] + ')' if r.get('err') else ''), str(r.get('parts', '')),
                            str(r.get('multi', '')), r.get('iou', ''), r.get('cmax', ''), '%.1f' % r['sec']]
                print('| ' + ' | '.join(row) + ' |', flush=True)


if __name__ == '__main__':
    main()
