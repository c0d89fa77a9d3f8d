#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// The browser tests as a queue of spec files that more than one Playwright run takes from (scripts/test-all.sh):
// one run starts after the node tests, a second one when the native tests have finished and left their core
// idle. Each file runs in a Playwright process of its own, on the runner's own ports and output folder, with
// the page as built (no rebuild of dist/ under the other runner's server). A file is claimed by creating its
// folder in the queue (mkdir is atomic), so no file runs twice and none is left out.
//
//   node scripts/e2e-queue.mjs init                      the queue made anew: every spec file, longest first
//   node scripts/e2e-queue.mjs run --runner A --port P   take files until none is left; exit 1 if one failed
//   node scripts/e2e-queue.mjs summary                   the totals and the ten slowest tests; exit 1 if a file
//                                                        failed or did not run
//
// The order: the files' last measured times (tests/e2e/durations.json, rewritten by `summary --record`), the
// files it does not know first. build/e2e-queue/ holds the queue, the claims, and each file's JSON report and
// exit; the runners' lines go to their own output, each with the runner's name in front.
import { spawn } from 'node:child_process';
import { mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const QUEUE = resolve(ROOT, 'build/e2e-queue');
const DURATIONS = resolve(ROOT, 'tests/e2e/durations.json');

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

function init() {
  rmSync(QUEUE, { recursive: true, force: true });
  mkdirSync(resolve(QUEUE, 'claims'), { recursive: true });
  const known = readJson(DURATIONS, {});
  const files = specFiles().sort((a, b) => (known[b] ?? Infinity) - (known[a] ?? Infinity) || a.localeCompare(b));
  writeFileSync(resolve(QUEUE, 'files.json'), JSON.stringify(files, null, 1));
  console.log(`e2e-queue: ${files.length} spec files queued`);
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

// One spec file in a Playwright process of its own; its lines go out with the runner's name in front.
function runFile(file, i, runner, port) {
  const report = resolve(QUEUE, `${i}.json`);
  const env = {
    ...process.env,
    TVF_TEST_PORT: String(port),
    TVF_E2E_PREBUILT: '1',
    PLAYWRIGHT_JSON_OUTPUT_NAME: report,
  };
  const output = resolve(ROOT, 'test-results/e2e', file.replace(/^tests\/e2e\//, '').replace(/\.spec\.mjs$/, ''));
  // The argument is a regular expression over the files' paths: this one matches this file alone.
  const only = `${file.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}$`;
  const args = ['playwright', 'test', only, '--reporter=list,json', `--output=${output}`];
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
      writeFileSync(resolve(QUEUE, `${i}.done.json`), JSON.stringify({ file, runner, code, seconds }));
      done(code === 0);
    });
  });
}

async function run(runner, port) {
  const files = readJson(resolve(QUEUE, 'files.json'), null);
  if (!files) throw new Error('no queue: run `node scripts/e2e-queue.mjs init` first');
  let ok = true, taken = 0;
  for (let i = claimNext(files); i >= 0; i = claimNext(files)) {
    taken++;
    ok = (await runFile(files[i], i, runner, port)) && ok;
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

function summary(record) {
  const files = readJson(resolve(QUEUE, 'files.json'), []);
  const total = { passed: 0, failed: 0, skipped: 0, flaky: 0 };
  const missing = [], failed = [], seconds = {}, byRunner = {}, tests = [];
  files.forEach((file, i) => {
    const done = readJson(resolve(QUEUE, `${i}.done.json`), null);
    if (!done) return missing.push(file);
    seconds[file] = done.seconds;
    byRunner[done.runner] = (byRunner[done.runner] ?? 0) + done.seconds;
    const report = readJson(resolve(QUEUE, `${i}.json`), null);
    const c = counts(report);
    tests.push(...testTimes(report));
    for (const k of Object.keys(total)) total[k] += c[k];
    if (done.code !== 0 || c.failed > 0) failed.push(`${file} (exit ${done.code}, ${c.failed} failed)`);
  });
  const busy = Object.entries(byRunner).map(([r, s]) => `${r} ${Math.round(s)} s`).join(', ');
  console.log(`e2e-queue: ${total.passed} passed, ${total.skipped} skipped, ${total.flaky} flaky, ` +
    `${total.failed} failed in ${files.length} spec files (runners busy: ${busy})`);
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
  return files.length > 0 && !failed.length && !missing.length;
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
