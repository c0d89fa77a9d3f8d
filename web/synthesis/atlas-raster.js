// SPDX-License-Identifier: GPL-2.0-or-later
// The mesh laid out in one atlas on the synthesis context: the atlas's map of faces (per texel its face and
// barycentric coordinates, drawn once per atlas from the faces' UVs and the gutter's quads), the faces' frames
// (3D-to-UV map and normal), the field per corner, the render targets of every pyramid level, and the seam
// indirection (seams.js) per level. A field's Jacobian is then one full-screen pass over the map, whatever the
// face count (drawing bunny00's 75k triangles took SwiftShader 100-130 ms an update, whatever their shader did;
// armadillo-sub2's 832k, 0.75-0.9 s). One per atlas (resolution and UVs); the synthesizer works in its levels.
// Kept apart from the level loop because it changes only when the model or the atlas does.
import { FloatTarget, GLError, drawWithin, isPow2 } from './gl.js';
import { cornerData } from './atlas-corners.js';
import { gutterQuads, gutterReach } from './atlas-gutter.js';
import {
  RASTER_SHARE,
  blockRects,
  coarserRects,
  faceBoxes,
  faceMoved,
  faceNormals,
  noteJacobianDrawn,
} from './raster-delta.js';
import { halfEdgeNeighbours } from '../geometry/mesh-geometry.js';
import { fillCornerField } from './corner-field.js';
import { coarserIndirection, seamIndirection } from './seams.js';

// Texels per row of the per-corner textures (at most; a multiple of 3, so that a face's corners share a row):
// bunny00's 225k corners fill 55 rows.
const CORNER_ROW = 4095;

// Faces apart (in the mesh's order) that two moved faces' corners may be and still go to the GPU in one upload.
const UPLOAD_GAP = 64;

// Texels of a seam map sent to the GPU per step (RGBA32F: 1 MB).
const BAND_TEXELS = 1 << 16;

// The phase (phase-clock.js) of the steps that the first field of an atlas takes for its map of faces.
const FIXED_PHASE = "the atlas's faces to the GPU, their map drawn (once per atlas)";

// The locator program's attributes (aUV: 2 floats, aCorner: an int, a vertex each) from the two buffers, in the
// vertex array bound.
export function locatorAttributes(gl, program, uvBuffer, cornerBuffer) {
  gl.bindBuffer(gl.ARRAY_BUFFER, uvBuffer);
  const uvAt = gl.getAttribLocation(program, 'aUV');
  gl.enableVertexAttribArray(uvAt);
  gl.vertexAttribPointer(uvAt, 2, gl.FLOAT, false, 8, 0);
  gl.bindBuffer(gl.ARRAY_BUFFER, cornerBuffer);
  const cornerAt = gl.getAttribLocation(program, 'aCorner');
  gl.enableVertexAttribArray(cornerAt);
  gl.vertexAttribIPointer(cornerAt, 1, gl.INT, 4, 0);
}

