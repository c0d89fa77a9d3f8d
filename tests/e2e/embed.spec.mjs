// <tangent-field-designer> embedded in other people's pages, from the tarball `npm pack` makes, installed
// into a scratch project and served by a plain static server (no COOP/COEP) that sends a strict CSP
// (scripts/serve.mjs --plain --csp). Checks independence of two elements, hostile host CSS, CSP, a bundled
// consumer app, node imports, that removed elements leave no worker and no WebGL context behind, and that the
// package's default (peer) build in a page that already uses three.js loads no second copy of three.
// The plain pages use the standalone bundle (script tag); the bundled app and the three.js page the peer build.
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { cpSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import * as esbuild from 'esbuild';
import { faceVector, relativeDifference, trackErrors } from './helpers.mjs';
import { icosphereOff } from '../icosphere.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const FIXTURES = resolve(ROOT, 'tests/e2e/embed');
const SITE = resolve(ROOT, '.cache/embed-site'); // served by the second web server (playwright.config.mjs)
const PACK = resolve(ROOT, '.cache/embed-pack');
const PORT = Number(process.env.TVF_EMBED_PORT || Number(process.env.TVF_TEST_PORT || 8191) + 100);
const ORIGIN = `http://127.0.0.1:${PORT}`;

test.describe.configure({ mode: 'serial' });

test.beforeAll(async () => {
  test.setTimeout(600_000);
  // The package as a user gets it: npm pack (prepack builds lib/), installed into a scratch project that has
  // its peer dependencies (three, three-mesh-bvh) as its own dependencies, packed from our node_modules (the
  // versions we build with; npm's cache need not hold their registry documents).
  rmSync(PACK, { recursive: true, force: true });
  mkdirSync(PACK, { recursive: true });
  execFileSync('npm', ['pack', '--pack-destination', PACK], { cwd: ROOT, stdio: 'pipe' });
  const tarball = resolve(PACK, readdirSync(PACK).find((f) => f.endsWith('.tgz')));
  const peerDirs = ['three', 'three-mesh-bvh'].map((p) => resolve(ROOT, 'node_modules', p));
  const peers = execFileSync('npm', ['pack', '--ignore-scripts', '--pack-destination', PACK, ...peerDirs], { cwd: ROOT, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] })
    .split('\n').map((f) => f.trim()).filter((f) => f.endsWith('.tgz')).map((f) => resolve(PACK, f));
  expect(peers).toHaveLength(2);
  for (const f of readdirSync(SITE, { withFileTypes: true })) rmSync(resolve(SITE, f.name), { recursive: true, force: true });
  writeFileSync(resolve(SITE, 'package.json'), JSON.stringify({ name: 'scratch', private: true, type: 'module' }));
  execFileSync('npm', ['install', '--offline', '--no-audit', '--no-fund', tarball, ...peers], { cwd: SITE, stdio: 'pipe' });
  writeFileSync(resolve(SITE, 'index.html'), '<!doctype html><title>embed tests</title>');
  cpSync(FIXTURES, SITE, { recursive: true });
  mkdirSync(resolve(SITE, 'models'), { recursive: true });
  cpSync(resolve(ROOT, 'dist/models/bunny.glb'), resolve(SITE, 'models/bunny.glb'));
  writeFileSync(resolve(SITE, 'models/ico.off'), icosphereOff(2));
  mkdirSync(resolve(SITE, 'designs'), { recursive: true });
  writeFileSync(resolve(SITE, 'designs/two-sources.json'), JSON.stringify({ boundary: 'free', gamma: 0, constraints: [{ type: 'source', vertex: 0, strength: 1 }, { type: 'sink', vertex: 3, strength: 1 }] }));
  writeFileSync(resolve(SITE, 'models/broken.glb'), Buffer.from('glTF this is not a binary glTF at all'));
  // The bundled consumer app: its code and ours in one file; our worker and wasm copied as the docs say.
  await esbuild.build({
    entryPoints: [resolve(SITE, 'app-src.js')],
    outfile: resolve(SITE, 'app/app.js'),
    bundle: true,
    format: 'esm',
    absWorkingDir: SITE,
    logLevel: 'error',
  });
  cpSync(resolve(SITE, 'node_modules/tangent-field-designer/lib'), resolve(SITE, 'app/tangent-field-designer'), { recursive: true });
});

