#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// npm run bench [-- [--tvf build/tvf] [--repeat N] [--big-repeat N] [--no-big] [--amd | --compare] [MESH.off ...]]
//
// Runs the native `tvf bench MESH --json --repeat N` over the mesh ladder (~15k to ~133k edges, real meshes
// from Debian's libcgal-demo, fetched by scripts/fetch-meshes.sh) plus a 1.25M-edge subdivided armadillo,
// prints a markdown table (Sec. 6.1 style: times in ms, medians over the repeats) and writes
// bench-data/bench-native.json. Build the binary first: npm run build:native.
// METIS nested dissection by default; --amd for AMD; --compare for both (interleaved in one process per mesh,
// one table row per mesh and ordering).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
export const MESH_DIR = resolve(ROOT, 'bench-data/meshes');
// Smallest to largest (edge counts from `tvf info`).
export const LADDER = ['homer', 'knot2', 'lion-head', 'camel', 'mannequin-devil', 'man', 'diplodocus', 'armadillo',
  'bunny00', 'refined_elephant'];
export const BIG = 'armadillo-sub2'; // 1,248,000 edges

export function meshPath(name) {
  return name.includes('/') || name.endsWith('.off') ? resolve(name) : resolve(MESH_DIR, `${name}.off`);
}

export function meshName(path) {
  return path.replace(/^.*\//, '').replace(/\.[^.]*$/, '');
}

// Makes sure the ladder's meshes exist (scripts/fetch-meshes.sh is idempotent and quick when they do).
export function ensureMeshes(paths) {
  if (paths.every((p) => existsSync(p))) return;
  console.error('bench: fetching meshes (scripts/fetch-meshes.sh)');
  execFileSync('bash', [resolve(ROOT, 'scripts/fetch-meshes.sh')], { stdio: ['ignore', 'ignore', 'inherit'] });
  const missing = paths.filter((p) => !existsSync(p));
  if (missing.length) throw new Error(`missing meshes: ${missing.join(', ')}`);
}

// `extra`: ['--amd'] for AMD, ['--compare'] for both orderings (the CLI defaults to METIS, as the page does).
export function runNative(tvf, mesh, repeat, extra = []) {
  const out = execFileSync(tvf, ['bench', mesh, '--json', '--repeat', String(repeat), ...extra], {
    encoding: 'utf8',
    maxBuffer: 1 << 24,
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  return JSON.parse(out);
}

// The median of the numbers (NaN for none).
export const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  return s.length === 0 ? NaN : s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

export const fmt = (x, digits = 1) =>
  x === undefined || x === null || Number.isNaN(x) ? '–' : Number(x).toFixed(x >= 100 ? 0 : digits);

export function nativeTable(rows) {
  const head = '| mesh | E | nnz/row M | nnz/row L | analyze | factor | solve | update | 50-edge stroke+solve | reconstruct |';
  const lines = [head, '|' + ' --- |'.repeat(10)];
  for (const r of rows) {
    if (r.error) {
      lines.push(`| ${r.name} | – | ${r.error} |`);
      continue;
    }
    lines.push(`| ${r.name} | ${r.edges.toLocaleString('en-US')} | ${fmt(r.nnzPerRowM)} | ${fmt(r.nnzPerRowL)} | ` +
      `${fmt(r.analyzeMs)} | ${fmt(r.factorMs)} | ${fmt(r.solveMs, 2)} | ${fmt(r.updateMs, 2)} | ` +
      `${fmt(r.strokeUpdateSolveMs)} | ${fmt(r.reconstructMs)} |`);
  }
  return lines.join('\n');
}

export function parseArgs(argv, extraFlags = {}) {
  const opts = { tvf: resolve(ROOT, 'build/tvf'), repeat: 5, bigRepeat: 2, big: true, meshes: [], ...extraFlags };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--tvf') opts.tvf = resolve(argv[++i]);
    else if (a === '--repeat') opts.repeat = Number(argv[++i]);
    else if (a === '--big-repeat') opts.bigRepeat = Number(argv[++i]);
    else if (a === '--no-big') opts.big = false;
    else if (a.startsWith('--') && a.slice(2) in extraFlags) {
      const key = a.slice(2);
      opts[key] = typeof extraFlags[key] === 'boolean' ? true : argv[++i];
    } else if (a.startsWith('--')) throw new Error(`unknown option ${a}`);
    else opts.meshes.push(a);
  }
  if (!opts.meshes.length) opts.meshes = [...LADDER, ...(opts.big ? [BIG] : [])];
  opts.meshes = opts.meshes.map(meshPath);
  return opts;
}

export const repeatFor = (opts, mesh) => (meshName(mesh) === BIG ? opts.bigRepeat : opts.repeat);

async function main() {
  const opts = parseArgs(process.argv.slice(2), { amd: false, compare: false });
  const extra = opts.compare ? ['--compare'] : opts.amd ? ['--amd'] : [];
  if (!existsSync(opts.tvf)) {
    console.error(`bench: ${opts.tvf} not found; build it: npm run build:native`);
    process.exit(1);
  }
  ensureMeshes(opts.meshes);
  const rows = [];
  for (const mesh of opts.meshes) {
    const name = meshName(mesh);
    process.stderr.write(`bench: ${name} ... `);
    try {
      const r = runNative(opts.tvf, mesh, repeatFor(opts, mesh), extra);
      if (r.metis) for (const o of ['metis', 'amd']) rows.push({ name: `${name} (${o === 'metis' ? 'METIS' : 'AMD'})`, mesh, edges: r.edges, ...r[o] });
      else rows.push({ name, ...r });
      process.stderr.write(`${r.edges} edges, factor ${fmt((r.metis ?? r).factorMs)} ms\n`);
    } catch (err) {
      const msg = (err.stderr?.toString() || err.message).trim().split('\n').pop();
      rows.push({ name, mesh, error: msg });
      process.stderr.write(`FAILED: ${msg}\n`);
    }
  }
  const table = nativeTable(rows);
  console.log(table);
  mkdirSync(resolve(ROOT, 'bench-data'), { recursive: true });
  const out = resolve(ROOT, 'bench-data/bench-native.json');
  writeFileSync(out, JSON.stringify({ date: new Date().toISOString(), tvf: opts.tvf, results: rows }, null, 2) + '\n');
  console.error(`bench: wrote ${out}`);
  if (rows.some((r) => r.error)) process.exit(1);
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) await main();
