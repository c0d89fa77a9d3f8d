// Shared helpers for the end-to-end tests. Geometry is done in the test process from copies the page hands
// out through window.tvf, so the checks do not trust the page's own arithmetic.
import { expect } from '@playwright/test';

// Console errors and uncaught exceptions, collected from the moment the page is created.
export function trackErrors(page) {
  const errors = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
  });
  page.on('pageerror', (err) => errors.push(`pageerror: ${err.message}`));
  return errors;
}

export async function openDesigner(page) {
  await page.goto('/');
  await page.waitForFunction(() => window.tvf && window.tvf.ready, null, { timeout: 60_000 });
  // Rejects (and fails the test with the page's message) when the core or the default model cannot load.
  await page.evaluate(() => window.tvf.ready.then(() => true));
}

// A new page (browser.newPage options) with the designer open and its console errors collected: {page, errors}.
export async function openDesignerPage(browser, options) {
  const page = await browser.newPage(options);
  const errors = trackErrors(page);
  await openDesigner(page);
  return { page, errors };
}

// Big arrays leave the page as base64, one string each: Playwright serializes a plain array number by number
// (the 1024x656 canvas's grey values took 4.9-5.9 s, synthesisReadback()'s 800,000 numbers at 256² 5.4-6.2 s;
// as strings 0.36-0.37 s and 0.46-0.58 s). packInPage runs in the page: a typed array as {type, base64} of its bytes;
// unpacked in the test process as a typed array of the same type and values.
function packInPage(a) {
  const bytes = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return { type: a.constructor.name, base64: btoa(text) };
}

function unpack({ type, base64 }) {
  const bytes = Uint8Array.from(Buffer.from(base64, 'base64')); // a copy: aligned for its element type
  return new globalThis[type](bytes.buffer);
}

// window.tvf.synthesisReadback() with the arrays it names carried packed, as typed arrays; the rest as the page
// gives it.
export async function synthesisReadback(page, names) {
  const r = await page.evaluate(`(async (names, pack) => {
    const r = await window.tvf.synthesisReadback();
    return { ...r, ...Object.fromEntries(names.map((name) => [name, pack(r[name])])) };
  })(${JSON.stringify(names)}, ${packInPage})`);
  for (const name of names) r[name] = unpack(r[name]);
  return r;
}

// The designer's whole canvas read in the page (drawn into a 2D canvas, row 0 at the top) and carried out as
// `as` says: 'grey', {w, h, sums, left, top, scale}, sums the pixels' r + g + b (packed); 'rgb', its RGB bytes
// (packed).
function readCanvas(page, as) {
  const read = (as, pack) => {
    const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(src, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    if (as === 'rgb') {
      const rgb = new Uint8Array((d.length / 4) * 3);
      for (let i = 0, j = 0; i < d.length; i += 4, j += 3) rgb.set(d.subarray(i, i + 3), j);
      return pack(rgb);
    }
    const sums = new Uint16Array(d.length / 4);
    for (let i = 0, j = 0; i < d.length; i += 4, j++) sums[j] = d[i] + d[i + 1] + d[i + 2];
    const r = src.getBoundingClientRect();
    return { w: c.width, h: c.height, sums: pack(sums), left: r.left, top: r.top, scale: c.height / src.clientHeight };
  };
  return page.evaluate(`(${read})(${JSON.stringify(as)}, ${packInPage})`);
}

// The designer's whole canvas as grey values (row 0 at the top), with where it sits on the page: {w, h, grey,
// left, top, scale} (scale: drawing-buffer pixels per CSS pixel).
export async function readCanvasGrey(page) {
  const { sums, ...img } = await readCanvas(page, 'grey');
  return { ...img, grey: Array.from(unpack(sums), (sum) => sum / 3) };
}

// The designer's whole canvas as RGB bytes (row 0 at the top), a Uint8Array of 3 per pixel.
export async function readCanvasRgb(page) {
  return unpack(await readCanvas(page, 'rgb'));
}

// Fraction of pixels in the central box of the WebGL canvas that differ from the background colour.
export function centreCoverage(page, box = 0.3) {
  return page.evaluate((box) => {
    const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const w = src.width, h = src.height;
    const c = document.createElement('canvas');
    c.width = w;
    c.height = h;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(src, 0, 0);
    const x0 = Math.floor(w * (0.5 - box / 2)), y0 = Math.floor(h * (0.5 - box / 2));
    const data = ctx.getImageData(x0, y0, Math.floor(w * box), Math.floor(h * box)).data;
    const bg = [0x1b, 0x1d, 0x21]; // the page's clear colour (viewer.js)
    let differ = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - bg[0]) + Math.abs(data[i + 1] - bg[1]) + Math.abs(data[i + 2] - bg[2]) > 24) differ++;
    }
    return differ / (data.length / 4);
  }, box);
}

