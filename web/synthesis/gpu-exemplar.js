// SPDX-License-Identifier: GPL-2.0-or-later
// The exemplar's analysis (exemplar.js tables: per Gaussian-stack level the 8-D appearance and neighbourhood
// vectors, k-coherence candidates and the neighbourhood projection) as the textures and uniforms the
// correction pass reads, plus the exemplar's colours for rendering. Upload and release only: the layout the
// shaders (shaders.js) expect is decided here, once.
import { FloatTarget, GLError, isPow2 } from './gl.js';

// 8 floats per pixel as two RGBA32F images.
function split(a8) {
  const n = a8.length / 8, lo = new Float32Array(4 * n), hi = new Float32Array(4 * n);
  for (let p = 0; p < n; p++)
    for (let c = 0; c < 4; c++) {
      lo[4 * p + c] = a8[8 * p + c];
      hi[4 * p + c] = a8[8 * p + 4 + c];
    }
  return [lo, hi];
}

// uProj[4k + b]: b = 0: a0 -> y0, 1: a1 -> y0, 2: a0 -> y1, 3: a1 -> y1; column c of each 4x4 block holds the
// weights of appearance component (4 * (b & 1) + c) in reduced dimensions 4 * (b >> 1) .. + 3.
function packProjection(projection) {
  const proj = new Float32Array(512);
  for (let k = 0; k < 8; k++)
    for (let b = 0; b < 4; b++)
      for (let c = 0; c < 4; c++)
        for (let r = 0; r < 4; r++)
          proj[16 * (4 * k + b) + 4 * c + r] = projection[64 * k + 8 * (4 * (b & 1) + c) + 4 * (b >> 1) + r];
  return proj;
}

// tables: {size, levels: [{appearance, neighbourhood, candidates, projection, projectionOffset}], rgba8}.
// Returns {size, levels: [{app0, app1, nbr0, nbr1, cand, proj, projOff}], rgba (texture), rgba8}.
export function uploadExemplar(gl, tables) {
  const m = tables.size;
  if (!isPow2(m)) throw new GLError(`exemplar size must be a power of two (got ${m})`);
  const tex = (data) => new FloatTarget(gl, m, m, data, { target: false });
  const levels = tables.levels.map((L) => {
    const [app0, app1] = split(L.appearance);
    const [nbr0, nbr1] = split(L.neighbourhood);
    return {
      app0: tex(app0),
      app1: tex(app1),
      nbr0: tex(nbr0),
      nbr1: tex(nbr1),
      cand: tex(L.candidates),
      proj: packProjection(L.projection),
      projOff: Float32Array.from(L.projectionOffset),
    };
  });
  const rgba = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, rgba);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, m, m, 0, gl.RGBA, gl.UNSIGNED_BYTE, tables.rgba8);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
  return { size: m, levels, rgba, rgba8: tables.rgba8 };
}

export function disposeExemplar(gl, exemplar) {
  for (const L of exemplar.levels) for (const t of [L.app0, L.app1, L.nbr0, L.nbr1, L.cand]) t.dispose();
  gl.deleteTexture(exemplar.rgba);
}