const LIB = resolve(SITE, 'node_modules/tangent-field-designer/lib');
// Strings only three.js's and three-mesh-bvh's own code has (they survive minification).
const THREE_MARK = 'Multiple instances of Three.js being imported';
const BVH_MARK = 'MeshBVH: ';
const count = (text, mark) => text.split(mark).length - 1;

// Fraction of the central 40×40 pixels of a designer's canvas that differ from its background: > 0.5 when the
// model is drawn.
const coverage = (page, id) =>
  page.evaluate((id) => {
    const src = document.getElementById(id).shadowRoot.querySelector('canvas');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const d = g.getImageData(src.width / 2 - 20, src.height / 2 - 20, 40, 40).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 0x1b) + Math.abs(d[i + 1] - 0x1d) + Math.abs(d[i + 2] - 0x21) > 24) n++;
    return n / (d.length / 4);
  }, id);

// A site with the strict CSP and an inline import map allows that map by its hash: the server's policy with
// 'sha256-…' of the map added to script-src, for the pages that have one.
async function allowImportMaps(page) {
  await page.route(`${ORIGIN}/**/*.html`, async (route) => {
    const response = await route.fetch();
    const body = await response.text();
    const headers = response.headers();
    const map = body.match(/<script type="importmap">([\s\S]*?)<\/script>/);
    if (map) {
      const hash = createHash('sha256').update(map[1]).digest('base64');
      headers['content-security-policy'] = headers['content-security-policy'].replace("script-src 'self'", `script-src 'self' 'sha256-${hash}'`);
    }
    await route.fulfill({ response, body, headers });
  });
}

// Requests that left the server's origin, and CSP violations the page reported.
function watchRequests(page) {
  const foreign = [];
  page.on('request', (r) => {
    const url = r.url();
    if (!url.startsWith(ORIGIN) && !url.startsWith('blob:') && !url.startsWith('data:')) foreign.push(url);
  });
  return foreign;
}

// For the pages that load three.js: errors, three's warning that a second copy loaded, requests that left the
// origin, and the paths of every request.
function watchThree(page) {
  const errors = trackErrors(page);
  const warnings = [];
  page.on('console', (m) => /Multiple instances of Three/.test(m.text()) && warnings.push(m.text()));
  const foreign = watchRequests(page);
  const requests = [];
  page.on('request', (r) => requests.push(new URL(r.url()).pathname));
  return { errors, warnings, foreign, requests };
}

const record = (page) => page.evaluate(() => ({ events: window.__record.events.map(({ type, id }) => ({ type, id })), violations: window.__record.violations }));

test('the package imports in node without a DOM', () => {
  for (const spec of ['tangent-field-designer', 'tangent-field-designer/element', 'tangent-field-designer/standalone', 'tangent-field-designer/standalone/element']) {
    const out = execFileSync(
      process.execPath,
      ['--input-type=module', '-e', `const m = await import('${spec}'); console.log([typeof m.TangentFieldDesigner, typeof m.define, m.define() === m.TangentFieldDesigner].join(' '));`],
      { cwd: SITE, encoding: 'utf8' },
    );
    expect(out.trim()).toBe('function function true');
  }
});