export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const norm = (a) => Math.hypot(a[0], a[1], a[2]);

export function vertex(mesh, v) {
  return [mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]];
}

export function faceCorners(mesh, f) {
  return [0, 1, 2].map((k) => vertex(mesh, mesh.triangles[3 * f + k]));
}

export function faceNormal(mesh, f) {
  const [a, b, c] = faceCorners(mesh, f);
  const n = cross(sub(b, a), sub(c, a));
  const l = norm(n);
  return [n[0] / l, n[1] / l, n[2] / l];
}

export function surfacePoint(mesh, { face, bary }) {
  const [a, b, c] = faceCorners(mesh, face);
  return [0, 1, 2].map((k) => bary[0] * a[k] + bary[1] * b[k] + bary[2] * c[k]);
}

export function faceVector(vectors, f) {
  return [vectors[3 * f], vectors[3 * f + 1], vectors[3 * f + 2]];
}

// Angle in degrees between two vectors after projecting both into the plane with unit normal n.
export function angleInPlane(u, v, n) {
  const pu = sub(u, n.map((x) => x * dot(u, n)));
  const pv = sub(v, n.map((x) => x * dot(v, n)));
  const c = dot(pu, pv) / (norm(pu) * norm(pv));
  return (Math.acos(Math.min(1, Math.max(-1, c))) * 180) / Math.PI;
}

// Relative difference ‖a − b‖ / ‖b‖ of two flat arrays.
export function relativeDifference(a, b) {
  expect(a.length).toBe(b.length);
  let d = 0, n = 0;
  for (let i = 0; i < a.length; i++) {
    d += (a[i] - b[i]) ** 2;
    n += b[i] ** 2;
  }
  return Math.sqrt(d) / Math.sqrt(n);
}

// Two faces sharing an edge, near the top of the model (the ears on the bunny): a short API stroke
// between their barycentres gives a non-trivial field far away from where the mouse strokes go.
export function topFacePair(mesh) {
  const nF = mesh.triangles.length / 3;
  let top = 0, topY = -Infinity;
  for (let f = 0; f < nF; f++) {
    const y = faceCorners(mesh, f).reduce((s, p) => s + p[1], 0) / 3;
    if (y > topY) (topY = y), (top = f);
  }
  const edgeKey = (i, j) => (i < j ? `${i},${j}` : `${j},${i}`);
  const mine = new Set([0, 1, 2].map((k) => edgeKey(mesh.triangles[3 * top + k], mesh.triangles[3 * top + ((k + 1) % 3)])));
  for (let f = 0; f < nF; f++) {
    if (f === top) continue;
    for (let k = 0; k < 3; k++) {
      if (mine.has(edgeKey(mesh.triangles[3 * f + k], mesh.triangles[3 * f + ((k + 1) % 3)]))) return [top, f];
    }
  }
  throw new Error('top face has no neighbour');
}

export const CENTRE = [1 / 3, 1 / 3, 1 / 3];

// ---- the studio's tests (studio.spec.mjs)

// Mesh copies plus the core's edge list, as plain arrays.
export async function readMesh(page) {
  return page.evaluate(() => {
    const m = window.tvf.mesh();
    return { positions: Array.from(m.positions), triangles: Array.from(m.triangles), edges: Array.from(window.tvf.edges()) };
  });
}

