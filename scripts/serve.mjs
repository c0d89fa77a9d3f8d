#!/usr/bin/env node
// Static server for dist/ on 127.0.0.1:$PORT (default 8173). Sends COOP/COEP so the page is
// cross-origin isolated (SharedArrayBuffer for a threaded core) and the MIME types wasm streaming needs.
// --plain leaves COOP/COEP/CORP out (a plain static host); --csp sends the strict Content-Security-Policy an
// embedding page may have (docs/embedding.md).
// Usage: node scripts/serve.mjs [--root DIR] [--plain] [--csp]
import { createServer } from 'node:http';
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import { dirname, extname, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const argRoot = process.argv.indexOf('--root');
const DIST = argRoot > 0 ? resolve(process.argv[argRoot + 1]) : resolve(ROOT, 'dist');
const PORT = Number(process.env.PORT || 8173);
const HOST = '127.0.0.1';

const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.bin': 'application/octet-stream',
  '.obj': 'text/plain; charset=utf-8',
  '.off': 'text/plain; charset=utf-8',
  '.ply': 'application/octet-stream',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
};

const STRICT_CSP =
  "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self' blob:; style-src 'self'; " +
  "img-src 'self' blob: data:; connect-src 'self'; object-src 'none'; base-uri 'self'";

const ISOLATION_HEADERS = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
  'Cross-Origin-Resource-Policy': 'same-origin',
};

const COMMON_HEADERS = {
  ...(process.argv.includes('--plain') ? {} : ISOLATION_HEADERS),
  ...(process.argv.includes('--csp') ? { 'Content-Security-Policy': STRICT_CSP } : {}),
  'X-Content-Type-Options': 'nosniff',
  // Rebuilds replace files in place; the browser must revalidate rather than run a stale core.
  'Cache-Control': 'no-cache',
};

function send(res, code, text) {
  res.writeHead(code, { ...COMMON_HEADERS, 'Content-Type': 'text/plain; charset=utf-8' });
  res.end(text);
}

const server = createServer(async (req, res) => {
  if (req.method !== 'GET' && req.method !== 'HEAD') return send(res, 405, 'method not allowed\n');
  let pathname;
  try {
    pathname = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  } catch {
    return send(res, 400, 'bad request\n');
  }
  if (pathname.endsWith('/')) pathname += 'index.html';
  const file = resolve(DIST, '.' + pathname);
  if (file !== DIST && !file.startsWith(DIST + sep)) return send(res, 403, 'forbidden\n');
  let st;
  try {
    st = await stat(file);
  } catch {
    return send(res, 404, `not found: ${pathname}\n`);
  }
  if (!st.isFile()) return send(res, 404, `not found: ${pathname}\n`);
  // A validator, answered with 304 as any static host does: a reloaded page revalidates the core and the model
  // and takes them from the browser's cache (armadillo-sub2 reopened in a reloaded page: 0.57-0.68 of its
  // first opening in five runs, against 0.59-0.65 before: within the noise).
  const etag = `"${st.size.toString(36)}-${Math.floor(st.mtimeMs).toString(36)}"`;
  const validators = { ETag: etag, 'Last-Modified': st.mtime.toUTCString() };
  if (req.headers['if-none-match'] === etag) {
    res.writeHead(304, { ...COMMON_HEADERS, ...validators });
    return res.end();
  }
  res.writeHead(200, {
    ...COMMON_HEADERS,
    'Content-Type': MIME[extname(file).toLowerCase()] || 'application/octet-stream',
    'Content-Length': st.size,
    ...validators,
  });
  if (req.method === 'HEAD') return res.end();
  createReadStream(file)
    .on('error', () => res.destroy())
    .pipe(res);
});

server.on('error', (err) => {
  console.error(`serve: ${err.code === 'EADDRINUSE' ? `port ${PORT} is in use (set PORT)` : err.message}`);
  process.exit(1);
});

server.listen(PORT, HOST, () => {
  console.log(`serving ${DIST}`);
  console.log(`http://${HOST}:${PORT}/`);
});

for (const sig of ['SIGINT', 'SIGTERM']) process.on(sig, () => server.close(() => process.exit(0)));
