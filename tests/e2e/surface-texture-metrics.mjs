// Measures of a textured model as any glTF viewer shows it (shared/design texture-quality.md): from a GLB's own
// TEXCOORD_0 and embedded PNG (image row 0 = v 0), stripe direction on the surface against the field, and the
// colour jump across chart seams against the jump across interior edges.
import { inflateSync } from 'node:zlib';

// RGBA8 pixels of a PNG (8-bit RGB/RGBA, non-interlaced).
export function decodePng(bytes) {
  const b = Buffer.from(bytes);
  let off = 8, width = 0, height = 0, colourType = 0;
  const idat = [];
  while (off < b.length) {
    const len = b.readUInt32BE(off), type = b.toString('latin1', off + 4, off + 8);
    const data = b.subarray(off + 8, off + 8 + len);
    if (type === 'IHDR') (width = data.readUInt32BE(0)), (height = data.readUInt32BE(4)), (colourType = data[9]);
    if (type === 'IDAT') idat.push(data);
    off += 12 + len;
  }
  const channels = colourType === 6 ? 4 : 3;
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const out = new Uint8Array(width * height * 4);
  const prev = new Uint8Array(stride), cur = new Uint8Array(stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; i++) {
      const a = i >= channels ? cur[i - channels] : 0, up = prev[i], c = i >= channels ? prev[i - channels] : 0;
      let v = line[i];
      if (filter === 1) v += a;
      else if (filter === 2) v += up;
      else if (filter === 3) v += (a + up) >> 1;
      else if (filter === 4) {
        const p = a + up - c, pa = Math.abs(p - a), pb = Math.abs(p - up), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? up : c;
      }
      cur[i] = v & 255;
    }
    for (let x = 0; x < width; x++) for (let k = 0; k < 4; k++) out[4 * (y * width + x) + k] = k < channels ? cur[x * channels + k] : 255;
    prev.set(cur);
  }
  return { width, height, pixels: out };
}

// {positions (3 per vertex), uvs (2 per vertex), indices, image} of the first primitive of a GLB.
export function readGlb(bytes) {
  const b = Buffer.from(bytes);
  if (b.readUInt32LE(0) !== 0x46546c67) throw new Error('not a GLB');
  const jsonLen = b.readUInt32LE(12);
  const json = JSON.parse(b.toString('utf8', 20, 20 + jsonLen));
  const binStart = 20 + jsonLen + 8;
  const view = (i) => {
    const v = json.bufferViews[i];
    return b.subarray(binStart + (v.byteOffset ?? 0), binStart + (v.byteOffset ?? 0) + v.byteLength);
  };
  const accessor = (i) => {
    const a = json.accessors[i];
    const raw = view(a.bufferView);
    const n = a.count * { SCALAR: 1, VEC2: 2, VEC3: 3 }[a.type];
    const T = { 5126: Float32Array, 5125: Uint32Array, 5123: Uint16Array }[a.componentType];
    return new T(raw.buffer.slice(raw.byteOffset + (a.byteOffset ?? 0), raw.byteOffset + (a.byteOffset ?? 0) + n * T.BYTES_PER_ELEMENT));
  };
  const prim = json.meshes[0].primitives[0];
  const material = json.materials[prim.material];
  const texture = json.textures[material.pbrMetallicRoughness.baseColorTexture.index];
  const image = decodePng(view(json.images[texture.source].bufferView));
  const phases = prim.attributes.TEXCOORD_1 === undefined ? null : accessor(prim.attributes.TEXCOORD_1);
  return { positions: accessor(prim.attributes.POSITION), uvs: accessor(prim.attributes.TEXCOORD_0), indices: accessor(prim.indices), image, phases };
}

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);