export class AtlasRaster {
  // positions (3 per vertex), triangles (3 per face), cornerUVs (6 per face, in [0, 1]), resolution a power of
  // two; neighbour: the half-edge map of geometry/mesh-geometry.js when the caller holds one (the model's
  // Surface), else it is derived, once, for what is made here. corners and seams: cornerData() (with its gutter
  // quads, atlas-gutter.js, for `gutter` texels) and seamIndirection() of this mesh and atlas when made elsewhere
  // (the core's worker, atlas-prepared.js), else made here. locatorProgram: the synthesizer's map-of-faces
  // program (its attributes' locations).
  constructor(
    gl,
    locatorProgram,
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
    const made = corners ?? cornerData(positions, triangles, cornerUVs);
    const { uv, frames, faceArea, used, area3, areaUV } = made;
    if (!used) throw new GLError('the atlas has no usable triangle (all degenerate in UV or 3D)');
    this.vertexCount = 3 * nF;
    this.#cornerTextureSize(gl);
    this.uv = uv;
    this.frames = frames;
    const halfEdges = () => (neighbour ??= halfEdgeNeighbours(triangles, positions.length / 3));
    const quads =
      made.gutter ?? gutterQuads({ triangles, cornerUVs, corners: made, resolution, gutter, neighbour: halfEdges() });
    this.gutterUV = quads.uv;
    this.gutterSource = quads.source;
    this.gutterIndices = quads.indices;
    this.fieldData = new Float32Array(12 * nF); // RGBA per corner (atlas-corners.js FRAME_FLOATS): as drawn
    this.nextData = null; // a field to compare with the one drawn (a run that may draw only where it moved)
    this.drawnKey = null; // the options the Jacobian was last drawn with in full; null: none, or a draw cut short
    // For the draws where the field moved: the faces' normals, taken from the frames as they go to the GPU (they
    // are let go then), and their boxes, made at the first such draw (armadillo-sub2's 832k faces: 30-60 ms).
    this.normals = new Float32Array(3 * nF);
    const margin = Math.ceil(Math.SQRT2 * gutterReach(gutter)) + 1; // texels the gutter's quads reach
    this.boxes = () => (this.faceBoxes ??= faceBoxes(cornerUVs, resolution, margin));
    this.faceArea = faceArea;
    this.usedFaces = used;
    this.coverage = areaUV;
    // Surface length per atlas texel at the atlas's mean density.
    this.texelLength = Math.sqrt(area3 / areaUV) / resolution;
    this.#vertexArray(locatorProgram.program);
    this.located = false;
    this.levels = [];
    const t0 = performance.now();
    this.seamMaps = seams ?? seamIndirection({ positions, triangles, neighbour: halfEdges() }, cornerUVs, resolution);
    this.seams = {
      edges: this.seamMaps.seamEdges,
      redirectedTexels: this.seamMaps.redirected,
      ms: (this.seamMaps.ms ?? 0) + performance.now() - t0,
    };
  }