export function centroid(mesh, f) {
  const [a, b, c] = faceCorners(mesh, f);
  return [0, 1, 2].map((k) => (a[k] + b[k] + c[k]) / 3);
}

// Faces that share vertex v.
export function facesAround(mesh, v) {
  const out = [];
  for (let f = 0; f < mesh.triangles.length / 3; f++) {
    if (mesh.triangles[3 * f] === v || mesh.triangles[3 * f + 1] === v || mesh.triangles[3 * f + 2] === v) out.push(f);
  }
  return out;
}

// Corner of face f nearest to a 3D point (what the source/sink tools snap to).
export function nearestCorner(mesh, f, p) {
  let best = -1, bestD = Infinity;
  for (let k = 0; k < 3; k++) {
    const v = mesh.triangles[3 * f + k];
    const d = norm(sub(vertex(mesh, v), p));
    if (d < bestD) (bestD = d), (best = v);
  }
  return best;
}

// Value of the 1-form on the directed edge i → j (the core stores lower → higher).
export function edgeValue(mesh, oneForm, index, i, j) {
  const e = index.get(i < j ? `${i},${j}` : `${j},${i}`);
  if (e === undefined) throw new Error(`no edge ${i}-${j}`);
  return i < j ? oneForm[e] : -oneForm[e];
}

export function edgeIndex(mesh) {
  const index = new Map();
  for (let e = 0; e < mesh.edges.length / 2; e++) index.set(`${mesh.edges[2 * e]},${mesh.edges[2 * e + 1]}`, e);
  return index;
}

// Boundary edges as [i, j, k]: the face ijk holds the directed edge i → j, which no other face shares.
export function boundaryEdges(mesh) {
  const count = new Map();
  const T = mesh.triangles;
  const key = (i, j) => (i < j ? `${i},${j}` : `${j},${i}`);
  for (let t = 0; t < T.length; t += 3) for (let k = 0; k < 3; k++) {
    const kk = key(T[t + k], T[t + ((k + 1) % 3)]);
    count.set(kk, (count.get(kk) ?? 0) + 1);
  }
  const out = [];
  for (let t = 0; t < T.length; t += 3) for (let k = 0; k < 3; k++) {
    const i = T[t + k], j = T[t + ((k + 1) % 3)], l = T[t + ((k + 2) % 3)];
    if (count.get(key(i, j)) === 1) out.push([i, j, l]);
  }
  return out;
}

export function cornerAngle(mesh, at, a, b) {
  const p = vertex(mesh, at);
  const u = sub(vertex(mesh, a), p), w = sub(vertex(mesh, b), p);
  return Math.acos(Math.min(1, Math.max(-1, dot(u, w) / (norm(u) * norm(w)))));
}

// 1-to-4 midpoint subdivision (the same surface, 4^levels × the faces), as OFF text.
export function subdividedOff(mesh, levels) {
  let P = mesh.positions.slice(), T = mesh.triangles.slice();
  for (let l = 0; l < levels; l++) {
    const mid = new Map(), nT = [];
    const m = (a, b) => {
      const k = a < b ? `${a},${b}` : `${b},${a}`;
      if (!mid.has(k)) {
        mid.set(k, P.length / 3);
        for (let c = 0; c < 3; c++) P.push((P[3 * a + c] + P[3 * b + c]) / 2);
      }
      return mid.get(k);
    };
    for (let t = 0; t < T.length; t += 3) {
      const [a, b, c] = [T[t], T[t + 1], T[t + 2]];
      const ab = m(a, b), bc = m(b, c), ca = m(c, a);
      nT.push(a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca);
    }
    T = nT;
  }
  const lines = [`OFF`, `${P.length / 3} ${T.length / 3} 0`];
  for (let v = 0; v < P.length; v += 3) lines.push(`${P[v]} ${P[v + 1]} ${P[v + 2]}`);
  for (let t = 0; t < T.length; t += 3) lines.push(`3 ${T[t]} ${T[t + 1]} ${T[t + 2]}`);
  return lines.join('\n') + '\n';
}