// Per face of the GLB (non-indexed or indexed): 3D corners, pixel-space corners (u W, v H), normal, area.
export function faces({ positions, uvs, indices, image }) {
  const W = image.width, H = image.height;
  const out = [];
  for (let f = 0; f < indices.length / 3; f++) {
    const idx = [0, 1, 2].map((k) => indices[3 * f + k]);
    const P = idx.map((i) => [positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]]);
    const Q = idx.map((i) => [uvs[2 * i] * W, uvs[2 * i + 1] * H]);
    const n = cross(sub(P[1], P[0]), sub(P[2], P[0]));
    const l = norm(n);
    out.push({ P, Q, n: l > 0 ? n.map((x) => x / l) : [0, 0, 0], area: l / 2, centroid: [0, 1, 2].map((c) => (P[0][c] + P[1][c] + P[2][c]) / 3) });
  }
  return out;
}

function luminance(image) {
  const { width: W, height: H, pixels } = image;
  const L = new Float32Array(W * H);
  const alpha = new Uint8Array(W * H);
  for (let i = 0; i < W * H; i++) {
    L[i] = 0.299 * pixels[4 * i] + 0.587 * pixels[4 * i + 1] + 0.114 * pixels[4 * i + 2];
    alpha[i] = pixels[4 * i + 3] > 0 && pixels[4 * i] + pixels[4 * i + 1] + pixels[4 * i + 2] > 0 ? 1 : 0;
  }
  return { L, alpha };
}

// Pixel centres inside face f's pixel-space triangle, with the face's pixel -> surface map A = E T^-1 (3x2).
function facePixels(face, W, H, visit) {
  const [q0, q1, q2] = face.Q;
  const t = [q1[0] - q0[0], q2[0] - q0[0], q1[1] - q0[1], q2[1] - q0[1]];
  const det = t[0] * t[3] - t[1] * t[2];
  if (!(Math.abs(det) > 1e-12)) return;
  const ti = [t[3] / det, -t[1] / det, -t[2] / det, t[0] / det];
  const e1 = sub(face.P[1], face.P[0]), e2 = sub(face.P[2], face.P[0]);
  const A = [0, 1].map((c) => [0, 1, 2].map((k) => e1[k] * ti[c] + e2[k] * ti[2 + c])); // columns
  const x0 = Math.max(0, Math.floor(Math.min(q0[0], q1[0], q2[0]))), x1 = Math.min(W - 1, Math.ceil(Math.max(q0[0], q1[0], q2[0])));
  const y0 = Math.max(0, Math.floor(Math.min(q0[1], q1[1], q2[1]))), y1 = Math.min(H - 1, Math.ceil(Math.max(q0[1], q1[1], q2[1])));
  for (let y = y0; y <= y1; y++)
    for (let x = x0; x <= x1; x++) {
      const dx = x + 0.5 - q0[0], dy = y + 0.5 - q0[1];
      const l1 = ti[0] * dx + ti[1] * dy, l2 = ti[2] * dx + ti[3] * dy;
      if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
      visit(x, y, A);
    }
}

// Every textured pixel of face f (central differences, only where all 4 neighbours are textured) with its
// luminance gradient carried onto the surface: g = A (A^T A)^-1 g_px.
function faceGradients(face, image, { L, alpha }, visit) {
  const { width: W, height: H } = image;
  facePixels(face, W, H, (x, y, A) => {
    if (x < 1 || y < 1 || x >= W - 1 || y >= H - 1) return;
    const i = y * W + x;
    if (!alpha[i - 1] || !alpha[i + 1] || !alpha[i - W] || !alpha[i + W]) return;
    const gx = (L[i + 1] - L[i - 1]) / 2, gy = (L[i + W] - L[i - W]) / 2;
    const a = dot(A[0], A[0]), b = dot(A[0], A[1]), c = dot(A[1], A[1]), d = a * c - b * b;
    if (!(d > 0)) return;
    const s = (c * gx - b * gy) / d, t = (-b * gx + a * gy) / d;
    visit([0, 1, 2].map((k) => A[0][k] * s + A[1][k] * t));
  });
}

