// polydecomp.js: bench-only peer harness for bench_2d_experiments (docs/experiments-2d.md).
// Runs poly-decomp (npm) on one polygon; NODE_PATH or bench/peers/node_modules must hold it.
//
// usage: node polydecomp.js quick|exact POLY.txt PIECES.txt
//   quick: decomp.quickDecomp (Bayazit's heuristic; recursion capped by the library's maxlevel)
//   exact: decomp.decomp (the library's exhaustive minimal decomposition; run under a timeout)
// Prints "method,pieces,cpu_s" (process CPU time of the call only, process.cpuUsage).
'use strict';
const fs = require('fs');
const decomp = require('poly-decomp');

const [method, polyFile, piecesFile] = process.argv.slice(2);
if (!piecesFile || (method !== 'quick' && method !== 'exact')) {
  process.stderr.write('usage: node polydecomp.js quick|exact POLY.txt PIECES.txt\n');
  process.exit(2);
}
const tok = fs.readFileSync(polyFile, 'utf8').trim().split(/\s+/).map(Number);
const n = tok[0];
const poly = [];
for (let i = 0; i < n; i++) poly.push([tok[1 + 2 * i], tok[2 + 2 * i]]);
decomp.makeCCW(poly);
const c0 = process.cpuUsage();
const parts = method === 'quick' ? decomp.quickDecomp(poly) : decomp.decomp(poly);
const c = process.cpuUsage(c0);
const sec = (c.user + c.system) / 1e6;
const pieces = parts === false ? [] : parts;
let out = pieces.length + '\n';
for (const p of pieces) out += p.length + ' ' + p.map((v) => v[0].toPrecision(17) + ' ' + v[1].toPrecision(17)).join(' ') + '\n';
fs.writeFileSync(piecesFile, out);
process.stdout.write(`${method},${pieces.length},${sec}\n`);
