// The synthesis controller's queue (web/synthesis/controller.js), without a GPU: whenIdle() resolves only once
// nothing is queued or pending, a run queued while it waited included (it once returned after the run it
// first saw, with an edit's exact field still to come: the texture then lagged an edit behind).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { SynthesisController } from '../../web/synthesis/controller.js';

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

test('whenIdle waits for a run queued while it waited', async () => {
  const c = new SynthesisController({ viewer: {}, getModel: () => null, analyzeExemplar: async () => ({}) });
  const done = [];
  c.exclusive(async () => {
    await sleep(30);
    done.push('first');
  });
  const idle = c.whenIdle().then(() => done.push('idle'));
  await sleep(10);
  c.exclusive(async () => {
    await sleep(30);
    done.push('second');
  });
  await idle;
  assert.deepEqual(done, ['first', 'second', 'idle']);
});

test('whenIdle waits for a change still to be scheduled, and for a settle timer', async () => {
  const c = new SynthesisController({ viewer: {}, getModel: () => null, analyzeExemplar: async () => ({}) });
  for (const [hold, release] of [
    [() => (c.pendingField = true), () => (c.pendingField = false)],
    [() => (c.settleTimer = setTimeout(() => {}, 1000)), () => (clearTimeout(c.settleTimer), (c.settleTimer = null))],
  ]) {
    hold();
    let resolved = false;
    const idle = c.whenIdle().then(() => (resolved = true));
    await sleep(30);
    assert.equal(resolved, false);
    release();
    await idle;
    assert.equal(resolved, true);
  }
});