// The faces within 2 periods of each face (by centroid distance: across chart seams), with their Gaussian weight
// (sigma = period): neighbours(f, visit(g, w)).
function windowOf(F, period) {
  const cell = 2 * period;
  const grid = new Map();
  const key = (p) => p.map((x) => Math.floor(x / cell)).join(',');
  F.forEach((face, f) => {
    const k = key(face.centroid);
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(f);
  });
  return (f, visit) => {
    const c = F[f].centroid.map((x) => Math.floor(x / cell));
    for (let dx = -1; dx <= 1; dx++)
      for (let dy = -1; dy <= 1; dy++)
        for (let dz = -1; dz <= 1; dz++)
          for (const g of grid.get(`${c[0] + dx},${c[1] + dy},${c[2] + dz}`) ?? []) {
            const d = norm(sub(F[g].centroid, F[f].centroid));
            if (d <= cell) visit(g, Math.exp(-(d * d) / (2 * period * period)));
          }
  };
}

// Stripe direction vs the field per face (texture-quality.md): every pixel's luminance gradient (central
// differences, only where all 4 neighbours are textured) carried to the surface, g = A (A^T A)^-1 g_px,
// accumulated as g g^T per face, summed over faces within 2 periods (Gaussian, sigma = period, by centroid
// distance: across chart seams), the dominant direction projected into the face's plane; stripe direction =
// n x that. fieldPerFace: 3 per face. Returns area-weighted mean error (degrees, mod 180) and share within 10°.
export function stripeAlignment(glb, fieldPerFace, period) {
  const F = faces(glb);
  const tensors = new Float64Array(6 * F.length);
  const lum = luminance(glb.image);
  F.forEach((face, f) => {
    faceGradients(face, glb.image, lum, (g) => {
      const T = tensors.subarray(6 * f, 6 * f + 6);
      T[0] += g[0] * g[0], T[1] += g[0] * g[1], T[2] += g[0] * g[2], T[3] += g[1] * g[1], T[4] += g[1] * g[2], T[5] += g[2] * g[2];
    });
  });
  const neighbours = windowOf(F, period);
  let sumW = 0, sumErr = 0, within = 0, measured = 0;
  const errors = new Float64Array(F.length).fill(NaN);
  F.forEach((face, f) => {
    const v = fieldPerFace.slice(3 * f, 3 * f + 3);
    if (!(face.area > 0) || !(norm(v) > 1e-9)) return;
    const S = new Float64Array(6);
    neighbours(f, (g, w) => {
      for (let k = 0; k < 6; k++) S[k] += w * tensors[6 * g + k];
    });
    // In-plane basis and the 2x2 tensor.
    const n = face.n;
    const b1 = (() => {
      const e = sub(face.P[1], face.P[0]);
      const l = norm(e);
      return e.map((x) => x / l);
    })();
    const b2 = cross(n, b1);
    const Tv = (u, w) => u[0] * (S[0] * w[0] + S[1] * w[1] + S[2] * w[2]) + u[1] * (S[1] * w[0] + S[3] * w[1] + S[4] * w[2]) + u[2] * (S[2] * w[0] + S[4] * w[1] + S[5] * w[2]);
    const m11 = Tv(b1, b1), m12 = Tv(b1, b2), m22 = Tv(b2, b2);
    if (!(m11 + m22 > 0)) return;
    const gradAngle = 0.5 * Math.atan2(2 * m12, m11 - m22); // dominant gradient direction in (b1, b2)
    const stripeAngle = gradAngle + Math.PI / 2;
    const fieldAngle = Math.atan2(dot(v, b2), dot(v, b1));
    let err = Math.abs(stripeAngle - fieldAngle) % Math.PI;
    if (err > Math.PI / 2) err = Math.PI - err;
    const deg = (err * 180) / Math.PI;
    errors[f] = deg;
    sumW += face.area;
    sumErr += face.area * deg;
    if (deg <= 10) within += face.area;
    measured++;
  });
  return { meanDegrees: sumErr / sumW, shareWithin10: within / sumW, faces: measured, errors };
}

