// Turns the things a user or script can hand us (URL, File, ArrayBuffer) into one byte array and a format
// name for the core. The core reads a single buffer, so a .gltf's external buffers are inlined here as
// data: URIs when we can get at them (same-origin URL, or files dropped together), and refused otherwise.

export const FORMATS = ['glb', 'gltf', 'obj', 'off', 'ply'];
export const ACCEPT = FORMATS.map((f) => `.${f}`).join(',');

export function formatOf(name) {
  if (!name) return '';
  const m = /\.([a-z0-9]+)$/i.exec(name.split(/[?#]/)[0]);
  if (!m) return '';
  const ext = m[1].toLowerCase();
  if (!FORMATS.includes(ext)) {
    throw new Error(`${name}: unsupported file type .${ext} (use .glb, .gltf, .obj, .off or .ply)`);
  }
  return ext;
}

function baseName(path) {
  return decodeURIComponent(path.split(/[?#]/)[0].split('/').pop() || path);
}

function toBase64(bytes) {
  let s = '';
  const CHUNK = 0x8000; // String.fromCharCode's argument count is limited
  for (let i = 0; i < bytes.length; i += CHUNK) s += String.fromCharCode(...bytes.subarray(i, i + CHUNK));
  return btoa(s);
}

// Rewrites external buffer URIs of a .gltf as data: URIs. fetchBuffer(uri) → Uint8Array, or null when the
// buffer cannot be had. A file that does not parse as JSON is passed through for the core to diagnose.
async function inlineGltfBuffers(bytes, name, fetchBuffer) {
  let gltf;
  try {
    gltf = JSON.parse(new TextDecoder().decode(bytes));
  } catch {
    return bytes;
  }
  const external = (gltf.buffers || []).filter((b) => b && typeof b.uri === 'string' && !b.uri.startsWith('data:'));
  if (!external.length) return bytes;
  for (const buf of external) {
    const data = await fetchBuffer(buf.uri);
    if (!data) {
      throw new Error(
        `${name} refers to the external buffer "${buf.uri}", which a single .gltf file cannot bring along. ` +
          'Load a .glb instead, a .gltf with embedded (data: URI) buffers, ' +
          'or drop the .gltf together with its .bin files.',
      );
    }
    buf.uri = `data:application/octet-stream;base64,${toBase64(data)}`;
  }
  return new TextEncoder().encode(JSON.stringify(gltf));
}

// src: URL string | URL | ArrayBuffer | ArrayBufferView | Blob/File. opts: {name, format, companions: File[]}.
// offThread(source): reads a URL (absolute) or a Blob on another thread → {bytes, copy, digest} (core-proxy.js
// readBytesOffThread), or null when it cannot; then this thread reads it. Used for files of OFF_THREAD_BYTES
// and more.
// Returns {bytes: Uint8Array, format, name, digest (documents.js modelKey's) and copy (a second copy of the
// bytes, for the core), when made elsewhere, thread ('worker' | 'page': where the bytes were read)}.
export async function readModel(src, opts = {}, offThread = async () => null) {
  let bytes, copy, digest, thread = 'page', name = opts.name || '', fetchBuffer = async () => null;
  if (typeof src === 'string' || src instanceof URL) {
    const url = new URL(src, document.baseURI);
    name ||= baseName(url.pathname);
    ({ bytes, copy, digest } = await fetchModel(url, offThread));
    thread = digest ? 'worker' : 'page';
    fetchBuffer = async (uri) => {
      const r = await fetch(new URL(uri, url)).catch(() => null);
      return r && r.ok ? new Uint8Array(await r.arrayBuffer()) : null;
    };
  } else if (typeof Blob !== 'undefined' && src instanceof Blob) {
    name ||= src.name || '';
    const elsewhere = src.size >= OFF_THREAD_BYTES ? await offThread(src) : null;
    ({ bytes, copy, digest } = elsewhere ?? { bytes: new Uint8Array(await src.arrayBuffer()) });
    thread = digest ? 'worker' : 'page';
    const companions = opts.companions || [];
    fetchBuffer = async (uri) => {
      const want = baseName(uri);
      const file = companions.find((f) => f.name === want);
      return file ? new Uint8Array(await file.arrayBuffer()) : null;
    };
  } else if (src instanceof ArrayBuffer) {
    bytes = new Uint8Array(src);
  } else if (ArrayBuffer.isView(src)) {
    bytes = new Uint8Array(src.buffer, src.byteOffset, src.byteLength);
  } else {
    throw new Error('loadModel expects a URL, a File/Blob, an ArrayBuffer or a typed array');
  }
  const format = opts.format ?? formatOf(name);
  if (!bytes.length) throw new Error(`${name || 'the model'} is empty`);
  if (format === 'gltf') {
    const inlined = await inlineGltfBuffers(bytes, name || 'the glTF file', fetchBuffer);
    if (inlined !== bytes) digest = copy = undefined; // of the bytes read, not those kept
    bytes = inlined;
  }
  return { bytes, format, name: name || 'model', digest, copy, thread };
}

// Files from this size on are read on a worker (a 33 MB body read here blocked the page for up to a second);
// smaller ones here, where a worker's start would cost more than the read (bunny00's 2.6 MB: ~0.5 s more).
const OFF_THREAD_BYTES = 4 << 20;

// The size is asked first (HEAD): a big body is left to the worker, a small one read here. Where the server
// does not say, the page fetches and looks at the size, and a big body's request is aborted once its headers
// are in and made again there: that abort cost the page's thread 250 ms in one task (Chromium's cancel of a
// 33 MB body already in the HTTP cache, in a trace of a model opened again). The same messages as the
// worker's read (core/model-bytes.js).
async function fetchModel(url, offThread) {
  if ((await sizeOf(url)) >= OFF_THREAD_BYTES) {
    return (await offThread(url.href)) ?? { bytes: await bodyBytes(await fetchChecked(url)) };
  }
  const abort = new AbortController();
  let res = await fetchChecked(url, abort.signal);
  if (Number(res.headers.get('content-length')) >= OFF_THREAD_BYTES) {
    abort.abort();
    const elsewhere = await offThread(url.href);
    if (elsewhere) return elsewhere;
    res = await fetchChecked(url);
  }
  return { bytes: await bodyBytes(res) };
}

// The body read chunk by chunk, yielding to the page every YIELD_BYTES: arrayBuffer() delivered bunny00's
// 2.6 MB in one task of 130–230 ms (bench:web's long tasks), and so did a reader whose chunks were all there
// (each read() resolves at once, in the same task).
const YIELD_BYTES = 512 << 10;
const yieldToPage = () =>
  globalThis.scheduler?.yield ? globalThis.scheduler.yield() : new Promise((resolve) => setTimeout(resolve, 0));

export async function bodyBytes(res) {
  if (!res.body) return new Uint8Array(await res.arrayBuffer());
  const reader = res.body.getReader();
  // content-length is the encoded size: a compressed body grows past it.
  let bytes = new Uint8Array(Math.max(1 << 16, Number(res.headers.get('content-length')) || 0));
  let size = 0;
  for (let chunk = await reader.read(); !chunk.done; chunk = await reader.read()) {
    const { value } = chunk;
    if (size + value.length > bytes.length) {
      const grown = new Uint8Array(Math.max(2 * bytes.length, size + value.length));
      grown.set(bytes.subarray(0, size));
      bytes = grown;
    }
    bytes.set(value, size);
    if (Math.floor((size + value.length) / YIELD_BYTES) > Math.floor(size / YIELD_BYTES)) await yieldToPage();
    size += value.length;
  }
  return size === bytes.length ? bytes : bytes.slice(0, size);
}

// The body's size by a HEAD request (a CORS-safelisted method: no preflight), or 0 when it cannot be had (blob:
// and data: URLs take GET only, and the refusal would show in the console).
async function sizeOf(url) {
  if (url.protocol !== 'http:' && url.protocol !== 'https:') return 0;
  try {
    const res = await fetch(url, { method: 'HEAD' });
    return res.ok ? Number(res.headers.get('content-length')) || 0 : 0;
  } catch {
    return 0;
  }
}

async function fetchChecked(url, signal) {
  let res;
  try {
    res = await fetch(url, { signal });
  } catch (err) {
    throw new Error(`could not fetch ${url.href}: ${err.message}`);
  }
  if (!res.ok) throw new Error(`could not fetch ${url.href}: HTTP ${res.status} ${res.statusText}`.trim());
  return res;
}
