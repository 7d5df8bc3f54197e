// Bench-only harness (never part of libacd or CI): V-HACD 4 (kmammou/v-hacd, BSD-3-Clause) as
// compiled to WebAssembly by the npm package vhacd-js, run on one mesh.
//
// usage: node vhacd_run.mjs MODULE_DIR INPUT.(obj|off) HULLS.obj [maxHulls]
//   MODULE_DIR: the node_modules directory holding vhacd-js (bench/peers/vhacd.sh installs it).
//   Without maxHulls, V-HACD's defaults (64 hulls, 400000 voxels, 1% volume error, depth 10).
// Prints "hulls,cpu_seconds" (CPU of computeConvexHulls only, user + system, from
// process.cpuUsage) and writes the hulls as one OBJ with one `o` group per hull (full precision).
import { readFileSync, writeFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import { join } from "node:path";

const [moduleDir, input, output, maxHulls] = process.argv.slice(2);
if (!moduleDir || !input || !output) {
  console.error("usage: node vhacd_run.mjs MODULE_DIR INPUT.(obj|off) HULLS.obj [maxHulls]");
  process.exit(1);
}

// Triangles of an OBJ or OFF file (polygons fanned from their first corner).
function readMesh(path) {
  const text = readFileSync(path, "utf8");
  const pos = [];
  const idx = [];
  const fan = (f) => {
    for (let i = 1; i + 1 < f.length; i++) idx.push(f[0], f[i], f[i + 1]);
  };
  if (/\.off$/i.test(path)) {
    const tok = text.replace(/#[^\n]*/g, " ").split(/\s+/).filter((s) => s.length);
    let k = 0;
    if (/^[A-Z]*OFF$/.test(tok[0])) k++;
    const nv = parseInt(tok[k++], 10);
    const nf = parseInt(tok[k++], 10);
    k++; // edges
    for (let i = 0; i < 3 * nv; i++) pos.push(parseFloat(tok[k++]));
    for (let i = 0; i < nf; i++) {
      const n = parseInt(tok[k++], 10);
      const f = [];
      for (let j = 0; j < n; j++) f.push(parseInt(tok[k++], 10));
      fan(f);
    }
  } else {
    let nv = 0;
    for (const line of text.split("\n")) {
      const w = line.trim().split(/\s+/);
      if (w[0] === "v") {
        pos.push(+w[1], +w[2], +w[3]);
        nv++;
      } else if (w[0] === "f") {
        fan(w.slice(1).map((s) => {
          const i = parseInt(s.split("/")[0], 10);
          return i < 0 ? nv + i : i - 1;
        }));
      }
    }
  }
  for (const x of pos) if (!Number.isFinite(x)) throw new Error(`${path}: a coordinate is not finite`);
  for (const i of idx) if (!(i >= 0 && 3 * i < pos.length)) throw new Error(`${path}: face index ${i} out of range`);
  return { positions: new Float64Array(pos), indices: new Uint32Array(idx) };
}

const mod = await import(pathToFileURL(join(moduleDir, "vhacd-js", "lib", "vhacd.js")).href);
const mesh = readMesh(input);
const decomposer = await mod.ConvexMeshDecomposition.create();
const options = maxHulls ? { maxHulls: parseInt(maxHulls, 10) } : undefined;
const c0 = process.cpuUsage();
const hulls = decomposer.computeConvexHulls(mesh, options);
const c1 = process.cpuUsage(c0);
const out = [];
let base = 1;
hulls.forEach((h, i) => {
  out.push(`o hull_${i}`);
  for (let k = 0; k < h.positions.length; k += 3)
    out.push(`v ${h.positions[k]} ${h.positions[k + 1]} ${h.positions[k + 2]}`);
  for (let k = 0; k < h.indices.length; k += 3)
    out.push(`f ${h.indices[k] + base} ${h.indices[k + 1] + base} ${h.indices[k + 2] + base}`);
  base += h.positions.length / 3;
});
writeFileSync(output, out.join("\n") + "\n");
console.log(`${hulls.length},${((c1.user + c1.system) / 1e6).toFixed(2)}`);
