#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// The browser tests as a queue of spec files that more than one Playwright run takes from (scripts/test-all.sh):
// each runner takes the next item until none is left. An item is a spec file, or several short ones run in one
// Playwright process: a process of its own cost a file 3.3-3.8 s before its first test (an empty spec file,
// measured 2026-12-02: Playwright, the two servers, the browser). Each item runs on the runner's own ports and
// output folder, with the page as built (no rebuild of dist/ under the other runner's server). An item is claimed
// by creating its folder in the queue (mkdir is atomic), so no file runs twice and none is left out.
//
//   node scripts/e2e-queue.mjs init                      the queue made anew: every spec file, longest first
//   node scripts/e2e-queue.mjs run --runner A --port P   take items until none is left; exit 1 if one failed
//   node scripts/e2e-queue.mjs summary                   the totals and the ten slowest tests; exit 1 if a file
//                                                        failed or did not run
//
// The order: the files' last measured times (tests/e2e/durations.json, rewritten by `summary --record`), the
// files it does not know first, each alone; files shorter than BATCH_SECONDS go together, up to that many
// seconds an item. build/e2e-queue/ holds the queue, the claims, and each item's JSON report and exit; the
// runners' lines go to their own output, each with the runner's name in front.
import { spawn } from 'node:child_process';
import { mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const QUEUE = resolve(ROOT, 'build/e2e-queue');
const DURATIONS = resolve(ROOT, 'tests/e2e/durations.json');
const BATCH_SECONDS = 80; // seconds as durations.json has them: a run of scripts/test-all.sh, with all beside it

function specFiles(dir = resolve(ROOT, 'tests/e2e')) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((d) => {
    const path = resolve(dir, d.name);
    if (d.isDirectory()) return specFiles(path);
    return d.name.endsWith('.spec.mjs') ? [relative(ROOT, path)] : [];
  });
}

function readJson(path, fallback) {
  try {
    return JSON.parse(readFileSync(path, 'utf8'));
  } catch {
    return fallback;
  }
}

// Longest first; the short files packed into items of up to BATCH_SECONDS, first fit, in that order.
function items(files, known) {
  const sorted = [...files].sort((a, b) => (known[b] ?? Infinity) - (known[a] ?? Infinity) || a.localeCompare(b));
  const out = [];
  for (const file of sorted) {
    const t = known[file] ?? Infinity;
    const open = t < BATCH_SECONDS && out.find((it) => it.seconds + t <= BATCH_SECONDS);
    if (open) (open.files.push(file), (open.seconds += t));
    else out.push({ files: [file], seconds: t });
  }
  return out.map((it) => it.files);
}

function init() {
  rmSync(QUEUE, { recursive: true, force: true });
  mkdirSync(resolve(QUEUE, 'claims'), { recursive: true });
  const files = specFiles();
  const queue = items(files, readJson(DURATIONS, {}));
  writeFileSync(resolve(QUEUE, 'files.json'), JSON.stringify(queue, null, 1));
  console.log(`e2e-queue: ${files.length} spec files queued in ${queue.length} items`);
}

function claimNext(files) {
  for (let i = 0; i < files.length; i++) {
    try {
      mkdirSync(resolve(QUEUE, 'claims', String(i)));
      return i;
    } catch (err) {
      if (err.code !== 'EEXIST') throw err;
    }
  }
  return -1;
}

// One item's spec files in a Playwright process of its own; its lines go out with the runner's name in front.
function runItem(files, i, runner, port) {
  const report = resolve(QUEUE, `${i}.json`);
  const env = {
    ...process.env,
    TVF_TEST_PORT: String(port),
    TVF_E2E_PREBUILT: '1',
    PLAYWRIGHT_JSON_OUTPUT_NAME: report,
  };
  const output = resolve(ROOT, 'test-results/e2e', String(i));
  // The arguments are regular expressions over the files' paths: each matches its file alone.
  const only = files.map((file) => `${file.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}$`);
  const args = ['playwright', 'test', ...only, '--reporter=list,json', `--output=${output}`];
  const t0 = Date.now();
  return new Promise((done) => {
    const child = spawn('npx', args, { cwd: ROOT, env, stdio: ['ignore', 'pipe', 'pipe'] });
    const prefix = (stream, out) => {
      let rest = '';
      stream.setEncoding('utf8'); // a character split between two chunks stays whole
      stream.on('data', (chunk) => {
        const lines = (rest + chunk).split('\n');
        rest = lines.pop();
        for (const line of lines) out.write(`[${runner}] ${line}\n`);
      });
      stream.on('end', () => rest && out.write(`[${runner}] ${rest}\n`));
    };
    prefix(child.stdout, process.stdout);
    prefix(child.stderr, process.stderr);
    child.on('close', (code) => {
      const seconds = (Date.now() - t0) / 1000;
      writeFileSync(resolve(QUEUE, `${i}.done.json`), JSON.stringify({ files, runner, code, seconds }));
      done(code === 0);
    });
  });
}

