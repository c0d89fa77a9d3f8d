// The shape of web/ (docs/architecture.md), checked on the source: every module imports only its own layer or
// the layers below it, there is no import cycle, no module keeps mutable state at the top level (each
// <tangent-field-designer> owns its state), no file grows past 400 lines, and no line of web/ or core/ past 120
// columns (clang-format's ColumnLimit for core/ is 110; 120 leaves room for what it cannot break).
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import test from 'node:test';
import { fileURLToPath } from 'node:url';

const WEB = resolve(dirname(fileURLToPath(import.meta.url)), '../../web');
const CORE = resolve(WEB, '../core');
const MAX_COLUMNS = 120;

// Higher imports lower, never the reverse. Entry points (the page, the package entries, the core's worker)
// compose a whole program and may import any layer; they sit at the top of web/, and every module inside a
// layer's folder is checked, core/'s worker ops included: that core/ imports nothing of synthesis/, session/ or
// element/ is this rule (they are all above it).
export const LAYERS = {
  element: 7, export: 6, synthesis: 6, stripes: 6, quad: 6, tools: 6, views: 5, session: 4, core: 3, geometry: 2, '.': 1,
};
const ENTRY_POINTS = new Set(['index.js', 'main.js', 'element-entry.js', 'core-worker.js']);

function sources(dir = WEB, extensions = ['.js']) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    if (e.isDirectory()) return sources(join(dir, e.name), extensions);
    return extensions.some((x) => e.name.endsWith(x)) ? [join(dir, e.name)] : [];
  });
}

const layerOf = (file) => {
  const rel = relative(WEB, file);
  return rel.includes('/') ? rel.split('/')[0] : '.';
};

function localImports(file) {
  const text = readFileSync(file, 'utf8');
  const specs = [...text.matchAll(/^\s*(?:import|export)\s[^;]*?from\s+['"](\.[^'"]+)['"]/gms)].map((m) => m[1]);
  return specs.filter((s) => s.endsWith('.js')).map((s) => resolve(dirname(file), s));
}

const files = sources();

test('web/ has a layer for every folder', () => {
  for (const f of files) assert.ok(layerOf(f) in LAYERS, `${relative(WEB, f)} is in no layer of docs/architecture.md`);
});

test('layers import downward only', () => {
  const upward = [];
  for (const f of files) {
    const rel = relative(WEB, f);
    if (ENTRY_POINTS.has(rel)) continue;
    for (const target of localImports(f)) {
      const from = layerOf(f), to = layerOf(target);
      if (from !== to && LAYERS[to] >= LAYERS[from]) upward.push(`${rel} → ${relative(WEB, target)}`);
    }
  }
  assert.deepEqual(upward, []);
});

test('no import cycles', () => {
  const graph = new Map(files.map((f) => [f, localImports(f)]));
  const state = new Map();
  const cycles = [];
  const visit = (f, path) => {
    if (state.get(f) === 'done') return;
    if (state.get(f) === 'open') return void cycles.push([...path.slice(path.indexOf(f)), f].map((p) => relative(WEB, p)).join(' → '));
    state.set(f, 'open');
    for (const g of graph.get(f) ?? []) visit(g, [...path, f]);
    state.set(f, 'done');
  };
  for (const f of files) visit(f, []);
  assert.deepEqual(cycles, []);
});

test('no module-level mutable state', () => {
  const found = [];
  for (const f of files) {
    const lines = readFileSync(f, 'utf8').split('\n');
    lines.forEach((line, k) => {
      if (/^(let|var)\s/.test(line) || /^const\s+\w+\s*=\s*new\s+(Map|Set|WeakMap|Array)\b/.test(line)) found.push(`${relative(WEB, f)}:${k + 1}: ${line.trim()}`);
    });
  }
  assert.deepEqual(found, []);
});

test('no JS file over 400 lines', () => {
  const long = files.map((f) => [relative(WEB, f), readFileSync(f, 'utf8').split('\n').length - 1]).filter(([, n]) => n > 400);
  assert.deepEqual(long, []);
});

test(`no line over ${MAX_COLUMNS} columns in web/ (.js, .css) or core/ (.cpp, .h)`, () => {
  const wide = [];
  for (const f of [...sources(WEB, ['.js', '.css']), ...sources(CORE, ['.cpp', '.h'])]) {
    readFileSync(f, 'utf8')
      .split('\n')
      .forEach((line, k) => {
        // Columns are characters (code points), not UTF-16 units: 'γ' and '→' take one column each.
        const columns = [...line].length;
        if (columns > MAX_COLUMNS) wide.push(`${relative(resolve(WEB, '..'), f)}:${k + 1}: ${columns} columns`);
      });
  }
  assert.deepEqual(wide, []);
});

// A count written for people goes through dom.js's grouped(), never toLocaleString or Intl: their first call loads
// the locale's data on the main thread (72 ms in a big model's load, 182 ms as armadillo-sub2's quad mesh arrived).
test('counts are grouped without the locale data (no toLocaleString or Intl in web/)', async () => {
  const found = files.filter((f) => /\.toLocaleString\(|\bIntl\./.test(readFileSync(f, 'utf8'))).map((f) => relative(WEB, f));
  assert.deepEqual(found, []);
  const { grouped } = await import('../../web/dom.js');
  assert.deepEqual([0, 7, 999, 1000, 832000, 1248000.4, 999999.6].map(grouped),
    ['0', '7', '999', '1,000', '832,000', '1,248,000', '1,000,000']);
});