// Colour jump across seam edges (the two faces' UVs differ at the edge) against interior edges: colours sampled
// (bilinear) 1.5 pixels into each face at 3 points along the edge. triangles: the mesh's own vertex indices (the
// GLB is unwelded), 3 per face in the GLB's face order.
export function seamJumpRatio(glb, triangles) {
  const { width: W, height: H, pixels } = glb.image;
  const F = faces(glb);
  const sample = (x, y) => {
    const x0 = Math.floor(x - 0.5), y0 = Math.floor(y - 0.5), fx = x - 0.5 - x0, fy = y - 0.5 - y0;
    const at = (xx, yy, k) => pixels[4 * (Math.min(H - 1, Math.max(0, yy)) * W + Math.min(W - 1, Math.max(0, xx))) + k];
    return [0, 1, 2].map((k) => (1 - fy) * ((1 - fx) * at(x0, y0, k) + fx * at(x0 + 1, y0, k)) + fy * ((1 - fx) * at(x0, y0 + 1, k) + fx * at(x0 + 1, y0 + 1, k)));
  };
  const edges = new Map();
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      if (!edges.has(key)) edges.set(key, []);
      edges.get(key).push({ f, ka: a < b ? k : (k + 1) % 3, kb: a < b ? (k + 1) % 3 : k });
    }
  // The point on the edge at t, moved 1.5 px towards the face's third corner.
  const inside = (face, ka, kb, t) => {
    const A = face.Q[ka], B = face.Q[kb], C = face.Q[3 - ka - kb];
    const p = [A[0] + t * (B[0] - A[0]), A[1] + t * (B[1] - A[1])];
    const e = [B[0] - A[0], B[1] - A[1]];
    let nrm = [-e[1], e[0]];
    if ((C[0] - A[0]) * nrm[0] + (C[1] - A[1]) * nrm[1] < 0) nrm = [e[1], -e[0]];
    const l = Math.hypot(nrm[0], nrm[1]) || 1;
    return [p[0] + (1.5 * nrm[0]) / l, p[1] + (1.5 * nrm[1]) / l];
  };
  let seam = 0, nSeam = 0, interior = 0, nInterior = 0, seamEdges = 0;
  for (const list of edges.values()) {
    if (list.length !== 2) continue;
    const [e0, e1] = list;
    const f0 = F[e0.f], f1 = F[e1.f];
    const same = (p, q) => Math.abs(p[0] - q[0]) < 1e-3 && Math.abs(p[1] - q[1]) < 1e-3;
    const isSeam = !(same(f0.Q[e0.ka], f1.Q[e1.ka]) && same(f0.Q[e0.kb], f1.Q[e1.kb]));
    seamEdges += isSeam;
    for (const t of [0.25, 0.5, 0.75]) {
      const c0 = sample(...inside(f0, e0.ka, e0.kb, t)), c1 = sample(...inside(f1, e1.ka, e1.kb, t));
      const j = Math.abs(c0[0] - c1[0]) + Math.abs(c0[1] - c1[1]) + Math.abs(c0[2] - c1[2]);
      if (isSeam) (seam += j), nSeam++;
      else (interior += j), nInterior++;
    }
  }
  return { seamJump: seam / nSeam, interiorJump: interior / nInterior, ratio: seam / nSeam / (interior / nInterior), seamEdges };
}

// Surface length per pixel of the GLB's image at the atlas's mean density.
export function pixelLength(glb) {
  let a3 = 0, a2 = 0;
  for (const face of faces(glb)) {
    a3 += face.area;
    const [q0, q1, q2] = face.Q;
    a2 += Math.abs((q1[0] - q0[0]) * (q2[1] - q0[1]) - (q2[0] - q0[0]) * (q1[1] - q0[1])) / 2;
  }
  return Math.sqrt(a3 / a2);
}