// Surface points under a horizontal screen line across the view: `count + 1` samples from x0 in steps of dx (both
// as fractions of the view's width) at height y (a fraction of its height); misses off the model are dropped.
export function surfacePointsAlongScreenLine(page, { x0, dx, y, count }) {
  return page.evaluate(({ x0, dx, y, count }) => {
    const rect = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view').getBoundingClientRect();
    const pts = [];
    for (let k = 0; k <= count; k++) {
      const h = window.tvf.pick(rect.left + rect.width * (x0 + dx * k), rect.top + rect.height * y);
      if (h) pts.push({ face: h.face, bary: h.bary });
    }
    return pts;
  }, { x0, dx, y, count });
}

// In the page (pass to page.evaluate): for each start face, a strip of `crossings` faces walked away from it (each
// step to the neighbour farthest from the start), as stroke points at the centres of every `every`-th face and the
// last. Every centre of a strip zig-zags, and a zig-zag is taken literally; every fourth follows its course.
// Shared by the page tests and scripts/bench-web.mjs.
export function stripStrokesInPage({ starts, crossings, every = 1 }) {
  const { positions, triangles } = window.tvf.mesh();
  const edgeFaces = new Map();
  const key = (a, b) => (a < b ? a * 4294967296 + b : b * 4294967296 + a);
  for (let g = 0; g < triangles.length / 3; ++g)
    for (let k = 0; k < 3; ++k) {
      const e = key(triangles[3 * g + k], triangles[3 * g + ((k + 1) % 3)]);
      const list = edgeFaces.get(e);
      if (list) list.push(g);
      else edgeFaces.set(e, [g]);
    }
  const centre = (f) => [0, 1, 2].map((c) => (positions[3 * triangles[3 * f] + c] + positions[3 * triangles[3 * f + 1] + c] + positions[3 * triangles[3 * f + 2] + c]) / 3);
  return starts.map((start) => {
    const origin = centre(start);
    const faces = [start];
    for (let f = start, step = 0; step < crossings; ++step) {
      let next = -1, farthest = -1;
      for (let k = 0; k < 3; ++k)
        for (const g of edgeFaces.get(key(triangles[3 * f + k], triangles[3 * f + ((k + 1) % 3)]))) {
          if (g === f) continue;
          const d = Math.hypot(...centre(g).map((x, i) => x - origin[i]));
          if (d > farthest) [farthest, next] = [d, g];
        }
      if (next < 0) break;
      faces.push((f = next));
    }
    return faces.filter((_, i) => i % every === 0 || i === faces.length - 1).map((face) => ({ face, bary: [1 / 3, 1 / 3, 1 / 3] }));
  });
}

// The field at `face` (its corners' vertex vectors averaged) turned by `radians` about the face's normal: what an
// edit asks there to move the field near that face only (the frame tests of texture-phases and stripes).
export async function fieldTurnedAt(page, face, radians) {
  // The face's three corners: their positions and vertex vectors, 9 numbers each.
  const { P, V } = await page.evaluate((f) => {
    const { positions, triangles } = window.tvf.mesh(), vectors = window.tvf.vertexVectors();
    const corners = (a) => [0, 1, 2].flatMap((k) => {
      const v = triangles[3 * f + k];
      return [a[3 * v], a[3 * v + 1], a[3 * v + 2]];
    });
    return { P: corners(positions), V: corners(vectors) };
  }, face);
  const at = (a, k) => a.slice(3 * k, 3 * k + 3);
  const v = [0, 1, 2].map((d) => (V[d] + V[3 + d] + V[6 + d]) / 3);
  const m = cross(sub(at(P, 1), at(P, 0)), sub(at(P, 2), at(P, 0)));
  const nv = cross(m.map((x) => x / norm(m)), v);
  return v.map((x, d) => Math.cos(radians) * x + Math.sin(radians) * nv[d]);
}
