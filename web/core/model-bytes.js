// A model file's bytes, read on a worker thread. Chromium consumes a response body or a file on the thread
// that asked for it: a 33 MB scan fetched on the page blocked its thread for 0.6–1.0 s in one task, and the
// autosave key's digest of the bytes took 41–49 ms more (node). A throwaway core worker (never initialized: no
// core, no wasm) reads the URL or the Blob, digests the bytes and hands them over.
//
// Worker side: bytesOps (composed by web/core-worker.js); the page's side is core-proxy.js readBytesOffThread.
// fnv1a is the digest the autosave keys use (session/documents.js modelKey), the same on both sides. Imports
// the worker's Transfer.
import { Transfer } from './worker/transfer.js';

export function fnv1a(bytes) {
  let h = 0x811c9dc5;
  for (let i = 0; i < bytes.length; i++) h = Math.imul(h ^ bytes[i], 0x01000193);
  return (h >>> 0).toString(16).padStart(8, '0');
}

// The worker's op. source: an absolute URL (string) or a Blob. Resolves with {bytes, copy (ArrayBuffers: the
// page keeps one and hands the other to the core, and the copy is made here: 33 MB took the page's thread
// ~180 ms in a profile of the page, 119 ms under node), digest}; a URL that cannot be fetched fails with the
// message the page's own fetch would give.
export function bytesOps() {
  const anytime = {
    async readBytes(source) {
      let buffer;
      if (typeof source === 'string') {
        let res;
        try {
          res = await fetch(source);
        } catch (err) {
          throw new Error(`could not fetch ${source}: ${err.message}`);
        }
        if (!res.ok) throw new Error(`could not fetch ${source}: HTTP ${res.status} ${res.statusText}`.trim());
        buffer = await res.arrayBuffer();
      } else buffer = await source.arrayBuffer();
      const copy = buffer.slice(0);
      return new Transfer({ bytes: buffer, copy, digest: fnv1a(new Uint8Array(buffer)) }, [buffer, copy]);
    },
  };
  return { anytime };
}