// The face's frame of the field: X its direction in the face's plane, Y = n x X (null where it has none).
export function fieldFrame(face, v) {
  const inPlane = sub(v, face.n.map((x) => x * dot(v, face.n)));
  const l = norm(inPlane);
  if (!(face.area > 0) || !(l > 1e-12)) return null;
  const X = inPlane.map((x) => x / l);
  return { X, Y: cross(face.n, X) };
}

// Stripe direction against the field, each texel's gradient read in its own face's frame of the field (the
// field's direction X and n x X there), so that the field's turning and the surface's bending inside the window
// are not read as error, where stripeAlignment compares a window's 3D tensor with the middle face's field alone
// (straight stripes painted along their exact field read 3.7-7.7° so on the held-out models' atlases, 7.4° on a
// tube as thin as two periods: tests/node/stripe-measure.test.mjs). Each texel adds |g|^2 (cos
// m t, sin m t), t its gradient's angle from X; a face's sum is taken over the faces within 2 periods (Gaussian,
// sigma = period, as stripeAlignment) and its angle, atan2 / m, is the gradient's mean angle from the field.
// Stripes along the field have their gradient across it: m = 2, error = 90° - |angle|. A grid (symmetry 4, the
// face's direction any one of the four): m = 4, both families' gradients at 0 mod 90°, error = |angle|.
// fieldPerFace: 3 per face. Returns the area-weighted mean error (degrees), the shares within 1, 5 and 10°, and
// the error per face (NaN where unmeasured).
export function stripeAlignmentAlongField(glb, fieldPerFace, period, symmetry = 2) {
  const m = symmetry === 4 ? 4 : 2;
  const F = faces(glb);
  const lum = luminance(glb.image);
  const moments = new Float64Array(2 * F.length);
  F.forEach((face, f) => {
    const frame = fieldFrame(face, fieldPerFace.slice(3 * f, 3 * f + 3));
    if (!frame) return;
    const { X, Y } = frame;
    faceGradients(face, glb.image, lum, (g) => {
      const gX = dot(g, X), gY = dot(g, Y), e = gX * gX + gY * gY;
      const angle = m * Math.atan2(gY, gX);
      moments[2 * f] += e * Math.cos(angle);
      moments[2 * f + 1] += e * Math.sin(angle);
    });
  });
  const neighbours = windowOf(F, period);
  const errors = new Float64Array(F.length).fill(NaN);
  let area = 0, sum = 0, w1 = 0, w5 = 0, w10 = 0;
  F.forEach((face, f) => {
    if (!(face.area > 0) || !(norm(fieldPerFace.slice(3 * f, 3 * f + 3)) > 1e-9)) return;
    let C = 0, S = 0;
    neighbours(f, (g, w) => {
      C += w * moments[2 * g];
      S += w * moments[2 * g + 1];
    });
    if (!(C * C + S * S > 0)) return;
    const angle = (Math.atan2(S, C) / m) * (180 / Math.PI);
    const deg = m === 2 ? 90 - Math.abs(angle) : Math.abs(angle);
    errors[f] = deg;
    area += face.area, sum += face.area * deg;
    w1 += deg <= 1 ? face.area : 0, w5 += deg <= 5 ? face.area : 0, w10 += deg <= 10 ? face.area : 0;
  });
  return { meanDegrees: sum / area, within1: w1 / area, within5: w5 / area, within10: w10 / area, errors };
}

