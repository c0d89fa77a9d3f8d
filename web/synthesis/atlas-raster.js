// SPDX-License-Identifier: GPL-2.0-or-later
// The mesh laid out in one atlas on the synthesis context: the per-corner vertex data that rasterizes the
// per-texel Jacobian (UV, field, 3D-to-UV frame, normal), the render targets of every pyramid level, and the
// seam indirection (seams.js) per level. One per atlas (resolution and UVs); the synthesizer works in its
// levels. Kept apart from the level loop because it changes only when the model or the atlas does.
import { FloatTarget, GLError, drawFullscreen, isPow2 } from './gl.js';
import { CORNER_FLOATS as STRIDE, cornerData } from './atlas-corners.js';
import { gutterQuads } from './atlas-gutter.js';
import { halfEdgeNeighbours } from '../geometry/mesh-geometry.js';
import { coarserIndirection, seamIndirection } from './seams.js';

export class AtlasRaster {
  // positions (3 per vertex), triangles (3 per face), cornerUVs (6 per face, in [0, 1]), resolution a power of
  // two; neighbour: the half-edge map of geometry/mesh-geometry.js when the caller holds one (the model's
  // Surface), else it is derived, once, for what is made here. corners and seams: cornerData() (with its gutter
  // quads, atlas-gutter.js, for `gutter` texels) and seamIndirection() of this mesh and atlas when made elsewhere
  // (the core's worker, atlas-prepared.js), else made here.
  constructor(
    gl,
    jacobianProgram,
    { resolution, positions, triangles, cornerUVs, neighbour = null, corners = null, seams = null, gutter = 2 },
  ) {
    if (!isPow2(resolution) || resolution < 4 || resolution > 4096)
      throw new GLError(`atlas resolution must be a power of two in [4, 4096] (got ${resolution})`);
    const nF = triangles.length / 3;
    if (cornerUVs.length !== 6 * nF)
      throw new GLError(`cornerUVs must hold 6 numbers per face (${6 * nF}), got ${cornerUVs.length}`);
    this.gl = gl;
    this.resolution = resolution;
    this.triangles = Int32Array.from(triangles);
    const { data, faceArea, used, area3, areaUV } = corners ?? cornerData(positions, triangles, cornerUVs);
    if (!used) throw new GLError('the atlas has no usable triangle (all degenerate in UV or 3D)');
    this.data = data;
    const halfEdges = () => (neighbour ??= halfEdgeNeighbours(triangles, positions.length / 3));
    const made = { triangles, cornerUVs, corners: { data }, resolution, gutter };
    const quads = corners?.gutter ?? gutterQuads({ ...made, neighbour: halfEdges() });
    this.gutterData = quads.data;
    this.gutterSource = quads.source;
    this.gutterIndices = quads.indices;
    this.fieldData = new Float32Array(9 * nF + 3 * quads.source.length);
    this.faceArea = faceArea;
    this.vertexCount = 3 * nF;
    this.usedFaces = used;
    this.coverage = areaUV;
    // Surface length per atlas texel at the atlas's mean density.
    this.texelLength = Math.sqrt(area3 / areaUV) / resolution;
    this.#vertexArray(jacobianProgram.program);
    this.levels = [];
    const t0 = performance.now();
    this.seamMaps = seams ?? seamIndirection({ positions, triangles, neighbour: halfEdges() }, cornerUVs, resolution);
    this.seams = {
      edges: this.seamMaps.seamEdges,
      redirectedTexels: this.seamMaps.redirected,
      ms: (this.seamMaps.ms ?? 0) + performance.now() - t0,
    };
  }

  // The GPU textures, one per step, for a caller to yield between them: each allocation can wait for the GPU
  // process (a 16 MB target took 55-88 ms behind an 832k-face view with software GL). Per level (finest first,
  // down to 2x2): the Jacobian, the state as four parity-class quarters plus a spare (sub-passes write a quarter
  // into the spare, which then takes its place), the unpacked result, and the seam indirection (an all-zero map
  // where the atlas has no seams). Not checked for completeness: the context has float render targets
  // (createContext), and a check waits for the GPU process.
  *allocate() {
    const { gl, resolution } = this;
    const target = (size) => new FloatTarget(gl, size, size, null, { check: false });
    for (let r = resolution, k = 0; r >= 2; r >>= 1, k++) {
      const L = { size: r, quarters: [] };
      this.levels.push(L);
      for (const name of ['jac', 'result', 'spare']) {
        L[name] = target(name === 'spare' ? r / 2 : r);
        yield;
      }
      for (let q = 0; q < 4; q++) L.quarters.push(target(r / 2));
      yield;
      const map = k === 0 ? this.seamMaps.map : coarserIndirection(this.seamMaps.map, resolution, k);
      L.indirection = new FloatTarget(gl, r, r, map, { target: false });
      yield;
    }
    this.seamMaps = null;
  }

