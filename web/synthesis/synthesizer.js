// SPDX-License-Identifier: GPL-2.0-or-later
// Field-guided, exemplar-based parallel texture synthesis in a mesh's texture atlas, on the GPU (WebGL2):
// Lefebvre & Hoppe 2005 ("Parallel controllable texture synthesis": coarse-to-fine coordinate upsampling, jitter,
// sub-pass correction; anisometric synthesis through a per-texel Jacobian) with the appearance-space exemplar and
// k-coherence of Lefebvre & Hoppe 2006. The exemplar analysis (Gaussian stack, appearance PCA, neighbourhood PCA,
// k-coherence) comes from the wasm core (core/texture/, ExemplarAnalysis binding); everything per texel runs here
// in float render targets, with no read-back inside the level loop.
//
// Usage:
//   const syn = new Synthesizer();                 // its own WebGL2 context
//   syn.setExemplar(tables);                       // exemplarTables(analysis) from exemplar.js
//   syn.setAtlas({resolution, positions, triangles, cornerUVs});
//   const stats = syn.synthesize(vertexVectors, {featureScale, magnitudeExponent, seed, ...});
//   syn.readCoordinates(), syn.readJacobian(), syn.readColour({magnification, nearest})
import { coarserIndirection, seamIndirection } from './seams.js';
import {
  ByteTarget,
  FloatTarget,
  FULLSCREEN_VS,
  GLError,
  Program,
  createContext,
  drawFullscreen,
  sync,
} from './gl.js';
import {
  COPY_FS,
  CORRECT_FS,
  DILATE_FS,
  JACOBIAN_DOWN_FS,
  JACOBIAN_FS,
  JACOBIAN_VS,
  RESOLVE_FS,
  SEAM_RESOLVE_FS,
  UNPACK_FS,
  UPSAMPLE_FS,
} from './shaders.js';

export const DEFAULTS = Object.freeze({
  featureScale: 1, // 1: one exemplar pixel spans one atlas texel (at the atlas's mean density) on the surface
  magnitudeExponent: 0, // texture scale follows (|field| / mean |field|)^exponent; 0 = direction only (paper Sec. 6)
  jitter: 0.2, // randomness per level in level texels (LH05 r_l); a number or one value per level, coarsest first
  finestJitter: 0.0, // the finest level adds no jitter of its own by default
  passes: 2, // correction passes per level, each of 4 sub-passes
  kappa: 0.25, // extra cost of non-coherent (k-coherence) candidates, LH06's coherence bias
  seed: 1,
  gutter: 2, // texels of Jacobian dilation around the charts
  seams: true, // follow the seam indirection across chart boundaries (atlases with seams only)
  timing: 'levels', // 'levels': wait for the GPU after each level (per-level times); 'total': only at the end
});

const defaultNextFrame = () =>
  new Promise((resolve) => (typeof requestAnimationFrame === 'function' ? requestAnimationFrame(() => resolve()) : setTimeout(resolve, 0)));

const isPow2 = (n) => Number.isInteger(n) && n > 0 && (n & (n - 1)) === 0;

export class Synthesizer {
  constructor(gl = createContext()) {
    this.gl = gl;
    this.vao = gl.createVertexArray();
    this.programs = {
      jacobian: new Program(gl, JACOBIAN_VS, JACOBIAN_FS, 'jacobian'),
      dilate: new Program(gl, FULLSCREEN_VS, DILATE_FS, 'dilate'),
      jacobianDown: new Program(gl, FULLSCREEN_VS, JACOBIAN_DOWN_FS, 'jacobian-down'),
      upsample: new Program(gl, FULLSCREEN_VS, UPSAMPLE_FS, 'upsample'),
      correct: new Program(gl, FULLSCREEN_VS, CORRECT_FS, 'correct'),
      unpack: new Program(gl, FULLSCREEN_VS, UNPACK_FS, 'unpack'),
      resolve: new Program(gl, FULLSCREEN_VS, RESOLVE_FS, 'resolve'),
      copy: new Program(gl, FULLSCREEN_VS, COPY_FS, 'copy'),
      seamResolve: new Program(gl, FULLSCREEN_VS, SEAM_RESOLVE_FS, 'seam-resolve'),
    };
    this.exemplar = null;
    this.atlas = null;
    this.levels = [];
    this.lastStats = null;
  }