test('two designers on one page under a strict CSP: independent fields, events, errors and styles', async ({ page }) => {
  const errors = trackErrors(page);
  const foreign = watchRequests(page);
  const response = await page.goto(`${ORIGIN}/two.html`);
  // The page is served as a plain static host would, with the strict policy.
  const headers = response.headers();
  expect(headers['content-security-policy']).toContain("script-src 'self' 'wasm-unsafe-eval'");
  expect(headers['cross-origin-embedder-policy']).toBeUndefined();
  expect(await page.evaluate(() => window.crossOriginIsolated)).toBe(false);

  await page.evaluate(() => Promise.all([document.getElementById('a').ready, document.getElementById('b').ready]));
  const faces = await page.evaluate(() => ['a', 'b'].map((id) => document.getElementById(id).info().faces));
  expect(faces).toEqual([3674, 320]);
  expect(await page.evaluate(() => typeof window.tvf)).toBe('undefined');
  expect((await record(page)).events.filter((e) => e.type === 'load')).toEqual([
    expect.objectContaining({ type: 'load' }),
    expect.objectContaining({ type: 'load' }),
  ]);
  expect(new Set((await record(page)).events.filter((e) => e.type === 'load').map((e) => e.id))).toEqual(new Set(['a', 'b']));

  // Hostile host CSS reaches neither the canvas nor the controls.
  const look = await page.evaluate(() => {
    const root = document.getElementById('a').shadowRoot;
    const canvas = root.querySelector('canvas'), button = root.querySelector('[data-tool="stroke"]');
    const cs = (el) => getComputedStyle(el);
    const r = canvas.getBoundingClientRect();
    return {
      canvas: [cs(canvas).display, cs(canvas).visibility, cs(canvas).opacity, Math.round(r.width) > 200, Math.round(r.height) > 150],
      button: [cs(button).display, cs(button).fontSize, cs(button).color, cs(button).backgroundColor],
      panel: cs(root.querySelector('.toolbar')).visibility,
    };
  });
  expect(look.canvas).toEqual(['block', 'visible', '1', true, true]);
  expect(look.button[0]).not.toBe('none');
  expect(look.button[1]).toBe('13px');
  expect(look.button[2]).not.toBe('rgb(255, 0, 0)');
  expect(look.button[3]).not.toBe('rgb(255, 0, 0)');
  expect(look.panel).toBe('visible');
  // The model is drawn: the canvas centre differs from the background colour.
  expect(await coverage(page, 'a')).toBeGreaterThan(0.5);

  // A mouse stroke across the middle of a: only a's field and constraints change, events only on a.
  const before = await page.evaluate(() => ({ a: Array.from(document.getElementById('a').faceVectors()), b: Array.from(document.getElementById('b').faceVectors()) }));
  const eventsBefore = (await record(page)).events.length;
  await page.evaluate(() => (document.getElementById('a').tool = 'stroke'));
  const box = await page.locator('#a').boundingBox();
  const y = box.y + box.height * 0.6;
  const [x0, x1] = [box.x + box.width * 0.42, box.x + box.width * 0.58];
  expect(await page.evaluate(([x, y]) => document.getElementById('a').pick(x, y) !== null, [x0, y])).toBe(true);
  await page.mouse.move(x0, y);
  await page.mouse.down();
  await page.mouse.move(x1, y, { steps: 25 });
  await page.mouse.up();
  await expect.poll(() => page.evaluate(() => document.getElementById('a').constraints().length)).toBe(1);
  await page.evaluate(() => document.getElementById('a').ready);
  const after = await page.evaluate(() => ({ a: Array.from(document.getElementById('a').faceVectors()), b: Array.from(document.getElementById('b').faceVectors()), bc: document.getElementById('b').constraints().length }));
  expect(relativeDifference(after.a, before.a)).toBeGreaterThan(1e-3);
  expect(after.b).toEqual(before.b);
  expect(after.bc).toBe(0);
  const [stroke] = await page.evaluate(() => document.getElementById('a').constraints());
  expect(stroke.type).toBe('stroke');
  expect(faceVector(after.a, stroke.points[0].face).some((x) => x !== 0)).toBe(true);
  await expect.poll(async () => (await record(page)).events.slice(eventsBefore).filter((e) => e.type === 'fieldchange').length).toBeGreaterThan(0);
  const strokeEvents = (await record(page)).events.slice(eventsBefore);
  expect(strokeEvents.map((e) => e.type)).toEqual(expect.arrayContaining(['fieldchange', 'constraintschange']));
  expect(strokeEvents.every((e) => e.id === 'a')).toBe(true);

  // A broken src on b: `error` on b, b keeps its model and field, a hears nothing.
  const mark = (await record(page)).events.length;
  await page.evaluate(() => (document.getElementById('b').src = 'models/broken.glb'));
  await expect.poll(async () => (await record(page)).events.slice(mark).filter((e) => e.type === 'error').length).toBe(1);
  const failure = await page.evaluate((mark) => window.__record.events.slice(mark).find((e) => e.type === 'error'), mark);
  expect(failure.id).toBe('b');
  expect(failure.detail.code).toBe('model');
  expect(failure.detail.message).toContain('broken.glb');
  expect(await page.evaluate(() => document.getElementById('b').info().faces)).toBe(320);
  expect(await page.evaluate(() => Array.from(document.getElementById('b').faceVectors()))).toEqual(before.b);
  expect((await record(page)).events.slice(mark).every((e) => e.id === 'b')).toBe(true);
  // b still edits after the failure.
  await page.evaluate(() => document.getElementById('b').addSource(0));
  expect(await page.evaluate(() => document.getElementById('b').constraints().length)).toBe(1);

  expect((await record(page)).violations).toEqual([]);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('an esbuild-bundled consumer app, with assetBase set as the docs say', async ({ page }) => {
  // The app imports three itself and the package's default (peer) build: its bundle has one three.js.
  const app = readFileSync(resolve(SITE, 'app/app.js'), 'utf8');
  expect(count(app, THREE_MARK)).toBe(1);
  const { errors, warnings, foreign, requests } = watchThree(page);
  await page.goto(`${ORIGIN}/app/index.html`);
  const faces = await page.evaluate(() => document.getElementById('bundled').ready.then(() => document.getElementById('bundled').info().faces));
  expect(faces).toBe(320);
  // The worker and the core came from the folder assetBase names, not from next to the bundle.
  expect(requests).toContain('/app/tangent-field-designer/core-worker.js');
  expect(requests).toContain('/app/tangent-field-designer/wasm/tvf_core.wasm');
  // A page that is not cross-origin isolated has no shared memory: the plain core, one thread.
  expect(requests).not.toContain('/app/tangent-field-designer/wasm/tvf_core_threads.wasm');
  await page.evaluate(() => document.getElementById('bundled').addVortex(5));
  expect(await page.evaluate(() => document.getElementById('bundled').constraints()[0].type)).toBe('vortex');
  expect(await page.evaluate(() => document.getElementById('bundled').stats().factorKind)).not.toContain('threads');
  expect(await page.evaluate(() => window.__appScene?.isScene)).toBe(true);
  expect(warnings).toEqual([]);
  expect((await record(page)).violations).toEqual([]);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the peer build has no copy of three.js or three-mesh-bvh (its worker one of its own); the standalone bundle has both', async () => {
  const files = readdirSync(LIB).filter((f) => f.endsWith('.js'));
  const peer = files.filter((f) => !f.includes('standalone'));
  const standalone = files.filter((f) => f.includes('standalone'));
  expect(peer).toEqual(expect.arrayContaining(['tangent-field-designer.js', 'element.js', 'core-worker.js']));
  expect(standalone).toEqual(expect.arrayContaining(['tangent-field-designer.standalone.js', 'element.standalone.js']));
  const text = (f) => readFileSync(resolve(LIB, f), 'utf8');
  // The worker is a realm of its own that no import map reaches: it carries the parts of three and
  // three-mesh-bvh it builds the page's ray-casting BVH with (web/geometry/mesh-bvh-transfer.js), once.
  for (const f of peer.filter((f) => f !== 'core-worker.js')) expect([f, count(text(f), THREE_MARK), count(text(f), BVH_MARK)]).toEqual([f, 0, 0]);
  expect(count(text('core-worker.js'), THREE_MARK)).toBeLessThanOrEqual(1);
  expect(standalone.map((f) => count(text(f), THREE_MARK)).reduce((a, b) => a + b)).toBe(1);
  expect(standalone.some((f) => count(text(f), BVH_MARK) > 0)).toBe(true);
  // The peer build's bare imports are the peers, as a bundler or an import map resolves them; the standalone
  // bundle and the worker have none. (esbuild follows the relative imports and lists the bare ones.)
  const bare = async (entry) => {
    const { metafile } = await esbuild.build({ entryPoints: [resolve(LIB, entry)], bundle: true, write: false, packages: 'external', format: 'esm', metafile: true, logLevel: 'silent' });
    return [...new Set(Object.values(metafile.inputs).flatMap((i) => i.imports.filter((m) => m.external).map((m) => m.path)))].sort();
  };
  for (const entry of ['tangent-field-designer.js', 'element.js']) {
    const imports = await bare(entry);
    expect(imports).toEqual(expect.arrayContaining(['three', 'three-mesh-bvh', 'three/addons/controls/OrbitControls.js']));
    expect(imports.filter((p) => p !== 'three' && p !== 'three-mesh-bvh' && !p.startsWith('three/addons/'))).toEqual([]);
  }
  expect(await bare('core-worker.js')).toEqual([]);
  expect(await bare('tangent-field-designer.standalone.js')).toEqual([]);
  expect(await bare('element.standalone.js')).toEqual([]);
});

test('a page that already uses three.js, with an import map: the peer build uses its copy, one three.js loads', async ({ page }) => {
  await allowImportMaps(page);
  const { errors, warnings, foreign, requests } = watchThree(page);
  const response = await page.goto(`${ORIGIN}/three-page.html`);
  expect(response.headers()['content-security-policy']).toMatch(/script-src 'self' 'sha256-[^']+' 'wasm-unsafe-eval'/);
  await page.waitForFunction(() => window.__host);
  expect(await page.evaluate(() => window.__host)).toEqual({ revision: '187', designerDefined: true, ownDrawn: true });

  // The element works with the page's three: the model loads, is drawn, and edits change the field.
  expect(await page.evaluate(() => document.getElementById('d').ready.then(() => document.getElementById('d').info().faces))).toBe(320);
  expect(await coverage(page, 'd')).toBeGreaterThan(0.5);
  const before = await page.evaluate(() => Array.from(document.getElementById('d').faceVectors()));
  await page.evaluate(() => document.getElementById('d').addVortex(5));
  const after = await page.evaluate(() => Array.from(document.getElementById('d').faceVectors()));
  expect(relativeDifference(after, before)).toBeGreaterThan(1e-3);
  expect(page.workers().length).toBe(1);

  // One copy of three.js: each of its modules requested once, from the page's own node_modules/three; three
  // set window.__THREE__ once and never warned of a second instance; nothing of the standalone bundle loaded.
  const n = (path) => requests.filter((p) => p === path).length;
  expect(n('/node_modules/three/build/three.module.js')).toBe(1);
  expect(n('/node_modules/three/build/three.core.js')).toBe(1);
  expect(n('/node_modules/three/examples/jsm/controls/OrbitControls.js')).toBe(1);
  expect(n('/node_modules/three-mesh-bvh/src/index.js')).toBe(1);
  expect(n('/node_modules/tangent-field-designer/lib/tangent-field-designer.js')).toBe(1);
  expect(requests.filter((p) => p.includes('standalone'))).toEqual([]);
  expect(requests.filter((p) => /three[^/]*\.(module|core|cjs|min)\.js$/.test(p) && !p.startsWith('/node_modules/three/build/'))).toEqual([]);
  expect(await page.evaluate(() => window.__THREE__)).toBe('187');
  expect(warnings).toEqual([]);
  expect((await record(page)).violations).toEqual([]);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('control: the standalone bundle in that page brings a second three.js, and three says so', async ({ page }) => {
  await allowImportMaps(page);
  const { errors, warnings, requests } = watchThree(page);
  await page.goto(`${ORIGIN}/three-page-standalone.html`);
  await page.waitForFunction(() => window.__host);
  expect(await page.evaluate(() => document.getElementById('d').ready.then(() => document.getElementById('d').info().faces))).toBe(320);
  expect(requests.filter((p) => p === '/node_modules/three/build/three.module.js').length).toBe(1);
  expect(requests.some((p) => /\/standalone-chunk-[^/]*\.js$/.test(p))).toBe(true);
  expect(warnings.length).toBe(1);
  expect((await record(page)).violations).toEqual([]);
  expect(errors).toEqual([]);
});

test('twenty create/remove cycles leave no worker and no WebGL context behind', async ({ page }) => {
  const errors = trackErrors(page);
  const contextWarnings = [];
  page.on('console', (m) => /WebGL contexts|context lost/i.test(m.text()) && contextWarnings.push(m.text()));
  await page.goto(`${ORIGIN}/cycles.html`);
  await page.waitForFunction(() => window.__cycles);
  // The measurement sees a live designer's worker and context.
  expect(await page.evaluate(() => window.__cycles.keep('models/ico.off'))).toBe(320);
  expect(page.workers().length).toBe(1);
  await page.evaluate(() => window.__cycles.state.live.pop().remove());
  await expect.poll(() => page.workers().length).toBe(0);

  const result = await page.evaluate(() => window.__cycles.run(20, 'models/ico.off'));
  expect(result.created).toBe(21);
  // Every removed element gave its WebGL context back at once (21 = the probe above and the 20 cycles).
  expect(result.contextsLost).toBe(21);
  await expect.poll(() => page.workers().length).toBe(0);
  // Past Chromium's cap of 16 live contexts a leak would have cost an old context; a new designer works.
  expect(await page.evaluate(() => window.__cycles.keep('models/ico.off'))).toBe(320);
  expect(page.workers().length).toBe(1);
  expect(contextWarnings).toEqual([]);
  expect(errors).toEqual([]);
});

test('attributes drive the element and are reflected; an embedded element autosaves only when asked', async ({ page }) => {
  const errors = trackErrors(page);
  await page.goto(`${ORIGIN}/attributes.html`);
  await page.evaluate(() => document.getElementById('d').ready);
  const state = () =>
    page.evaluate(() => {
      const el = document.getElementById('d');
      const stroke = el.shadowRoot.querySelector('[data-tool="stroke"]');
      return {
        settings: el.settings(),
        constraints: el.constraints().map((c) => c.type),
        views: el.views(),
        props: { gamma: el.gamma, readonly: el.readonly, tool: el.tool, controls: el.controls },
        strokeButtonShown: getComputedStyle(stroke).display !== 'none',
        storage: Object.keys(localStorage).filter((k) => k.startsWith('tvf.')),
      };
    });
  let s = await state();
  expect(s.settings).toEqual({ boundary: 'free', gamma: 0.25, symmetry: 1, curvatureAlignment: 0, exactSingularities: false });
  expect(s.constraints).toEqual(['source', 'sink']); // designs/two-sources.json
  expect(s.views).toMatchObject({ arrows: true, singularities: true, streamlines: false, colorMap: false });
  expect(s.props).toMatchObject({ gamma: 0.25, readonly: true, controls: 'minimal' });
  expect(s.strokeButtonShown).toBe(false); // readonly: no editing tools
  // readonly keeps the tools on orbit/select (the source attribute asked for an edit tool).
  expect(await page.evaluate(() => document.getElementById('d').shadowRoot.querySelector('[data-tool="orbit"]').getAttribute('aria-pressed'))).toBe('true');

  // Properties write the attributes, and the element follows.
  await page.evaluate(() => {
    const el = document.getElementById('d');
    el.readonly = false;
    el.gamma = 0.5;
    el.tool = 'stroke';
  });
  expect(await page.evaluate(() => ['readonly', 'gamma', 'tool'].map((a) => document.getElementById('d').getAttribute(a)))).toEqual([null, '0.5', 'stroke']);
  await expect.poll(async () => (await state()).settings.gamma).toBe(0.5);
  s = await state();
  expect(s.strokeButtonShown).toBe(true);
  expect(await page.evaluate(() => document.getElementById('d').shadowRoot.querySelector('[data-tool="stroke"]').getAttribute('aria-pressed'))).toBe('true');
  expect(await page.evaluate(() => document.getElementById('d').history().undo)).toEqual(['load design', 'γ']);

  // Edits without the autosave attribute leave localStorage alone; with it, they are stored under its key.
  await page.evaluate(() => document.getElementById('d').addVortex(3));
  expect((await state()).storage).toEqual([]);
  await page.evaluate(() => (document.getElementById('d').autosave = 'notes'));
  // The save starts in the task after the edit resolves; autosaveIdle() waits for it.
  await page.evaluate(async () => {
    const el = document.getElementById('d');
    await el.addVortex(4);
    await el.autosaveIdle();
  });
  const keys = (await state()).storage;
  expect(keys).toHaveLength(1);
  expect(keys[0]).toMatch(/^tvf\.autosave\.v1:notes\|ico\.off\|/);
  expect((await record(page)).events.filter((e) => e.type === 'error')).toEqual([]);

  // An edit followed at once by the element's removal is still saved, in localStorage and in IndexedDB, and
  // the removed element reports no error.
  const savedVortices = () =>
    page.evaluate(async (key) => {
      const mirror = JSON.parse(localStorage.getItem(key)).design.constraints.filter((c) => c.type === 'vortex').length;
      const db = await new Promise((resolve, reject) => {
        const open = indexedDB.open('tvf-autosave');
        open.onsuccess = () => resolve(open.result);
        open.onerror = () => reject(open.error);
      });
      const records = await new Promise((resolve) => {
        const get = db.transaction(db.objectStoreNames[0]).objectStore(db.objectStoreNames[0]).getAll();
        get.onsuccess = () => resolve(get.result);
      });
      db.close();
      const latest = records.filter((r) => r.key.startsWith('notes|')).sort((a, b) => b.id - a.id)[0];
      return { mirror, indexedDB: latest.design.constraints.filter((c) => c.type === 'vortex').length };
    }, keys[0]);
  expect(await savedVortices()).toEqual({ mirror: 2, indexedDB: 2 });
  await page.evaluate(async () => {
    const el = document.getElementById('d');
    await el.addVortex(5);
    el.remove();
  });
  await expect.poll(savedVortices).toEqual({ mirror: 3, indexedDB: 3 });
  expect((await record(page)).events.filter((e) => e.type === 'error')).toEqual([]);
  expect(errors).toEqual([]);
});