  #vertexArray(program) {
    const gl = this.gl;
    this.buffer = gl.createBuffer();
    this.fieldBuffer = gl.createBuffer();
    this.indexBuffer = gl.createBuffer();
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    const attrib = (name, size, stride, offset) => {
      const loc = gl.getAttribLocation(program, name);
      if (loc < 0) return;
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, gl.FLOAT, false, stride * 4, offset * 4);
    };
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    // Allocated here, filled by the first synthesis a slice per task (rasterSteps): 110 MB at 832k faces. The
    // gutter's vertices follow the corners'.
    gl.bufferData(gl.ARRAY_BUFFER, this.data.byteLength + this.gutterData.byteLength, gl.STATIC_DRAW);
    this.facesUploaded = 0;
    attrib('aUV', 2, STRIDE, 0);
    attrib('aG1', 3, STRIDE, 2);
    attrib('aG2', 3, STRIDE, 5);
    attrib('aNormal', 3, STRIDE, 8);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.fieldBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.fieldData.byteLength, gl.DYNAMIC_DRAW);
    attrib('aField', 3, 3, 0);
    // WebGL 2 has no base vertex: the gutter's indices are moved past the corners here.
    const indices = this.gutterIndices.map((i) => i + this.vertexCount);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
  }

  // The Jacobian of every level for the field: the per-vertex `vertexVectors` (3 per vertex) or, for a combed
  // line or cross field, {cornerVectors} (9 per face, corner k of face f at 9f + 3k: geometry/chart-comb.js);
  // rasterized at the finest level with the gutter's quads past the charts, then averaged down. programs:
  // the synthesizer's; vao: its full-screen one. A generator: the field is filled and uploaded a slice of
  // faces at a time, and it yields after each slice so that the caller can give the page its frames (a
  // synthesis run step by step, synthesizer.js); the raster's draws are issued when it returns. Returns the
  // reference magnitude (area-weighted mean |field|).
  *rasterSteps(programs, vao, field, o) {
    const gl = this.gl;
    const nF = this.triangles.length / 3;
    const sums = { mag: 0, area: 0 };
    yield* this.#uploadFixed(Math.max(1, o.sliceFaces >> 2)); // 11 floats a corner against the field's 3
    const corners = field?.cornerVectors ?? null;
    if (corners && corners.length !== 9 * nF)
      throw new GLError(`cornerVectors must hold 9 numbers per face (${9 * nF}), got ${corners.length}`);
    // A slice of o.sliceFaces faces per task: at 832k faces the whole field in one bufferSubData (with the fixed
    // data beside it, 140 MB) held the page for 5-7 s while the GPU process caught up; 32k faces are ~1 MB.
    for (let f0 = 0; f0 < nF; f0 += o.sliceFaces) {
      const f1 = Math.min(nF, f0 + o.sliceFaces);
      if (corners) this.#fillCorners(corners, f0, f1, sums);
      else this.#fillField(field, f0, f1, sums);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.fieldBuffer);
      gl.bufferSubData(gl.ARRAY_BUFFER, 36 * f0, this.fieldData, 9 * f0, 9 * (f1 - f0));
      gl.bindBuffer(gl.ARRAY_BUFFER, null);
      yield; // the last slice too: its upload is waited for apart from the raster's draws
    }
    this.#fillGutter();
    const magRef = sums.mag > 0 ? sums.mag / sums.area : 1;
    // The gutter's quads first, then the triangles over them: a texel a triangle covers is always its own.
    const finest = this.levels[0];
    const rho = o.featureScale * this.texelLength;
    finest.jac.bindAsTarget();
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    programs.jacobian
      .use()
      .float('uInvRho', 1 / rho)
      .float('uTexel', 1 / this.resolution)
      .float('uMagRef', magRef)
      .float('uMagExponent', o.magnitudeExponent);
    gl.bindVertexArray(this.vao);
    const quads = this.gutterIndices.length;
    if (quads) gl.drawElements(gl.TRIANGLES, quads, gl.UNSIGNED_INT, 0);
    gl.drawArrays(gl.TRIANGLES, 0, this.vertexCount);
    gl.bindVertexArray(null);
    for (let k = 1; k < this.levels.length; k++) {
      this.levels[k].jac.bindAsTarget();
      programs.jacobianDown.use().texture('uJac', this.levels[k - 1].jac);
      drawFullscreen(gl, vao);
    }
    return magRef;
  }

  // The fixed data still to go to the GPU, `slice` faces per task; the array is let go once all is there.
  *#uploadFixed(slice) {
    const gl = this.gl, nF = this.vertexCount / 3, floats = 3 * STRIDE;
    while (this.facesUploaded < nF) {
      const f0 = this.facesUploaded, f1 = Math.min(nF, f0 + slice);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
      gl.bufferSubData(gl.ARRAY_BUFFER, 4 * floats * f0, this.data, floats * f0, floats * (f1 - f0));
      gl.bindBuffer(gl.ARRAY_BUFFER, null);
      this.facesUploaded = f1;
      if (f1 === nF) this.#uploadGutter();
      else yield;
    }
  }

  #uploadGutter() {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, this.data.byteLength, this.gutterData);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    this.data = null;
    this.gutterData = null;
  }

  // The gutter's vertices take the field of the corners they were made from (after every face's field is in).
  #fillGutter() {
    const out = this.fieldData, src = this.gutterSource, base = 3 * this.vertexCount;
    for (let i = 0; i < src.length; i++) {
      const o = base + 3 * i, c = 3 * src[i];
      out[o] = out[c];
      out[o + 1] = out[c + 1];
      out[o + 2] = out[c + 2];
    }
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.fieldBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 4 * base, out, base);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
  }

  // The field per corner of faces f0 .. f1 - 1 from the vertices', and their part of the reference magnitude
  // (area-weighted mean over faces of the corner mean). Math.sqrt, not Math.hypot: 5 x faster in V8, and this
  // is on the path from a stroke to its texture (bunny00: 7 -> 1.3 ms).
  #fillField(vertexVectors, f0, f1, sums) {
    const T = this.triangles, out = this.fieldData, A = this.faceArea;
    let magSum = 0, areaSum = 0;
    for (let f = f0; f < f1; f++) {
      let mag = 0;
      for (let k = 0; k < 3; k++) {
        const v = 3 * T[3 * f + k], o = 9 * f + 3 * k;
        const x = vertexVectors[v], y = vertexVectors[v + 1], z = vertexVectors[v + 2];
        out[o] = x;
        out[o + 1] = y;
        out[o + 2] = z;
        mag += Math.sqrt(x * x + y * y + z * z);
      }
      magSum += (mag / 3) * A[f];
      areaSum += A[f];
    }
    sums.mag += magSum;
    sums.area += areaSum;
  }

  // The same from a per-corner field (9 per face).
  #fillCorners(C, f0, f1, sums) {
    const out = this.fieldData;
    out.set(C.subarray(9 * f0, 9 * f1), 9 * f0);
    for (let f = f0; f < f1; f++) {
      let mag = 0;
      for (let c = 9 * f; c < 9 * f + 9; c += 3) {
        const x = C[c], y = C[c + 1], z = C[c + 2];
        mag += Math.sqrt(x * x + y * y + z * z) / 3;
      }
      sums.mag += mag * this.faceArea[f];
      sums.area += this.faceArea[f];
    }
  }

  dispose() {
    const gl = this.gl;
    gl.deleteBuffer(this.buffer);
    gl.deleteBuffer(this.fieldBuffer);
    gl.deleteBuffer(this.indexBuffer);
    gl.deleteVertexArray(this.vao);
    for (const L of this.levels)
      for (const t of [L.jac, L.result, L.spare, L.spare2, L.indirection, ...L.quarters]) t?.dispose();
    this.levels = [];
  }
}