  // The per-corner textures' size: CORNER_ROW texels wide (or the context's limit), as many rows as the corners
  // need.
  #cornerTextureSize(gl) {
    const max = gl.getParameter(gl.MAX_TEXTURE_SIZE);
    this.cornerRow = Math.min(max - (max % 3), CORNER_ROW);
    this.cornerRows = Math.max(1, Math.ceil(this.vertexCount / this.cornerRow));
    if (this.cornerRows > max)
      throw new GLError(
        `the texture's atlas raster holds at most ${Math.floor((max * this.cornerRow) / 3)} faces on this GPU ` +
          `(the model has ${this.vertexCount / 3})`,
      );
  }

  // The GPU textures, one per step (a seam map's upload a band of rows per step), for a caller to yield between
  // them: what goes up with them can wait for the GPU process. The map of faces, the
  // per-corner textures (frames and field), then per level (finest first, down to 2x2): the Jacobian, the state
  // as four parity-class quarters plus a spare (sub-passes write a quarter into the spare, which then takes its
  // place), the unpacked result, and the seam indirection (an all-zero map where the atlas has no seams). Not
  // checked for completeness: the context has float render targets (createContext), and a check waits for the
  // GPU process.
  *allocate() {
    const { gl, resolution } = this;
    const target = (size) => new FloatTarget(gl, size, size, null, { check: false });
    this.locator = target(resolution);
    yield;
    this.frameTexture = this.#cornerTexture();
    this.fieldTexture = this.#cornerTexture();
    yield;
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
      L.indirection = new FloatTarget(gl, r, r, null, { target: false });
      yield* this.#uploadRows(L.indirection, map);
    }
    this.seamMaps = null;
  }

  // A level's map into its texture a band of rows per step: a 1024² map (16 MB) in one call held the page
  // 20-40 ms with nothing else to do and over 100 ms behind a big model's frames (the copy through the GPU
  // process's transfer buffer), where a 1 MB band takes about 1 ms.
  *#uploadRows(target, data) {
    const gl = this.gl, size = target.width;
    const rows = Math.max(1, Math.floor(BAND_TEXELS / size));
    for (let y = 0; y < size; y += rows) {
      const h = Math.min(rows, size - y);
      gl.bindTexture(gl.TEXTURE_2D, target.texture);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, y, size, h, gl.RGBA, gl.FLOAT, data, 4 * size * y);
      gl.bindTexture(gl.TEXTURE_2D, null);
      yield;
    }
  }

  // An RGBA32F texture of a float triple per corner (corner c at texel c, row by row; w unused), read with
  // texelFetch.
  #cornerTexture() {
    const gl = this.gl;
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, this.cornerRow, this.cornerRows);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.bindTexture(gl.TEXTURE_2D, null);
    return texture;
  }

  // Corners first .. end - 1 of `data` (4 floats per corner, corner 0 first) into a per-corner texture: at most
  // three uploads (a partial row, whole rows, a partial row).
  #uploadCorners(texture, data, first, end) {
    const gl = this.gl, W = this.cornerRow;
    gl.bindTexture(gl.TEXTURE_2D, texture);
    for (let c = first; c < end; ) {
      const x = c % W, y = (c - x) / W;
      const rows = x === 0 ? Math.floor((end - c) / W) : 0;
      const [w, h] = rows > 0 ? [W, rows] : [Math.min(W - x, end - c), 1];
      gl.texSubImage2D(gl.TEXTURE_2D, 0, x, y, w, h, gl.RGBA, gl.FLOAT, data, 4 * c);
      c += w * h;
    }
    gl.bindTexture(gl.TEXTURE_2D, null);
  }

  // The map of faces' vertices: each face's corners (UV, and the corner's own index), then the gutter's quads'
  // (UV, and the corner whose field each takes), indexed past the corners (WebGL 2 has no base vertex).
  #vertexArray(program) {
    const gl = this.gl;
    const vertices = this.vertexCount + this.gutterSource.length;
    this.uvBuffer = gl.createBuffer();
    this.cornerBuffer = gl.createBuffer();
    this.indexBuffer = gl.createBuffer();
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    // Allocated here, filled by the first synthesis a slice per task (#uploadFixed).
    gl.bindBuffer(gl.ARRAY_BUFFER, this.uvBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, 8 * vertices, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, 4 * vertices, gl.STATIC_DRAW);
    locatorAttributes(gl, program, this.uvBuffer, this.cornerBuffer);
    const indices = this.gutterIndices.map((i) => i + this.vertexCount);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    this.facesUploaded = 0;
  }

  // The Jacobian of every level for the field: the per-vertex `vertexVectors` (3 per vertex); for a vector field,
  // {whitney: {positions, rows, oneForm}}, its Whitney reconstruction at each face's corners
  // (geometry/whitney-corners.js), made a slice at a time; or, for a combed line or cross field, {cornerVectors}
  // (9 per face, corner k of face f at 9f + 3k: geometry/chart-comb.js);
  // the first time, the fixed data goes up and the map of faces is drawn; then the field per corner, and a
  // full-screen pass at the finest level, averaged down; after a field drawn so, only round the faces whose field
  // moved (raster-delta.js; `lastDraw` says how many). programs: the synthesizer's; vao: its full-screen one.
  // A generator: the data go up a slice of faces at a time, and it yields after each slice so that the caller can
  // give the page its frames (a synthesis run step by step, synthesizer.js), the name of the phase it ends, if
  // not the field's; the draws are issued when it returns. Returns the reference magnitude (area-weighted mean
  // |field|).
  *rasterSteps(programs, vao, field, o) {
    const nF = this.triangles.length / 3;
    const sums = { mag: 0, area: 0 };
    if (!this.located) {
      yield* this.#uploadFixed(Math.max(1, o.sliceFaces >> 1)); // 21 numbers a face against the field's 12
      this.#drawLocator(programs.locator);
      yield FIXED_PHASE;
    }
    const corners = field?.cornerVectors ?? null;
    if (corners && corners.length !== 9 * nF)
      throw new GLError(`cornerVectors must hold 9 numbers per face (${9 * nF}), got ${corners.length}`);
    // Drawn only where the field moved when the last draw was under the same options (the angle kept too: a face
    // left as drawn is within it) and was not cut short, and the magnitude does not scale the features (the
    // reference magnitude, over the whole mesh, moves with any edit).
    const key = `${o.featureScale} ${o.magnitudeExponent} ${o.localDegrees}`;
    const sinTol = Math.sin((RASTER_SHARE * (o.localDegrees ?? 0) * Math.PI) / 180);
    const delta = this.drawnKey === key && sinTol > 0 && o.magnitudeExponent === 0;
    if (!delta) this.drawnKey = null; // until this draw is issued
    const out = delta ? (this.nextData ??= new Float32Array(12 * nF)) : this.fieldData;
    const moved = delta ? new Int32Array(nF) : null;
    let count = 0;
    // A slice of o.sliceFaces faces per task: at 832k faces the whole field in one upload (with the fixed data
    // beside it, 140 MB) held the page for 5-7 s while the GPU process caught up; 32k faces are ~1 MB.
    for (let f0 = 0; f0 < nF; f0 += o.sliceFaces) {
      const f1 = Math.min(nF, f0 + o.sliceFaces);
      fillCornerField(field, this.triangles, this.faceArea, f0, f1, sums, out);
      if (delta) count = this.#findMoved(f0, f1, sinTol, moved, count);
      else this.#uploadCorners(this.fieldTexture, this.fieldData, 3 * f0, 3 * f1);
      yield; // the last slice too: its upload is waited for apart from the raster's draws
    }
    // The moved faces' field to the GPU: at once with the draw where they are few (a run cut short before then
    // leaves the field drawn as it was, for the next to compare with), else a slice of faces per task.
    for (let i = 0; delta && i < count; i += o.sliceFaces) {
      this.drawnKey = null;
      this.#takeMoved(moved, i, Math.min(count, i + o.sliceFaces));
      if (count > o.sliceFaces) yield;
    }
    const rects = delta ? blockRects(this.boxes(), moved, count, this.resolution) : null;
    this.lastDraw = { faces: delta ? count : nF, whole: !delta, rects: rects?.length ?? null };
    const magRef = sums.mag > 0 ? sums.mag / sums.area : 1;
    if (!rects || rects.length) {
      this.#drawJacobian(programs, vao, o, magRef, rects);
      noteJacobianDrawn(this.levels, rects);
    }
    this.drawnKey = key;
    return magRef;
  }

  // Faces f0 .. f1 - 1 of nextData whose field moved from fieldData's (raster-delta.js faceMoved) onto `moved`
  // from `count`; returns the new count.
  #findMoved(f0, f1, sinTol, moved, count) {
    const next = this.nextData, drawn = this.fieldData, normals = this.normals;
    for (let f = f0; f < f1; f++) if (faceMoved(next, drawn, normals, f, sinTol)) moved[count++] = f;
    return count;
  }

  // The faces moved[from .. to - 1] (ascending) from nextData into fieldData and the field's texture, in runs of
  // faces a few apart (those between go as drawn): a few small uploads where one of the whole slice took software
  // GL 10-20 ms.
  #takeMoved(moved, from, to) {
    for (const f of moved.subarray(from, to)) this.fieldData.set(this.nextData.subarray(12 * f, 12 * f + 12), 12 * f);
    for (let i = from; i < to; ) {
      let j = i + 1;
      while (j < to && moved[j] - moved[j - 1] <= UPLOAD_GAP) j++;
      this.#uploadCorners(this.fieldTexture, this.fieldData, 3 * moved[i], 3 * moved[j - 1] + 3);
      i = j;
    }
  }

  // The Jacobian's pass at the finest level within rects (null: everywhere), averaged down level by level.
  #drawJacobian(programs, vao, o, magRef, rects) {
    const gl = this.gl;
    const rho = o.featureScale * this.texelLength;
    this.levels[0].jac.bindAsTarget();
    programs.jacobian
      .use()
      .texture('uLocator', this.locator)
      .texture('uField', this.fieldTexture)
      .texture('uFrames', this.frameTexture)
      .float('uInvRho', 1 / rho)
      .float('uTexel', 1 / this.resolution)
      .float('uMagRef', magRef)
      .float('uMagExponent', o.magnitudeExponent);
    drawWithin(gl, vao, rects);
    for (let k = 1; k < this.levels.length; k++) {
      this.levels[k].jac.bindAsTarget();
      programs.jacobianDown.use().texture('uJac', this.levels[k - 1].jac);
      drawWithin(gl, vao, rects && coarserRects(rects, k));
    }
  }

  // The fixed data to the GPU, `slice` faces per task: UVs, corner indices and frames; then the gutter's quads.
  // The arrays are let go once all is there.
  *#uploadFixed(slice) {
    const gl = this.gl, nF = this.vertexCount / 3;
    while (this.facesUploaded < nF) {
      const f0 = this.facesUploaded, f1 = Math.min(nF, f0 + slice);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.uvBuffer);
      gl.bufferSubData(gl.ARRAY_BUFFER, 24 * f0, this.uv, 6 * f0, 6 * (f1 - f0));
      const ids = new Int32Array(3 * (f1 - f0));
      for (let i = 0; i < ids.length; i++) ids[i] = 3 * f0 + i;
      gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
      gl.bufferSubData(gl.ARRAY_BUFFER, 12 * f0, ids);
      gl.bindBuffer(gl.ARRAY_BUFFER, null);
      this.#uploadCorners(this.frameTexture, this.frames, 3 * f0, 3 * f1);
      faceNormals(this.frames, this.normals, f0, f1);
      this.facesUploaded = f1;
      if (f1 < nF) yield FIXED_PHASE;
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, this.uvBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 8 * this.vertexCount, this.gutterUV);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 4 * this.vertexCount, this.gutterSource);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    this.uv = this.frames = this.gutterUV = null;
  }

  // The map of faces, once per atlas: the gutter's quads first, then the triangles over them (a texel a triangle
  // covers is always its own). Its vertices are let go once drawn.
  #drawLocator(program) {
    const gl = this.gl;
    this.locator.bindAsTarget();
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    program.use().int('uWidth', this.cornerRow);
    gl.bindVertexArray(this.vao);
    const quads = this.gutterIndices.length;
    if (quads) gl.drawElements(gl.TRIANGLES, quads, gl.UNSIGNED_INT, 0);
    gl.drawArrays(gl.TRIANGLES, 0, this.vertexCount);
    gl.bindVertexArray(null);
    this.#deleteVertices();
    this.located = true;
  }

  #deleteVertices() {
    const gl = this.gl;
    for (const b of [this.uvBuffer, this.cornerBuffer, this.indexBuffer]) gl.deleteBuffer(b);
    gl.deleteVertexArray(this.vao);
    this.uvBuffer = this.cornerBuffer = this.indexBuffer = this.vao = null;
  }

  dispose() {
    const gl = this.gl;
    if (this.vao) this.#deleteVertices();
    for (const t of [this.frameTexture, this.fieldTexture]) if (t) gl.deleteTexture(t);
    this.locator?.dispose();
    for (const L of this.levels) {
      for (const t of [L.jac, L.result, L.spare, L.spare2, L.indirection, L.kept, L.moved, L.redo, L.blocks])
        t?.dispose();
      for (const t of L.quarters) t.dispose();
    }
    this.levels = [];
  }
}
