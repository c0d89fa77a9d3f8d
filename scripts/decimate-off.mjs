#!/usr/bin/env node
// A low-poly stand-in of a fetched model, for measuring what the page does on coarse but curved meshes (the
// synthesized texture's defaults, docs/texture-synthesis.md): meshoptimizer's quadric simplifier (edge
// collapses, borders locked) down to about FACES faces, the unused vertices dropped, written as OFF. The result
// is checked by the core when it is opened; `tvf info OUT` reports its topology (genus, boundaries).
//   node scripts/decimate-off.mjs IN.off OUT.off FACES
import { readFileSync, writeFileSync } from 'node:fs';
import { MeshoptSimplifier } from 'meshoptimizer';

const [input, output, facesArg] = process.argv.slice(2);
if (!input || !output || !(Number(facesArg) > 0)) {
  console.error('usage: node scripts/decimate-off.mjs IN.off OUT.off FACES');
  process.exit(2);
}
const words = readFileSync(input, 'utf8').replace(/#.*$/gm, '').split(/\s+/).filter(Boolean);
const nV = Number(words[1]), nF = Number(words[2]);
const positions = Float32Array.from(words.slice(4, 4 + 3 * nV), Number);
const indices = new Uint32Array(3 * nF);
for (let f = 0, i = 4 + 3 * nV; f < nF; f++, i += 4) {
  if (words[i] !== '3') throw new Error(`${input}: face ${f} is not a triangle`);
  for (let k = 0; k < 3; k++) indices[3 * f + k] = Number(words[i + 1 + k]);
}
await MeshoptSimplifier.ready;
const [kept] = MeshoptSimplifier.simplify(indices, positions, 3, 3 * Number(facesArg), 1, ['LockBorder']);
const remap = new Map();
const used = [];
for (const v of kept) if (!remap.has(v)) remap.set(v, remap.size), used.push(v);
const lines = [`OFF\n${used.length} ${kept.length / 3} 0`];
for (const v of used) lines.push(`${positions[3 * v]} ${positions[3 * v + 1]} ${positions[3 * v + 2]}`);
for (let f = 0; f < kept.length; f += 3) lines.push(`3 ${remap.get(kept[f])} ${remap.get(kept[f + 1])} ${remap.get(kept[f + 2])}`);
writeFileSync(output, lines.join('\n') + '\n');
console.log(`${output}: ${used.length} vertices, ${kept.length / 3} faces (from ${nF})`);
