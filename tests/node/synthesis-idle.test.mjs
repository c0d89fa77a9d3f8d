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

// quick-edits.js: a change soon after another is a quick edit (a preview now, the full texture after a settle
// timer) only while the texture is behind that one; once it has caught up, the change gets its full run at once.
test('a change after the texture caught up runs in full at once; one while a run is queued is a quick edit', async () => {
  let version = 0;
  const errors = [];
  const c = new SynthesisController({
    viewer: {},
    getModel: () => null, // each run fails at once ('no model loaded'): the texture has caught up
    getFieldVersion: () => ++version,
    analyzeExemplar: async () => ({}),
    onError: (err) => errors.push(err.message),
  });
  c.active = true;
  c.stats = {}; // a texture shown: a quick edit gets a preview
  c.fieldChanged();
  assert.deepEqual([c.pendingPreview, c.settleTimer], [false, null]);
  await sleep(20);
  assert.equal(c.runsQueued, 0);
  c.fieldChanged(); // 20 ms after the one before, which the texture has caught up with
  assert.deepEqual([c.pendingPreview, c.settleTimer], [false, null]);
  await sleep(20);
  // A run still queued (behind an export, say) when the next change comes: that one is a quick edit.
  let release;
  c.exclusive(() => new Promise((resolve) => (release = resolve)));
  c.fieldChanged();
  await sleep(5);
  assert.equal(c.runsQueued, 1);
  c.fieldChanged();
  assert.equal(c.pendingPreview, true);
  assert.notEqual(c.settleTimer, null);
  // Dragged: quick whatever the texture's state.
  clearTimeout(c.settleTimer);
  c.settleTimer = null;
  release();
  await sleep(20);
  assert.equal(c.runsQueued, 0);
  c.fieldChanged({ interactive: true });
  assert.notEqual(c.settleTimer, null);
  clearTimeout(c.settleTimer);
  c.settleTimer = null;
  await sleep(20);
  assert.ok(errors.length > 0 && errors.every((m) => /no model/.test(m)), errors.join('; '));
});
