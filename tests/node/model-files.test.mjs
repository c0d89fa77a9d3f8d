// A model file's body read in slices (web/session/model-files.js bodyBytes): the bytes that come back are the
// body's, whatever the chunking and whatever content-length says (a compressed body's is smaller than the
// bytes read; a server may send none).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { bodyBytes } from '../../web/session/model-files.js';

function body(bytes, chunk) {
  return new ReadableStream({
    start(controller) {
      for (let i = 0; i < bytes.length; i += chunk) controller.enqueue(bytes.slice(i, i + chunk));
      controller.close();
    },
  });
}

const random = (n) => {
  const bytes = new Uint8Array(n);
  let x = 12345;
  for (let i = 0; i < n; i++) bytes[i] = (x = (x * 1103515245 + 12345) >>> 0) >>> 24;
  return bytes;
};

test('a body read in slices is the body, byte for byte', async () => {
  const bytes = random(3_000_001);
  for (const [chunk, length] of [[65_536, bytes.length], [1_000_000, null], [7_777, 1_000], [4096, 2 * bytes.length]]) {
    const headers = length == null ? {} : { 'content-length': String(length) };
    const res = new Response(body(bytes, chunk), { headers });
    const read = await bodyBytes(res);
    assert.equal(read.length, bytes.length, `chunk ${chunk}, content-length ${length}`);
    assert.deepEqual(read, bytes);
  }
});

test('an empty body reads as no bytes', async () => {
  assert.equal((await bodyBytes(new Response(body(new Uint8Array(0), 1)))).length, 0);
});
