// The correspondence between a big (fine) mesh and its coarse stand-in (coarse-mesh.js), built once per model
// in the preview worker: every fine vertex and face centre gets the closest point of the coarse surface (a
// coarse face and barycentric coordinates), found by coarse-search.js. Through it a design made on the fine mesh
// is posed on the coarse one (designOnCoarse, specOnCoarse: design-on-coarse.js) and the coarse field is carried
// back to every fine vertex (and face, for an N-field's representatives) (fieldOnFine: field-on-fine.js), so
// the page draws a preview on the mesh it shows.
//
// Owns the per-vertex and per-face maps and the fine normals; imports coarse-search.js, design-on-coarse.js,
// field-on-fine.js and geometry/mesh-geometry.js (the fine normals).
import { CoarseSearch } from './coarse-search.js';
import { designOnCoarse, pointOnCoarse, specOnCoarse } from './design-on-coarse.js';
import { fieldOnFine } from './field-on-fine.js';
import { faceNormals, vertexNormals } from '../../geometry/mesh-geometry.js';

export class SurfaceMap {
  // fine: {positions, triangles} (Float64Array, Int32Array); coarse: {positions, triangles, fineVertex}
  // (coarse-mesh.js); kept: the vertex parts of this map as kept() gave them for this very mesh (a model opened
  // again, worker/preview-cache.js), or null to search them.
  constructor(fine, coarse, kept = null) {
    this.fine = fine;
    this.coarse = coarse;
    this.nV = fine.positions.length / 3;
    this.nF = fine.triangles.length / 3;
    this.search = new CoarseSearch(fine, coarse, kept?.nearest);
    if (kept) {
      this.vertexFace = kept.vertexFace;
      this.vertexBary = kept.vertexBary;
    } else this.#searchVertices();
    // The face centres' closest points are found when asked for (faceOnCoarse): a vector field's preview needs
    // a few, for the constraints; all of them took 0.2 s of the first field at 832k faces.
    this.faceFace = new Int32Array(this.nF).fill(-1);
    this.faceBary = new Float64Array(3 * this.nF);
    this.allFaces = false;
    // The planes the carried field is laid into: the area-weighted vertex normals, and the fine faces' unit
    // normals when a line or cross field needs them (faceNormals()).
    this.vertexNormals = vertexNormals(fine.positions, fine.triangles);
    this.faceNormalsCache = null;
  }

  #searchVertices() {
    this.vertexFace = new Int32Array(this.nV);
    this.vertexBary = new Float64Array(3 * this.nV);
    const p = [0, 0, 0];
    for (let v = 0; v < this.nV; v++) {
      for (let k = 0; k < 3; k++) p[k] = this.fine.positions[3 * v + k];
      this.search.closest(p, this.search.aroundFineVertex(v), v, this.vertexFace, this.vertexBary);
    }
  }

  // What a model opened again takes instead of the vertices' search (the constructor's `kept`).
  kept() {
    return { vertexFace: this.vertexFace, vertexBary: this.vertexBary, nearest: this.search.nearest };
  }

  #fineCentre(f, out) {
    const { positions: P, triangles: T } = this.fine;
    for (let k = 0; k < 3; k++) out[k] = (P[3 * T[3 * f] + k] + P[3 * T[3 * f + 1] + k] + P[3 * T[3 * f + 2] + k]) / 3;
    return out;
  }

  // Most fine faces lie inside one coarse face, all three corners mapped there: the centre's coordinates are
  // then the mean of the corners' (the map is affine on the coarse face), no search needed.
  #insideOneFace(f) {
    const T = this.fine.triangles;
    const a = T[3 * f], b = T[3 * f + 1], c = T[3 * f + 2];
    const face = this.vertexFace[a];
    if (this.vertexFace[b] !== face || this.vertexFace[c] !== face) return false;
    this.faceFace[f] = face;
    const bary = this.vertexBary;
    for (let k = 0; k < 3; k++) this.faceBary[3 * f + k] = (bary[3 * a + k] + bary[3 * b + k] + bary[3 * c + k]) / 3;
    return true;
  }

  // A fine face across coarse faces: its centre's closest point is searched from its corners' coarse faces,
  // descending to their neighbours while it lies on a border (CoarseSearch.closest), rather than from every
  // face around the corners' nearest kept vertices (twice the tests, for the same point).
  #closestOfCorners(f, p) {
    this.search.closest(p, this.search.facesOfCorners(f, this.vertexFace), f, this.faceFace, this.faceBary);
  }

  // The coarse face under fine face f's centre (its coordinates in faceBary[3f..]), found the first time.
  faceOnCoarse(f) {
    if (this.faceFace[f] < 0 && !this.#insideOneFace(f)) this.#closestOfCorners(f, this.#fineCentre(f, [0, 0, 0]));
    return this.faceFace[f];
  }

  // Every fine face's, once: an N-field's representatives are carried to all of them.
  everyFaceOnCoarse() {
    if (!this.allFaces) for (let f = 0; f < this.nF; f++) this.faceOnCoarse(f);
    this.allFaces = true;
  }

  faceNormals() {
    return (this.faceNormalsCache ??= faceNormals(this.fine.positions, this.fine.triangles));
  }

  // ------------------------------------------------------------------------------------------ designs

  // A point of the fine surface ({face, bary}) on the coarse surface.
  pointOnCoarse(point) {
    return pointOnCoarse(this, point);
  }

  // A constraint of the design format on the fine mesh, posed on the coarse one.
  specOnCoarse(spec) {
    return specOnCoarse(this, spec);
  }

  // A whole design document on the coarse mesh.
  designOnCoarse(doc) {
    return designOnCoarse(this, doc);
  }

  // ------------------------------------------------------------------------------------------ fields

  // The coarse field on the fine mesh, into out: {vertexVectors, faceVectors} (arrays to refill; the face
  // vectors only when given).
  fieldOnFine(coarseFaceVectors, coarseVertexVectors, symmetry, out) {
    return fieldOnFine(this, coarseFaceVectors, coarseVertexVectors, symmetry, out);
  }
}
