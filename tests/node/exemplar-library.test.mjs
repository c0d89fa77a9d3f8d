// The exemplar library (web/synthesis/exemplar.js): an exemplar asked for again while its analysis is under way
// (the Texture panel's thumbnail and the first synthesis ask for the default together) is analysed once, and
// both get the same tables; a failed analysis is not kept, and the next call tries again.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { ExemplarLibrary } from '../../web/synthesis/exemplar.js';

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

test('an exemplar asked for twice at once is analysed once', async () => {
  let calls = 0;
  const library = new ExemplarLibrary(async (spec) => {
    calls++;
    await sleep(20);
    return { size: spec.size };
  });
  const [a, b] = await Promise.all([library.procedural('stripes', 64, 1), library.procedural('stripes', 64, 1)]);
  assert.equal(calls, 1);
  assert.equal(a.cached, false);
  assert.equal(b.cached, true);
  assert.equal(a.tables, b.tables);
  await library.procedural('stripes', 64, 2);
  assert.equal(calls, 2, 'another seed is another exemplar');
});

test('a failed analysis is not kept: the next call analyses again', async () => {
  let calls = 0;
  const library = new ExemplarLibrary(async () => {
    calls++;
    if (calls === 1) throw new Error('the core is not there');
    return { size: 64 };
  });
  const first = library.procedural('weave', 64, 1);
  const second = library.procedural('weave', 64, 1);
  await assert.rejects(first, /not there/);
  const r = await second;
  assert.equal(calls, 2);
  assert.equal(r.cached, false);
});