// A grid's two families apart, each against its own direction of a cross field: each texel's gradient, in its
// face's frame of the field, belongs to the lines along X where it lies nearer Y, else to those along Y, and adds
// |g|^2 (cos 2t, sin 2t) to that family's moments, t its angle from the family's gradient direction (Y or X). A
// window (as above) takes each neighbour's families in the middle face's order: a cross field's face direction is
// any one of its four, so a neighbour whose X lies nearer the middle face's Y has its two swapped. Returns, per
// family (0: along X, 1: along Y of each face), the error per face (degrees; NaN where unmeasured).
export function gridFamiliesAlongField(glb, fieldPerFace, period) {
  const F = faces(glb);
  const lum = luminance(glb.image);
  const moments = new Float64Array(4 * F.length);
  const frames = F.map((face, f) => fieldFrame(face, fieldPerFace.slice(3 * f, 3 * f + 3)));
  F.forEach((face, f) => {
    if (!frames[f]) return;
    const { X, Y } = frames[f];
    faceGradients(face, glb.image, lum, (g) => {
      const gX = dot(g, X), gY = dot(g, Y), e = gX * gX + gY * gY;
      const family = Math.abs(gY) >= Math.abs(gX) ? 0 : 1;
      const t = Math.atan2(gY, gX) - (family === 0 ? Math.PI / 2 : 0);
      moments[4 * f + 2 * family] += e * Math.cos(2 * t);
      moments[4 * f + 2 * family + 1] += e * Math.sin(2 * t);
    });
  });
  const neighbours = windowOf(F, period);
  const families = [new Float64Array(F.length).fill(NaN), new Float64Array(F.length).fill(NaN)];
  F.forEach((face, f) => {
    if (!frames[f] || !(norm(fieldPerFace.slice(3 * f, 3 * f + 3)) > 1e-9)) return;
    const sums = [0, 0, 0, 0];
    neighbours(f, (g, w) => {
      if (!frames[g]) return;
      const swap = Math.abs(dot(frames[g].X, frames[f].Y)) > Math.abs(dot(frames[g].X, frames[f].X));
      for (let k = 0; k < 2; k++) {
        const into = swap ? 1 - k : k;
        sums[2 * into] += w * moments[4 * g + 2 * k];
        sums[2 * into + 1] += w * moments[4 * g + 2 * k + 1];
      }
    });
    for (let k = 0; k < 2; k++) {
      const [C, S] = [sums[2 * k], sums[2 * k + 1]];
      if (C * C + S * S > 0) families[k][f] = Math.abs((Math.atan2(S, C) / 2) * (180 / Math.PI));
    }
  });
  return families;
}

// A truth for the measures above: the GLB's texture repainted, inside its faces, with the level sets of the
// height along `direction` (unit; the planes d·P = k / frequency cutting the surface), grey 1 + 127 (1 + cos 2π
// f d·P), the texels outside the faces untextured, and the field those stripes follow exactly, per face:
// n x (d - (d·n) n). A face across which the height barely changes (|d - (d·n) n| < 0.3) gets no field, and is
// not measured. Returns {glb, field}.
export function paintHeightStripes(glb, direction, frequency) {
  const { width: W, height: H } = glb.image;
  // Texels outside every face (the gutters, which the bake fills with its own pattern) left untextured, so that
  // no gradient mixes the two.
  const pixels = new Uint8Array(glb.image.pixels.length);
  const F = faces(glb);
  const field = new Float64Array(3 * F.length);
  F.forEach((face, f) => {
    const along = sub(direction, face.n.map((x) => x * dot(direction, face.n)));
    if (norm(along) >= 0.3) field.set(cross(face.n, along), 3 * f);
    const [q0] = face.Q;
    facePixels(face, W, H, (x, y, A) => {
      const dx = x + 0.5 - q0[0], dy = y + 0.5 - q0[1];
      const P = [0, 1, 2].map((k) => face.P[0][k] + A[0][k] * dx + A[1][k] * dy);
      const grey = 1 + Math.round(127 * (1 + Math.cos(2 * Math.PI * frequency * dot(direction, P))));
      const i = 4 * (y * W + x);
      pixels[i] = pixels[i + 1] = pixels[i + 2] = grey;
      pixels[i + 3] = 255;
    });
  });
  return { glb: { ...glb, image: { ...glb.image, pixels } }, field };
}
