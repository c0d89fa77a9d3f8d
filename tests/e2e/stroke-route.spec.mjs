// The stroke route of docs/architecture.md ("One stroke, from pointer-up to the drawn field") is the route a
// stroke takes: a stroke drawn with the mouse on the default model, and the web/ modules whose functions ran
// between its pointer-up and the frame that draws its field, recorded by Chromium's precise coverage (call
// counts, reset just before the pointer-up, taken at a breakpoint just after view-sync.js draws) and mapped
// through the bundle's source map to the modules they came from. The recorded modules must be those the doc
// lists, no more and no fewer, so the doc cannot drift from the code. The worker's modules run on a thread of
// their own and are not recorded here: the doc's list ends, on the page's side, where the request is posted.
import { expect, test } from '@playwright/test';
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesignerPage } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const SECTION = 'One stroke, from pointer-up to the drawn field';

// A file of web/ as the doc names it: in full (web/session/session.js) or from its layer's folder
// (session/specs.js), and one at web/'s root in full (web/dom.js); C++ sources (core/…/*.cpp) end otherwise.
const WEB_FILE =
  /(?:web\/)?((?:element|export|synthesis|stripes|tools|views|session|core|geometry)\/[\w/.-]*?\.js)\b|web\/([\w-]+\.js)\b/g;
const webFiles = (text) => [...text.matchAll(WEB_FILE)].map((m) => `web/${m[1] ?? m[2]}`);