async function run(runner, port) {
  const queue = readJson(resolve(QUEUE, 'files.json'), null);
  if (!queue) throw new Error('no queue: run `node scripts/e2e-queue.mjs init` first');
  let ok = true, taken = 0;
  for (let i = claimNext(queue); i >= 0; i = claimNext(queue)) {
    taken += queue[i].length;
    ok = (await runItem(queue[i], i, runner, port)) && ok;
  }
  console.log(`e2e-queue: runner ${runner} ran ${taken} spec files${ok ? '' : ', some FAILED'}`);
  return ok;
}

// Playwright's JSON report: every test's final status.
function counts(report) {
  const c = { passed: 0, failed: 0, skipped: 0, flaky: 0 };
  const walk = (suite) => {
    for (const spec of suite.specs ?? [])
      for (const test of spec.tests ?? []) {
        const s = test.status; // expected, unexpected, skipped, flaky
        if (s === 'expected') c.passed++;
        else if (s === 'skipped') c.skipped++;
        else if (s === 'flaky') c.flaky++;
        else c.failed++;
      }
    for (const child of suite.suites ?? []) walk(child);
  };
  for (const s of report?.suites ?? []) walk(s);
  return c;
}

// Playwright's JSON report: every test's run as [seconds, title path].
function testTimes(report) {
  const times = [];
  const walk = (suite, path) => {
    for (const spec of suite.specs ?? [])
      for (const test of spec.tests ?? [])
        for (const result of test.results ?? [])
          times.push([result.duration / 1000, [...path, spec.title].join(' › ')]);
    for (const child of suite.suites ?? []) walk(child, [...path, child.title]);
  };
  for (const s of report?.suites ?? []) walk(s, [s.title]);
  return times;
}

// An item's seconds shared among its files by their tests' own times (for durations.json's order).
function fileSeconds(files, seconds, times) {
  const own = files.map((file) => {
    const name = file.replace(/^tests\/e2e\//, '');
    return times.filter(([, title]) => title.startsWith(`${name} › `)).reduce((sum, [t]) => sum + t, 0);
  });
  const total = own.reduce((a, b) => a + b, 0);
  return files.map((file, k) => [file, total > 0 ? (seconds * own[k]) / total : seconds / files.length]);
}

function summary(record) {
  const queue = readJson(resolve(QUEUE, 'files.json'), []);
  const total = { passed: 0, failed: 0, skipped: 0, flaky: 0 };
  const missing = [], failed = [], seconds = {}, byRunner = {}, tests = [];
  queue.forEach((files, i) => {
    const done = readJson(resolve(QUEUE, `${i}.done.json`), null);
    if (!done) return missing.push(...files);
    byRunner[done.runner] = (byRunner[done.runner] ?? 0) + done.seconds;
    const report = readJson(resolve(QUEUE, `${i}.json`), null);
    const c = counts(report);
    const times = testTimes(report);
    tests.push(...times);
    for (const [file, t] of fileSeconds(files, done.seconds, times)) seconds[file] = t;
    for (const k of Object.keys(total)) total[k] += c[k];
    if (done.code !== 0 || c.failed > 0) failed.push(`${files.join(', ')} (exit ${done.code}, ${c.failed} failed)`);
  });
  const nfiles = queue.reduce((n, files) => n + files.length, 0);
  const busy = Object.entries(byRunner).map(([r, s]) => `${r} ${Math.round(s)} s`).join(', ');
  console.log(`e2e-queue: ${total.passed} passed, ${total.skipped} skipped, ${total.flaky} flaky, ` +
    `${total.failed} failed in ${nfiles} spec files, ${queue.length} items (runners busy: ${busy})`);
  // The slowest tests, where a run's time is most worth looking for: each line is one test's own time.
  tests.sort((a, b) => b[0] - a[0]);
  const testSeconds = tests.reduce((sum, [t]) => sum + t, 0);
  console.log(`e2e-queue: ${Math.round(testSeconds)} s in the tests themselves; the slowest:`);
  for (const [t, title] of tests.slice(0, 10)) console.log(`e2e-queue: ${t.toFixed(1).padStart(6)} s  ${title}`);
  for (const f of failed) console.log(`e2e-queue: FAILED ${f}`);
  for (const f of missing) console.log(`e2e-queue: NOT RUN ${f}`);
  if (record && !missing.length) {
    const rounded = Object.fromEntries(Object.entries(seconds).map(([f, s]) => [f, Math.round(s)]));
    writeFileSync(DURATIONS, JSON.stringify(rounded, null, 1) + '\n');
  }
  return nfiles > 0 && !failed.length && !missing.length;
}

function option(name, fallback) {
  const i = process.argv.indexOf(name);
  return i > 0 && process.argv[i + 1] ? process.argv[i + 1] : fallback;
}

const command = process.argv[2];
if (command === 'init') init();
else if (command === 'run') process.exitCode = (await run(option('--runner', 'A'), Number(option('--port', 8191)))) ? 0 : 1;
else if (command === 'summary') process.exitCode = summary(process.argv.includes('--record')) ? 0 : 1;
else {
  console.error('usage: node scripts/e2e-queue.mjs init | run --runner NAME --port PORT | summary [--record]');
  process.exitCode = 2;
}
