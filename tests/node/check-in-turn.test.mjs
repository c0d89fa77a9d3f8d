// The synthesis programs checked ahead of a texture a few a frame (web/synthesis/gl.js checkInTurn): every
// question about a program waits for the GPU process, 8-17 ms each with software GL beside a big model's
// drawing, and all of them in one task were a long task of that model's load. Programs stand in for the real
// ones here: each check() takes a set time, and the frames are counted.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { checkInTurn } from '../../web/synthesis/gl.js';

const busy = (ms) => {
  for (const end = performance.now() + ms; performance.now() < end; );
};

function setup(count, checkMs, { checked = 0 } = {}) {
  const log = { frame: 0, checks: [] };
  const programs = Array.from({ length: count }, (_, i) => ({
    checked: i < checked,
    check() {
      busy(checkMs);
      this.checked = true;
      log.checks.push(log.frame);
    },
  }));
  const nextFrame = async () => {
    await new Promise((resolve) => setTimeout(resolve, 0));
    log.frame++;
  };
  return { programs, nextFrame, log };
}

test('thirteen checks of 6 ms with a budget of 8 ms: every program checked, at most two a frame', async () => {
  const { programs, nextFrame, log } = setup(13, 6);
  const t0 = performance.now();
  assert.equal(await checkInTurn(programs, nextFrame, { budgetMs: 8 }), true);
  assert.ok(programs.every((p) => p.checked));
  const perFrame = new Map();
  for (const f of log.checks) perFrame.set(f, (perFrame.get(f) ?? 0) + 1);
  assert.ok(Math.max(...perFrame.values()) <= 2, `checks a frame: ${[...perFrame.values()]}`);
  assert.ok(perFrame.size >= 7, `frames used: ${perFrame.size}`);
  assert.ok(performance.now() - t0 >= 13 * 6);
});

test('quick checks go in one task; the guard runs each', async () => {
  const { programs, nextFrame, log } = setup(13, 0);
  let guarded = 0;
  const run = (f) => (guarded++, f());
  assert.equal(await checkInTurn(programs, nextFrame, { budgetMs: 8, run }), true);
  assert.deepEqual(new Set(log.checks), new Set([0]));
  assert.equal(guarded, 13);
});

test('programs already checked are passed over without waiting for a frame', async () => {
  const { programs, nextFrame, log } = setup(5, 10, { checked: 4 });
  assert.equal(await checkInTurn(programs, nextFrame, { budgetMs: 1 }), true);
  assert.deepEqual(log.checks, [0]);
});

test('a context lost on the way: the rest left unchecked, and false', async () => {
  const { programs, nextFrame, log } = setup(6, 5);
  const lost = () => log.frame >= 2;
  assert.equal(await checkInTurn(programs, nextFrame, { budgetMs: 4, lost }), false);
  assert.equal(programs.filter((p) => p.checked).length, 2);
  assert.ok(programs.slice(2).every((p) => !p.checked));
});