// The doc's list: {steps, files, count, participants}. steps: the file each numbered item names first, in order;
// files: every web/ file the items name (the steps and the helpers they call); count: the number of files the
// section says the test records; participants: the web/ files the sequence diagram's participants name.
function documentedRoute(markdown) {
  const section = markdown.split(/^## /m).find((s) => s.startsWith(SECTION));
  if (!section) throw new Error(`docs/architecture.md has no section "${SECTION}"`);
  const items = [];
  for (const line of section.split('\n')) {
    if (/^\d+\. /.test(line)) items.push(line);
    else if (items.length && /^ {3,}\S/.test(line)) items[items.length - 1] += ` ${line.trim()}`;
    else if (items.length) break;
  }
  const steps = items.map((item) => item.match(/^\d+\. \*\*(web\/[\w/.-]+\.js)\*\*/)?.[1]);
  if (!items.length || steps.includes(undefined)) throw new Error('each step of the route names its file first');
  const files = [...new Set(items.flatMap(webFiles))].sort();
  const count = Number(section.match(/requires exactly the files\s+this list names: (\d+)/)?.[1]);
  const diagram = section.slice(section.indexOf('```mermaid'));
  const participants = [...diagram.matchAll(/^\s*participant \w+ as (.*)$/gm)].flatMap(([, label]) => {
    // 'core/worker/dispatch.js · edit-ops.js': the files after the first are in its folder.
    const [first, ...rest] = label.split(' · ');
    const named = webFiles(first);
    if (!rest.length) return named;
    const folder = named[0].slice(0, named[0].lastIndexOf('/') + 1);
    return [...named, ...rest.map((name) => folder + name.match(/^[\w.-]+\.js/)[0])];
  });
  return { steps, files, count, participants };
}

// ------------------------------------------------------------------------------------------ the source map

const BASE64 = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/';

function vlq(segment) {
  const values = [];
  let value = 0, shift = 0;
  for (const ch of segment) {
    const digit = BASE64.indexOf(ch);
    value += (digit & 31) << shift;
    if (digit & 32) shift += 5;
    else {
      values.push(value & 1 ? -(value >>> 1) : value >>> 1);
      value = shift = 0;
    }
  }
  return values;
}

// Per generated line, its segments [column, source, source line, source column], in column order.
function decodeMappings(mappings) {
  let source = 0, line = 0, column = 0;
  return mappings.split(';').map((text) => {
    const segments = [];
    let generated = 0;
    for (const part of text ? text.split(',') : []) {
      const v = vlq(part);
      generated += v[0];
      if (v.length < 4) continue;
      source += v[1];
      line += v[2];
      column += v[3];
      segments.push([generated, source, line, column]);
    }
    return segments;
  });
}

// The bundle's map: the source of any offset into the bundle, and the bundle position of a source position.
function bundleMap(bundleText, mapJson) {
  const lines = decodeMappings(mapJson.mappings);
  const sources = mapJson.sources.map((s) => s.replace(/^(\.\.\/)+/, ''));
  const lineStarts = [0];
  for (let i = bundleText.indexOf('\n'); i >= 0; i = bundleText.indexOf('\n', i + 1)) lineStarts.push(i + 1);
  return {
    // {file, line (1-based)} of the code at `offset`, or null where nothing is mapped.
    sourceAt(offset) {
      let lo = 0, hi = lineStarts.length - 1;
      while (lo < hi) {
        const mid = (lo + hi + 1) >> 1;
        if (lineStarts[mid] <= offset) lo = mid;
        else hi = mid - 1;
      }
      const column = offset - lineStarts[lo];
      const segment = lines[lo]?.findLast((s) => s[0] <= column);
      return segment ? { file: sources[segment[1]], line: segment[2] + 1 } : null;
    },
    // The first bundle position mapped to `file` past source line `after` (0-based): {lineNumber, columnNumber}.
    positionAfter(file, after) {
      const index = sources.indexOf(file);
      let best = null;
      lines.forEach((segments, lineNumber) => {
        for (const [columnNumber, source, line, column] of segments) {
          if (source !== index || line <= after) continue;
          if (!best || line < best.line || (line === best.line && column < best.column))
            best = { line, column, lineNumber, columnNumber };
        }
      });
      if (!best) throw new Error(`the bundle has no code of ${file} after its line ${after + 1}`);
      return { lineNumber: best.lineNumber, columnNumber: best.columnNumber };
    },
  };
}

// The web/ modules with a function called in `coverage` (Profiler.takePreciseCoverage) of the bundle `name`:
// {file → the lines where those functions start}.
function modulesEntered(coverage, map, name) {
  const entered = {};
  for (const script of coverage.result) {
    if (!script.url.endsWith(`/${name}`)) continue;
    for (const fn of script.functions) {
      const whole = fn.ranges[0];
      if (!whole.count || whole.startOffset === 0) continue;
      const at = map.sourceAt(whole.startOffset);
      if (at?.file.startsWith('web/')) (entered[at.file] ??= []).push(at.line);
    }
  }
  const files = Object.keys(entered).sort();
  return Object.fromEntries(files.map((f) => [f, [...new Set(entered[f])].sort((a, b) => a - b)]));
}

// ------------------------------------------------------------------------------------------ the worker

// A CDP session of each worker running `script` (the page's session attaches to them; its messages to them go
// wrapped in Target.sendMessageToTarget): [{send(method, params)}].
async function workerSessions(cdp, script) {
  const sessions = [];
  const pending = new Map();
  let nextId = 1;
  cdp.on('Target.receivedMessageFromTarget', ({ message }) => {
    const { id, result, error } = JSON.parse(message);
    const call = pending.get(id);
    if (!call) return;
    pending.delete(id);
    if (error) call.reject(new Error(error.message));
    else call.resolve(result);
  });
  cdp.on('Target.attachedToTarget', ({ sessionId, targetInfo }) => {
    if (targetInfo.type !== 'worker' || !targetInfo.url.endsWith(`/${script}`)) return;
    const send = (method, params = {}) =>
      new Promise((resolve, reject) => {
        const id = nextId++;
        pending.set(id, { resolve, reject });
        const message = JSON.stringify({ id, method, params });
        cdp.send('Target.sendMessageToTarget', { sessionId, message }).catch(reject);
      });
    sessions.push({ send, url: targetInfo.url });
  });
  await cdp.send('Target.setAutoAttach', { autoAttach: true, waitForDebuggerOnStart: false, flatten: false });
  return sessions;
}

// ------------------------------------------------------------------------------------------ the stroke

test('the stroke route the doc lists is the one a stroke takes', async ({ browser }, testInfo) => {
  const route = documentedRoute(readFileSync(resolve(ROOT, 'docs/architecture.md'), 'utf8'));
  const mapOf = (name) => {
    const json = JSON.parse(readFileSync(resolve(ROOT, `dist/${name}.map`), 'utf8'));
    return bundleMap(readFileSync(resolve(ROOT, `dist/${name}`), 'utf8'), json);
  };
  const map = mapOf('main.js');
  const workerMap = mapOf('core-worker.js');
  // The field is drawn when view-sync.js has rendered it: the pause comes just after its renderNow().
  const viewSync = readFileSync(resolve(ROOT, 'web/element/view-sync.js'), 'utf8').split('\n');
  const drawLine = viewSync.findIndex((l) => l.trim() === 'viewer.renderNow();');
  expect(drawLine, 'view-sync.js draws the field with viewer.renderNow()').toBeGreaterThan(0);
  const drawn = map.positionAfter('web/element/view-sync.js', drawLine);

  const { page, errors } = await openDesignerPage(browser);
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.startPreciseCoverage', { callCount: true, detailed: false });
  await cdp.send('Debugger.enable');
  const workers = await workerSessions(cdp, 'core-worker.js');
  await expect.poll(() => workers.length).toBeGreaterThan(0);
  for (const w of workers) {
    await w.send('Profiler.enable');
    await w.send('Profiler.startPreciseCoverage', { callCount: true, detailed: false });
  }

  // A horizontal screen line across the body on which every point hits the model.
  const line = await page.evaluate(() => {
    const view = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const r = view.getBoundingClientRect();
    const cx = r.left + r.width / 2, cy = r.top + r.height / 2, half = 80, n = 32;
    for (const dy of [40, 20, 60, 0, 80, -20, 100]) {
      let all = true;
      for (let k = 0; k <= n && all; k++) all = !!window.tvf.pick(cx - half + (2 * half * k) / n, cy + dy);
      if (all) return { x0: cx - half, x1: cx + half, y: cy + dy };
    }
    return null;
  });
  expect(line, 'a screen line across the model').not.toBeNull();
  await page.getByRole('button', { name: 'Stroke', exact: true }).click();
  await page.mouse.move(line.x0, line.y);
  await page.mouse.down();
  await page.mouse.move(line.x1, line.y, { steps: 20 });
  // Whatever the drag left for the next frames is done before the count starts, and so is every request queued
  // before the stroke (the worker's warm-up after the model's first frame): a read queued behind them returned.
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  await page.evaluate(() => window.tvf.debugCoreReadout());

  const { breakpointId } = await cdp.send('Debugger.setBreakpointByUrl', { urlRegex: '/main\\.js$', ...drawn });
  const recorded = new Promise((resolveRecorded, reject) => {
    cdp.once('Debugger.paused', async () => {
      try {
        const coverage = await cdp.send('Profiler.takePreciseCoverage');
        await cdp.send('Debugger.removeBreakpoint', { breakpointId });
        resolveRecorded(coverage);
      } catch (err) {
        reject(err);
      } finally {
        await cdp.send('Debugger.resume').catch(() => {});
      }
    });
  });
  const deferredBefore = await page.evaluate(() => window.tvf.perf().deferredUpdate?.seq ?? null);
  await cdp.send('Profiler.takePreciseCoverage'); // the count starts here
  for (const w of workers) await w.send('Profiler.takePreciseCoverage');
  await page.mouse.up();
  const never = new Promise((_, reject) => {
    const why = 'the pause after view-sync.js renderNow() never came: the field was not drawn';
    setTimeout(() => reject(new Error(why)), 60_000).unref();
  });
  const coverage = await Promise.race([recorded, never]);
  // The worker's part ends when the factor has taken the update the solve went through.
  await expect.poll(() => page.evaluate(() => window.tvf.perf().deferredUpdate?.seq ?? null)).not.toBe(deferredBefore);
  const workerCoverage = { result: [] };
  for (const w of workers) workerCoverage.result.push(...(await w.send('Profiler.takePreciseCoverage')).result);
  await cdp.send('Debugger.disable');
  await cdp.send('Profiler.stopPreciseCoverage');
  await expect(page.locator('#constraint-list li')).toHaveCount(1);

  const onPage = modulesEntered(coverage, map, 'main.js');
  const inWorker = modulesEntered(workerCoverage, workerMap, 'core-worker.js');
  const entered = [...new Set([...Object.keys(onPage), ...Object.keys(inWorker)])].sort();
  const functions = { page: onPage, worker: inWorker };
  const record = { entered, documented: route.files, steps: route.steps, functions };
  writeFileSync(testInfo.outputPath('stroke-route.json'), JSON.stringify(record, null, 1));
  const counts = `${Object.keys(onPage).length} on the page, ${Object.keys(inWorker).length} in the worker`;
  console.log(`stroke route: ${entered.length} web/ files entered from pointer-up to the drawn field (${counts})`);

  expect(entered, 'the files a stroke enters are those docs/architecture.md lists').toEqual(route.files);
  expect(route.count, 'the number of files the doc says the route enters').toBe(entered.length);
  expect(new Set(route.steps).size, 'each step of the route in a file of its own').toBe(route.steps.length);
  expect(route.participants, 'the sequence diagram shows the steps, in order').toEqual(route.steps);
  expect(errors).toEqual([]);
  await page.close();
});
