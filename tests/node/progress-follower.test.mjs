// The Texture panel's progress bar during a run (web/synthesis/progress-follower.js): the first step past 0 at
// once, then at most one update per 100 ms, and a change held back by that limit shown when it ends; with a
// delay, nothing for a run that ends within it.
import assert from 'node:assert/strict';
import test from 'node:test';
import { progressFollower } from '../../web/synthesis/progress-follower.js';

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
// Waits until check() holds (a loaded machine fires timers late), at most two seconds.
async function until(check) {
  for (const t0 = Date.now(); !check() && Date.now() - t0 < 2000; ) await sleep(10);
}

test('the bar shows the first progress at once, then follows at most ten times a second, catching up', async () => {
  let progress = { fraction: 0 };
  const shown = [];
  const follow = progressFollower(() => progress, () => shown.push(progress.fraction));
  follow();
  assert.deepEqual(shown, [], 'still at 0: nothing new to show');
  progress = { fraction: 0.11 };
  follow();
  assert.deepEqual(shown, [0.11], 'the first step past 0 at once');
  progress = { fraction: 0.2 };
  follow();
  progress = { fraction: 0.25 };
  follow();
  assert.deepEqual(shown, [0.11], 'held back within 100 ms');
  await until(() => shown.length > 1);
  assert.deepEqual(shown, [0.11, 0.25], 'the latest shown once the limit ended, with no further call');
  progress = { fraction: 0.2501 };
  follow();
  await sleep(150);
  assert.deepEqual(shown, [0.11, 0.25], 'the same percent is not shown again');
  follow.stop();
});

test('a run that ends while a change is held back shows nothing more', async () => {
  let progress = { fraction: 0.5 };
  const shown = [];
  const follow = progressFollower(() => progress, () => shown.push(progress?.fraction));
  follow();
  progress = { fraction: 0.6 };
  follow();
  follow.stop();
  progress = null;
  await sleep(150);
  assert.deepEqual(shown, [0.5]);
});

test('a run shorter than the delay shows no bar; a longer one shows it once the delay is over', async () => {
  let progress = { fraction: 0.3 };
  const shown = [];
  const quick = progressFollower(() => progress, () => shown.push(progress?.fraction), { delayMs: 80 });
  quick();
  progress = { fraction: 0.9 };
  quick();
  quick.stop();
  progress = null;
  await sleep(150);
  assert.deepEqual(shown, [], 'ended within the delay: nothing shown');

  progress = { fraction: 0.1 };
  const slow = progressFollower(() => progress, () => shown.push(progress?.fraction), { delayMs: 80 });
  slow();
  assert.deepEqual(shown, [], 'not before the delay');
  await until(() => shown.length > 0);
  assert.deepEqual(shown, [0.1], 'at the delay, with no step after it');
  progress = { fraction: 0.5 };
  await sleep(110);
  slow();
  assert.deepEqual(shown, [0.1, 0.5], 'then it follows as without a delay');
  slow.stop();
});