  // tables: {size, levels: [{appearance, neighbourhood, candidates, projection, projectionOffset}], rgba8}
  setExemplar(tables) {
    const gl = this.gl;
    const m = tables.size;
    if (!isPow2(m)) throw new GLError(`exemplar size must be a power of two (got ${m})`);
    this.#disposeExemplar();
    const split = (a8) => {
      const n = a8.length / 8, lo = new Float32Array(4 * n), hi = new Float32Array(4 * n);
      for (let p = 0; p < n; p++)
        for (let c = 0; c < 4; c++) {
          lo[4 * p + c] = a8[8 * p + c];
          hi[4 * p + c] = a8[8 * p + 4 + c];
        }
      return [lo, hi];
    };
    const tex = (data) => new FloatTarget(gl, m, m, data, { target: false });
    const levels = tables.levels.map((L) => {
      const [app0, app1] = split(L.appearance);
      const [nbr0, nbr1] = split(L.neighbourhood);
      // uProj[4k + b]: b = 0: a0 -> y0, 1: a1 -> y0, 2: a0 -> y1, 3: a1 -> y1; column c of each 4x4 block holds
      // the weights of appearance component (4 * (b & 1) + c) in reduced dimensions 4 * (b >> 1) .. + 3.
      const proj = new Float32Array(512);
      for (let k = 0; k < 8; k++)
        for (let b = 0; b < 4; b++)
          for (let c = 0; c < 4; c++)
            for (let r = 0; r < 4; r++)
              proj[16 * (4 * k + b) + 4 * c + r] = L.projection[64 * k + 8 * (4 * (b & 1) + c) + 4 * (b >> 1) + r];
      return {
        app0: tex(app0),
        app1: tex(app1),
        nbr0: tex(nbr0),
        nbr1: tex(nbr1),
        cand: tex(L.candidates),
        proj,
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
    this.exemplar = { size: m, levels, rgba, rgba8: tables.rgba8 };
  }

  // The mesh in the atlas: positions (3 per vertex), triangles (3 per face), cornerUVs (6 per face, in [0, 1]),
  // resolution a power of two. Builds the per-corner vertex data of the Jacobian raster.
  setAtlas({ resolution, positions, triangles, cornerUVs }) {
    if (!isPow2(resolution) || resolution < 4 || resolution > 4096) throw new GLError(`atlas resolution must be a power of two in [4, 4096] (got ${resolution})`);
    const nF = triangles.length / 3;
    if (cornerUVs.length !== 6 * nF) throw new GLError(`cornerUVs must hold 6 numbers per face (${6 * nF}), got ${cornerUVs.length}`);
    const gl = this.gl;
    const stride = 14;
    const data = new Float32Array(3 * nF * stride);
    let area3 = 0, areaUV = 0, used = 0;
    const faceArea = new Float64Array(nF);
    for (let f = 0; f < nF; f++) {
      const a = 3 * triangles[3 * f], b = 3 * triangles[3 * f + 1], c = 3 * triangles[3 * f + 2];
      const e1 = [positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]];
      const e2 = [positions[c] - positions[a], positions[c + 1] - positions[a + 1], positions[c + 2] - positions[a + 2]];
      const u = cornerUVs.subarray(6 * f, 6 * f + 6);
      const du1 = u[2] - u[0], dv1 = u[3] - u[1], du2 = u[4] - u[0], dv2 = u[5] - u[1];
      const det = du1 * dv2 - du2 * dv1;
      const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
      const nl = Math.hypot(n[0], n[1], n[2]);
      faceArea[f] = nl / 2;
      if (!(Math.abs(det) > 1e-14) || !(nl > 0)) continue; // degenerate in UV or in 3D: not drawn
      used++;
      area3 += nl / 2;
      areaUV += Math.abs(det) / 2;
      const G1 = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) / det);
      const G2 = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) / det);
      for (let k = 0; k < 3; k++) {
        const o = (3 * f + k) * stride;
        data[o] = u[2 * k];
        data[o + 1] = u[2 * k + 1];
        // field (2..4) is filled per synthesis
        data.set(G1, o + 5);
        data.set(G2, o + 8);
        data.set([n[0] / nl, n[1] / nl, n[2] / nl], o + 11);
      }
    }
    if (!used) throw new GLError('the atlas has no usable triangle (all degenerate in UV or 3D)');
    this.#disposeAtlas();
    const buffer = gl.createBuffer();
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    const prog = this.programs.jacobian.program;
    const attrib = (name, size, offset) => {
      const loc = gl.getAttribLocation(prog, name);
      if (loc < 0) return;
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, gl.FLOAT, false, stride * 4, offset * 4);
    };
    attrib('aUV', 2, 0);
    attrib('aField', 3, 2);
    attrib('aG1', 3, 5);
    attrib('aG2', 3, 8);
    attrib('aNormal', 3, 11);
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    this.atlas = {
      resolution,
      triangles: Int32Array.from(triangles),
      faceArea,
      data,
      stride,
      buffer,
      vao,
      vertexCount: 3 * nF,
      // Surface length per atlas texel at the atlas's mean density.
      texelLength: Math.sqrt(area3 / areaUV) / resolution,
      usedFaces: used,
      coverage: areaUV,
    };
    // Per level (finest first, down to 2x2): the Jacobian, the state as four parity-class quarters plus a spare
    // (sub-passes write a quarter into the spare, which then takes its place), and the unpacked result.
    this.levels = [];
    for (let r = resolution; r >= 2; r >>= 1) {
      const h = r / 2;
      this.levels.push({
        size: r,
        jac: new FloatTarget(gl, r, r),
        result: new FloatTarget(gl, r, r),
        quarters: [0, 1, 2, 3].map(() => new FloatTarget(gl, h, h)),
        spare: new FloatTarget(gl, h, h),
      });
    }
    this.jacScratch = new FloatTarget(gl, resolution, resolution);
    // Seam indirection per level (an all-zero map where the atlas has no seams).
    const t0 = performance.now();
    const seams = seamIndirection(positions, triangles, cornerUVs, resolution);
    this.levels.forEach((L, k) => {
      L.indirection = new FloatTarget(gl, L.size, L.size, k === 0 ? seams.map : coarserIndirection(seams.map, resolution, k), { target: false });
    });
    this.atlas.seams = { edges: seams.seamEdges, redirectedTexels: seams.redirected, ms: performance.now() - t0 };
  }

  // Runs the whole pyramid for the per-vertex field `vertexVectors` (3 per vertex, the core's vertexVectors).
  // Returns {levels: [{size, stackLevel, spacing, ms}], jacobianMs, totalMs, ...}.
  synthesize(vertexVectors, options = {}) {
    const steps = this.#steps(vertexVectors, options);
    for (let r = steps.next(); ; r = steps.next()) if (r.done) return r.value;
  }

  // The same, yielding to the page between draws so that the view keeps rendering and input keeps working
  // while the GPU (software rendering: seconds) works through the pyramid: after each group of draws estimated
  // at about `budgetTexels` texel-shadings, the GL queue is flushed and the next frame awaited. onProgress(f) gets
  // the share done (0..1); when cancelled() turns true the run stops and resolves to null (the previous result
  // stays). Options as synthesize(), plus `finestLevel` (0, or 1 for a quarter-cost preview that stops one level
  // short: the result then lives at half the atlas resolution, see resultLevel).
  async synthesizeInterleaved(vertexVectors, options = {}, { onProgress = () => {}, cancelled = () => false, budgetTexels = 1 << 15, nextFrame = defaultNextFrame } = {}) {
    const steps = this.#steps(vertexVectors, options);
    let pending = 0;
    for (let r = steps.next(); ; r = steps.next()) {
      if (r.done) return r.value;
      pending += r.value.texels;
      onProgress(r.value.progress);
      if (pending >= budgetTexels) {
        pending = 0;
        this.gl.flush();
        await nextFrame();
        if (cancelled()) {
          this.gl.bindFramebuffer(this.gl.FRAMEBUFFER, null);
          return null;
        }
      }
    }
  }

  *#steps(vertexVectors, options) {
    if (!this.exemplar) throw new GLError('no exemplar set');
    if (!this.atlas) throw new GLError('no atlas set');
    const o = { ...DEFAULTS, ...options };
    const gl = this.gl;
    const t0 = performance.now();
    const { resolution } = this.atlas;
    const m = this.exemplar.size;
    const stackTop = this.exemplar.levels.length - 1;

    const finestLevel = Math.min(o.finestLevel ?? 0, this.levels.length - 1);
    this.#rasterJacobian(vertexVectors, o);
    let done = 0;
    const work = (texels) => ({ texels, progress: Math.min(1, (done += texels) / total) });
    // Total shading work: the Jacobian and per level 4 upsample quarters, 4 x passes correction quarters
    // (weighted x8: they read ~90 texels each) and the unpack.
    let total = resolution * resolution * (1 + o.gutter);
    for (let k = finestLevel; k < this.levels.length; k++) total += this.levels[k].size ** 2 * (2 + 8 * o.passes);
    yield work(resolution * resolution * (1 + o.gutter));
    if (o.timing === 'levels') sync(gl, this.levels[0].jac);
    const tJac = performance.now();

    // Level plan: synthesis level k (k texels-of-finest per texel = 2^k) reads stack level
    // round(log2(sigma_k)), sigma_k = 2^k / featureScale exemplar pixels per texel; the coarsest level is the first
    // whose stack level reaches the top of the stack (nearly a constant colour), or a 2x2 atlas.
    const sigma0 = 1 / o.featureScale;
    let coarsest = 0;
    while (coarsest + 1 < this.levels.length) {
      coarsest++;
      if (Math.round(Math.log2(sigma0 * 2 ** coarsest)) >= stackTop - 1) break;
    }
    const plan = [];
    coarsest = Math.max(coarsest, finestLevel);
    for (let k = coarsest; k >= finestLevel; k--) {
      const s = Math.min(stackTop, Math.max(0, Math.round(Math.log2(sigma0 * 2 ** k))));
      plan.push({ k, stackLevel: s, spacing: 2 ** s });
    }
    const jitterOf = (i, k) => {
      if (k === 0) return o.finestJitter;
      return Array.isArray(o.jitter) ? (o.jitter[i] ?? o.jitter[o.jitter.length - 1]) : o.jitter;
    };

    const levelStats = [];
    let parent = null;
    let tLevel = performance.now();
    for (const [i, step] of plan.entries()) {
      const L = this.levels[step.k];
      const E = this.exemplar.levels[step.stackLevel];
      const half = L.size / 2;
      // Upsample (or initialise) each parity class into its quarter.
      for (let c = 0; c < 4; c++) {
        L.quarters[c].bindAsTarget();
        this.programs.upsample
          .use()
          .texture('uParent', parent ?? L.jac)
          .texture('uJac', L.jac)
          .int('uCoarsest', parent ? 0 : 1)
          .ivec2('uClass', c & 1, c >> 1)
          .float('uJitter', jitterOf(i, step.k))
          .int('uLevel', step.k)
          .int('uSeed', o.seed | 0)
          .float('uM', m);
        drawFullscreen(gl, this.vao);
      }
      yield work(L.size * L.size);
      // Correction: passes x 4 sub-passes, one parity class each, in LH05's order (0,0), (1,1), (1,0), (0,1).
      const prog = this.programs.correct;
      for (let pass = 0; pass < o.passes; pass++) {
        for (const c of [0, 3, 1, 2]) {
          L.spare.bindAsTarget();
          prog
            .use()
            .texture('uS0', L.quarters[0])
            .texture('uS1', L.quarters[1])
            .texture('uS2', L.quarters[2])
            .texture('uS3', L.quarters[3])
            .texture('uJac', L.jac)
            .texture('uIndir', L.indirection)
            .int('uSeams', o.seams ? 1 : 0)
            .texture('uApp0', E.app0)
            .texture('uApp1', E.app1)
            .texture('uNbr0', E.nbr0)
            .texture('uNbr1', E.nbr1)
            .texture('uCand', E.cand)
            .mat4v('uProj', E.proj)
            .vec4v('uProjOff', E.projOff)
            .ivec2('uSize', L.size, L.size)
            .ivec2('uClass', c & 1, c >> 1)
            .int('uMask', m - 1)
            .float('uM', m)
            .float('uH', step.spacing)
            .float('uKappa', o.kappa);
          drawFullscreen(gl, this.vao);
          [L.quarters[c], L.spare] = [L.spare, L.quarters[c]];
          yield work(2 * L.size * L.size);
        }
      }
      L.result.bindAsTarget();
      this.programs.unpack
        .use()
        .texture('uS0', L.quarters[0])
        .texture('uS1', L.quarters[1])
        .texture('uS2', L.quarters[2])
        .texture('uS3', L.quarters[3]);
      drawFullscreen(gl, this.vao);
      parent = L.result;
      if (step.k === finestLevel && o.seams) {
        // Gutter texels next to seams take the coordinates across the seam (for the magnified rendering).
        L.spare2 ??= new FloatTarget(gl, L.size, L.size);
        L.spare2.bindAsTarget();
        this.programs.seamResolve.use().texture('uCoord', L.result).texture('uJac', L.jac).texture('uIndir', L.indirection).float('uM', m);
        drawFullscreen(gl, this.vao);
        [L.result, L.spare2] = [L.spare2, L.result];
        parent = L.result;
      }
      yield work(L.size * L.size);
      if (o.timing === 'levels') sync(gl, L.result);
      const now = performance.now();
      levelStats.push({ size: L.size, stackLevel: step.stackLevel, spacing: step.spacing, jitter: jitterOf(i, step.k), ms: now - tLevel });
      tLevel = now;
    }
    if (o.timing !== 'levels') sync(gl, parent);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const t1 = performance.now();
    this.result = this.levels[finestLevel].result;
    this.resultLevel = finestLevel;
    this.lastStats = {
      resolution: this.levels[finestLevel].size,
      atlasResolution: resolution,
      preview: finestLevel > 0,
      exemplarSize: m,
      featureScale: o.featureScale,
      magnitudeExponent: o.magnitudeExponent,
      passes: o.passes,
      subpasses: 4,
      seed: o.seed,
      levels: levelStats,
      jacobianMs: tJac - t0,
      seams: o.seams ? this.atlas.seams : null,
      totalMs: t1 - t0,
      timing: o.timing,
    };
    return this.lastStats;
  }

  #rasterJacobian(vertexVectors, o) {
    const gl = this.gl;
    const A = this.atlas;
    const nF = A.triangles.length / 3;
    // Field per corner, and the reference magnitude (area-weighted mean over faces of the corner mean).
    let magSum = 0, areaSum = 0;
    for (let f = 0; f < nF; f++) {
      let mag = 0;
      for (let k = 0; k < 3; k++) {
        const v = 3 * A.triangles[3 * f + k];
        const off = (3 * f + k) * A.stride + 2;
        A.data[off] = vertexVectors[v];
        A.data[off + 1] = vertexVectors[v + 1];
        A.data[off + 2] = vertexVectors[v + 2];
        mag += Math.hypot(vertexVectors[v], vertexVectors[v + 1], vertexVectors[v + 2]) / 3;
      }
      magSum += mag * A.faceArea[f];
      areaSum += A.faceArea[f];
    }
    const magRef = magSum > 0 ? magSum / areaSum : 1;
    gl.bindBuffer(gl.ARRAY_BUFFER, A.buffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, A.data);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);

    const finest = this.levels[0];
    // Raster into the scratch target, dilate into the level-0 Jacobian (ping-pong for more than one ring).
    const rho = o.featureScale * A.texelLength;
    let dst = o.gutter % 2 === 0 ? finest.jac : this.jacScratch;
    let other = dst === finest.jac ? this.jacScratch : finest.jac;
    dst.bindAsTarget();
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    this.programs.jacobian
      .use()
      .float('uInvRho', 1 / rho)
      .float('uTexel', 1 / A.resolution)
      .float('uMagRef', magRef)
      .float('uMagExponent', o.magnitudeExponent);
    gl.bindVertexArray(A.vao);
    gl.drawArrays(gl.TRIANGLES, 0, A.vertexCount);
    gl.bindVertexArray(null);
    for (let g = 0; g < o.gutter; g++) {
      [dst, other] = [other, dst];
      dst.bindAsTarget();
      this.programs.dilate.use().texture('uJac', other).ivec2('uSize', A.resolution, A.resolution);
      drawFullscreen(gl, this.vao);
    }
    if (dst !== finest.jac) throw new Error('internal: Jacobian dilation ended in the wrong target');
    for (let k = 1; k < this.levels.length; k++) {
      this.levels[k].jac.bindAsTarget();
      this.programs.jacobianDown.use().texture('uJac', this.levels[k - 1].jac);
      drawFullscreen(gl, this.vao);
    }
    this.magRef = magRef;
  }

  readCoordinates() {
    return this.result.read();
  }

  readJacobian(level = this.resultLevel ?? 0) {
    return this.levels[level].jac.read();
  }

  // The exemplar's colours at the synthesized coordinates: RGBA8, (resolution * magnification)^2, row 0 = v 0.
  // magnification: output pixels per atlas texel (any positive number; the output is resolution * magnification
  // rounded). The same magnification as the page's renderer unless nearest.
  readColour({ magnification = 1, nearest = true } = {}) {
    const gl = this.gl;
    const level = this.levels[this.resultLevel ?? 0];
    const size = Math.round(level.size * magnification);
    const target = new ByteTarget(gl, size, size);
    target.bindAsTarget();
    this.programs.resolve
      .use()
      .texture('uCoord', this.result)
      .texture('uJac', level.jac)
      .texture('uExemplar', this.exemplar.rgba)
      .float('uMag', size / level.size)
      .float('uM', this.exemplar.size)
      .int('uMask', this.exemplar.size - 1)
      .int('uNearest', nearest ? 1 : 0);
    drawFullscreen(gl, this.vao);
    const pixels = target.read();
    target.dispose();
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return { width: size, height: size, pixels };
  }

  // Milliseconds of one plain full-screen pass (one fetch, one RGBA32F write per texel) at size^2, averaged
  // over `repeats` after a warm-up: the unit synthesis times are compared with.
  plainPassMs(size, repeats = 5) {
    const gl = this.gl;
    const a = new FloatTarget(gl, size, size), b = new FloatTarget(gl, size, size);
    const run = (n) => {
      let src = a, dst = b;
      for (let i = 0; i < n; i++) {
        dst.bindAsTarget();
        this.programs.copy.use().texture('uSource', src);
        drawFullscreen(gl, this.vao);
        [src, dst] = [dst, src];
      }
      sync(gl, src);
    };
    run(1);
    const t0 = performance.now();
    run(repeats);
    const ms = (performance.now() - t0) / repeats;
    a.dispose();
    b.dispose();
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return ms;
  }

  #disposeExemplar() {
    if (!this.exemplar) return;
    for (const L of this.exemplar.levels) for (const t of [L.app0, L.app1, L.nbr0, L.nbr1, L.cand]) t.dispose();
    this.gl.deleteTexture(this.exemplar.rgba);
    this.exemplar = null;
  }

  #disposeAtlas() {
    if (!this.atlas) return;
    const gl = this.gl;
    gl.deleteBuffer(this.atlas.buffer);
    gl.deleteVertexArray(this.atlas.vao);
    for (const L of this.levels) for (const t of [L.jac, L.result, L.spare, L.spare2, L.indirection, ...L.quarters]) t?.dispose();
    this.jacScratch?.dispose();
    this.levels = [];
    this.atlas = null;
    this.result = null;
  }

  dispose() {
    this.#disposeExemplar();
    this.#disposeAtlas();
    for (const p of Object.values(this.programs)) p.dispose();
    this.gl.deleteVertexArray(this.vao);
    this.gl.getExtension('WEBGL_lose_context')?.loseContext();
  }
}
