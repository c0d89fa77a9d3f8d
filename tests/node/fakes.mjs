// Stand-ins for what the node unit tests (tests/node/*.test.mjs) have no browser or wasm build for: meshes
// made here, a core link that speaks the worker's protocol (web/core/worker/dispatch.js), an in-memory IndexedDB
// and localStorage. Each fake keeps only the behaviour the page relies on, written from the protocol and the
// IndexedDB spec rather than from the code under test.
import { icosphereOff } from '../icosphere.mjs';
import { Surface } from '../../web/geometry/surface.js';

// ------------------------------------------------------------------------------------------ meshes

// OFF text → {positions: Float64Array, triangles: Int32Array} (triangles only, as tests/icosphere.mjs writes).
// A mesh as OFF text (the inverse of parseOff).
export function offText({ positions, triangles }) {
  const lines = [`OFF\n${positions.length / 3} ${triangles.length / 3} 0`];
  for (let v = 0; v < positions.length; v += 3) lines.push(`${positions[v]} ${positions[v + 1]} ${positions[v + 2]}`);
  for (let f = 0; f < triangles.length; f += 3) lines.push(`3 ${triangles[f]} ${triangles[f + 1]} ${triangles[f + 2]}`);
  return lines.join('\n') + '\n';
}

export function parseOff(text) {
  const words = text
    .split('\n')
    .map((l) => l.replace(/#.*/, '').trim())
    .filter(Boolean)
    .join(' ')
    .split(/\s+/);
  if (words.shift() !== 'OFF') throw new Error('not an OFF file');
  const [nV, nF] = [Number(words[0]), Number(words[1])];
  let k = 3;
  const positions = new Float64Array(3 * nV);
  for (let i = 0; i < 3 * nV; i++) positions[i] = Number(words[k++]);
  const triangles = new Int32Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    if (Number(words[k++]) !== 3) throw new Error('only triangles');
    for (let c = 0; c < 3; c++) triangles[3 * f + c] = Number(words[k++]);
  }
  return { positions, triangles };
}

// Unique edges, lower vertex first, sorted (a canonical order, as the core's).
export function edgesOf(triangles) {
  const seen = new Set();
  const list = [];
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const [i, j] = a < b ? [a, b] : [b, a];
      const key = `${i},${j}`;
      if (!seen.has(key)) seen.add(key), list.push([i, j]);
    }
  list.sort((p, q) => p[0] - q[0] || p[1] - q[1]);
  return Int32Array.from(list.flat());
}

export function icosphere(levels) {
  const mesh = parseOff(icosphereOff(levels));
  return { ...mesh, edges: edgesOf(mesh.triangles) };
}

// A flat n × n grid of squares over [x0, x0 + size]² in the z = 0 plane, each square cut into two
// counter-clockwise triangles (normals +z).
export function grid(n, size = 1, x0 = 0, y0 = x0) {
  const positions = new Float64Array(3 * (n + 1) * (n + 1));
  for (let j = 0; j <= n; j++)
    for (let i = 0; i <= n; i++) positions.set([x0 + (size * i) / n, y0 + (size * j) / n, 0], 3 * (j * (n + 1) + i));
  const tris = [];
  const v = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      // Alternate the diagonal so that no direction is favoured.
      if ((i + j) % 2) tris.push(v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1));
      else tris.push(v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
    }
  const triangles = Int32Array.from(tris);
  return { positions, triangles, edges: edgesOf(triangles) };
}

// ------------------------------------------------------------------------------------------ core link

// What each constraint type carries beyond its place (docs/design-format.md, "Constraints").
const KINDS = {
  stroke: { weight: true, strength: true },
  vector: { weight: true, strength: false },
  edge: { weight: true, strength: false },
  source: { weight: false, strength: true },
  sink: { weight: false, strength: true },
  vortex: { weight: false, strength: true },
  singularity: { weight: false, strength: false },
};
const TOP_LEVEL = new Set(['schema', 'mesh', 'boundary', 'gamma', 'symmetry', 'curvatureAlignment', 'constraints',
  'singularities', 'featureAngle', 'featureEdges', 'exactSingularities']);
const MUTATING = new Set(['loadMesh', 'add', 'remove', 'setWeight', 'setStrength', 'setBoundary', 'setGamma', 'setSymmetry', 'setCurvatureAlignment', 'applyDesign',
  'addSingularity', 'moveSingularity', 'setFeatures', 'addSingularities', 'removeConstraints', 'setExactSingularities']);
// Ops whose failure the worker takes back by applying the whole previous design again (core/setting-ops.js).
const RESTORES_DESIGN = new Set(['applyDesign', 'setSymmetry']);
// Constraints that are vector-field notions: the core refuses them for a symmetry N ≥ 2.
const VECTOR_NOTIONS = { source: 'sources', sink: 'sinks', vortex: 'vortices', edge: 'edge values' };
const NO_MESH_NEEDED = new Set(['loadMesh', 'warmUp']);

const checkWeight = (w) => {
  if (typeof w !== 'number' || !(w >= 1e-8 && w <= 1e8)) throw new Error(`weight ${w} is out of range (1e-8 … 1e8)`);
};
const checkStrength = (s) => {
  if (typeof s !== 'number' || !(Math.abs(s) <= 1e12)) throw new Error(`strength ${s} is out of range (|x| ≤ 1e12)`);
};
const checkSymmetry = (n) => {
  if (!Number.isInteger(n) || n < 1 || n > 6) throw new Error(`symmetry ${n} is out of range (a whole number 1 … 6)`);
};
const checkAlignment = (s, n) => {
  if (typeof s !== 'number' || !(s >= 0 && s <= 1e6)) throw new Error(`curvature alignment ${s} is out of range (0 … 1e6)`);
  if (s > 0 && n % 2) throw new Error(`curvature alignment needs an even symmetry (principal directions have no sign); this field has symmetry ${n}`);
};

// The core link a Session talks to (session.proxy): call(op, args) → {ok, value, snapshot?}, as the worker
// replies, with a failed mutating op rejecting with err.reply.snapshot (the whole document, as the core then
// holds it). Core ids are handed out fresh on every add, as the core does, and start far from the page ids.
// Messages go through structuredClone, as postMessage copies them.
export class FakeCore {
  // suggestedFeatureAngle: what the core would suggest for every mesh loaded (mesh/feature_edges.h: 35 on a
  // creased surface, 0 on a faceted curved one), taken for a load's featureAngle 'auto'.
  constructor({ firstId = 100, suggestedFeatureAngle = 35 } = {}) {
    this.suggestedFeatureAngle = suggestedFeatureAngle;
    this.mesh = null;
    this.ids = [];
    this.specs = new Map();
    this.nextId = firstId;
    this.boundary = 'free';
    this.gamma = 0;
    this.symmetry = 1;
    this.curvatureAlignment = 0;
    this.features = { angle: 0, add: [], remove: [] };
    this.exactSingularities = false;
    this.version = 0;
    this.log = []; // [op, args] of every call
    this.nonFinite = false; // the next snapshots carry a NaN in the field
    this.terminated = false;
    this.inFlight = 0;
    this.maxInFlight = 0;
  }

  // The design document as core.designJson() writes it: prescribed singularities listed apart, the features
  // only where not the default.
  document() {
    const all = this.ids.map((id) => structuredClone(this.specs.get(id)));
    const singular = all.filter((spec) => spec?.type === 'singularity');
    const { angle, add, remove } = this.features;
    return {
      schema: 'tvf-design/1',
      mesh: this.fingerprint(),
      boundary: structuredClone(this.boundary),
      gamma: this.gamma,
      symmetry: this.symmetry,
      curvatureAlignment: this.curvatureAlignment,
      constraints: all.filter((spec) => spec?.type !== 'singularity'),
      ...(singular.length ? { singularities: singular.map(({ vertex, index }) => ({ index, vertex })) } : {}),
      ...(angle ? { featureAngle: angle } : {}),
      ...(add.length || remove.length ? { featureEdges: structuredClone({ add, remove }) } : {}),
      ...(this.exactSingularities ? { exactSingularities: true } : {}),
    };
  }

  // A prescribed singularity's checks, as the core's: a vertex of the mesh that has none (but `self`), an index
  // that is a nonzero multiple of 1/n.
  #checkSingularity(vertex, index, n, self = null) {
    const nV = this.mesh.positions.length / 3;
    if (!Number.isInteger(vertex) || vertex < 0 || vertex >= nV) throw new Error(`singularity: vertex ${vertex} does not exist on the mesh`);
    if (typeof index !== 'number' || index === 0 || Math.abs(index * n - Math.round(index * n)) > 1e-9)
      throw new Error(`singularity: index ${index} is not a nonzero multiple of 1/${n}`);
    for (const [id, spec] of this.specs)
      if (id !== self && spec.type === 'singularity' && spec.vertex === vertex) throw new Error(`singularity: vertex ${vertex} already has one`);
  }

  // Features {angle, add, remove} checked as the core checks them: an angle in [0, 180], pairs that are edges.
  #checkFeatures({ angle, add, remove }) {
    if (typeof angle !== 'number' || !(angle >= 0 && angle <= 180)) throw new Error(`features: angle ${angle} is out of range (0 … 180)`);
    const edges = new Set();
    const E = this.mesh.edges;
    for (let k = 0; k < E.length; k += 2) edges.add(`${Math.min(E[k], E[k + 1])},${Math.max(E[k], E[k + 1])}`);
    for (const [a, b] of [...add, ...remove])
      if (!edges.has(`${Math.min(a, b)},${Math.max(a, b)}`)) throw new Error(`features: ${a}-${b} is not an edge of the mesh`);
  }

  fingerprint() {
    return { vertices: this.mesh.positions.length / 3, faces: this.mesh.triangles.length / 3, hash: `fake${this.mesh.triangles.length}` };
  }

  // The core's parse of one constraint for a field of symmetry n: checked against the mesh, defaults filled in.
  #parse(spec, n = this.symmetry) {
    if (!spec || typeof spec !== 'object' || Array.isArray(spec)) throw new Error('a constraint must be a JSON object');
    const kind = KINDS[spec.type];
    if (!kind) throw new Error(`unknown constraint type ${JSON.stringify(spec.type)}`);
    if (n >= 2 && VECTOR_NOTIONS[spec.type])
      throw new Error(`${spec.type}: ${VECTOR_NOTIONS[spec.type]} are vector-field notions; a field of symmetry ${n} has none`);
    const out = {};
    for (const [k, v] of Object.entries(spec)) if (v !== undefined) out[k] = structuredClone(v);
    const nF = this.mesh.triangles.length / 3, nV = this.mesh.positions.length / 3;
    const index = (what, x, n) => {
      if (!Number.isInteger(x) || x < 0 || x >= n) throw new Error(`${spec.type}: ${what} ${x} does not exist on the mesh`);
    };
    if (spec.type === 'stroke') {
      if (!Array.isArray(spec.points) || !spec.points.length) throw new Error('stroke: points must be a non-empty list');
      for (const p of spec.points) {
        index('face', p?.face, nF);
        if (!Array.isArray(p.bary) || p.bary.length !== 3 || Math.abs(p.bary[0] + p.bary[1] + p.bary[2] - 1) > 0.01)
          throw new Error('stroke: bary must be three numbers summing to 1');
      }
    }
    if (spec.type === 'vector' || spec.type === 'vortex') index('face', spec.face, nF);
    if (spec.type === 'source' || spec.type === 'sink') index('vertex', spec.vertex, nV);
    if (spec.type === 'singularity') this.#checkSingularity(spec.vertex, spec.index, n);
    if (spec.type === 'vector' && !(Array.isArray(spec.vector) && spec.vector.length === 3)) throw new Error('vector: vector must be [x, y, z]');
    if (spec.type === 'edge' && !(Array.isArray(spec.edge) && spec.edge.length === 2 && spec.edge[0] !== spec.edge[1]))
      throw new Error('edge: edge must be two different vertices');
    if (kind.weight) checkWeight((out.weight ??= 1));
    else if ('weight' in out) throw new Error(`${spec.type}: a ${spec.type} has no weight`);
    if (kind.strength) checkStrength((out.strength ??= 1));
    return out;
  }

  #checkBoundary(bc) {
    const ok = ['free', 'tangential', 'normal'].includes(bc) || (bc && typeof bc === 'object' && Number.isFinite(bc.angle));
    if (!ok) throw new Error(`boundary: ${JSON.stringify(bc)} is not a boundary condition`);
  }

  #checkGamma(g) {
    if (typeof g !== 'number' || !(g >= 0 && g <= 1e6)) throw new Error(`gamma ${g} is out of range (0 … 1e6)`);
  }

  #add(spec) {
    const id = this.nextId++;
    this.specs.set(id, this.#parse(spec));
    this.ids.push(id);
    return id;
  }

  // Replaces the whole design, all or nothing; every constraint gets a fresh id.
  #apply(design) {
    if (!design || typeof design !== 'object' || Array.isArray(design)) throw new Error('design: a design must be a JSON object');
    for (const key of Object.keys(design)) if (!TOP_LEVEL.has(key)) throw new Error(`design: unknown key "${key}"`);
    if (design.schema !== undefined && design.schema !== 'tvf-design/1') throw new Error(`design: unknown schema ${design.schema}`);
    if (design.mesh && JSON.stringify(design.mesh) !== JSON.stringify(this.fingerprint()))
      throw new Error('design: this design was made for another mesh');
    if (!Array.isArray(design.constraints)) throw new Error('design: no constraints list');
    const boundary = design.boundary ?? 'free', gamma = design.gamma ?? 0;
    const symmetry = design.symmetry ?? 1, alignment = design.curvatureAlignment ?? 0;
    this.#checkBoundary(boundary);
    this.#checkGamma(gamma);
    checkSymmetry(symmetry);
    checkAlignment(alignment, symmetry);
    const parsed = design.constraints.map((c) => this.#parse(c, symmetry));
    if (parsed.some((spec) => spec.type === 'singularity')) throw new Error('design: a singularity belongs in "singularities"');
    const singular = (design.singularities ?? []).map(({ vertex, index }) => ({ type: 'singularity', vertex, index }));
    const seen = new Set();
    for (const { vertex, index } of singular) {
      this.#checkSingularity(vertex, index, symmetry);
      if (seen.has(vertex)) throw new Error(`singularity: vertex ${vertex} already has one`);
      seen.add(vertex);
    }
    const features = { angle: design.featureAngle ?? 0, add: design.featureEdges?.add ?? [], remove: design.featureEdges?.remove ?? [] };
    this.#checkFeatures(features);
    const exact = design.exactSingularities ?? false;
    if (typeof exact !== 'boolean') throw new Error('design: "exactSingularities" must be true or false');
    this.features = structuredClone(features);
    this.exactSingularities = exact;
    parsed.push(...singular);
    this.ids = [];
    this.specs.clear();
    this.boundary = structuredClone(boundary);
    this.gamma = gamma;
    this.symmetry = symmetry;
    this.curvatureAlignment = alignment;
    for (const spec of parsed) this.#add(spec);
  }

  #constraint(id) {
    const spec = this.specs.get(id);
    if (!spec) throw new Error(`no constraint with id ${id}`);
    return spec;
  }

  #ops = {
    warmUp: () => true,
    loadMesh: (bytes, format, settings, design) => {
      if (format !== 'off') throw new Error(`load: the fake core reads OFF only (got ${format})`);
      const mesh = parseOff(new TextDecoder().decode(bytes));
      this.mesh = { ...mesh, edges: edgesOf(mesh.triangles) };
      this.ids = [];
      this.specs.clear();
      let settingsError = null, restoreError = null;
      this.symmetry = 1;
      this.curvatureAlignment = 0;
      try {
        const { boundary, gamma, symmetry = 1, curvatureAlignment = 0, featureAngle = 0 } = settings;
        const angle = featureAngle === 'auto' ? this.suggestedFeatureAngle : featureAngle;
        this.features = { angle, add: [], remove: [] };
        this.exactSingularities = settings.exactSingularities ?? false;
        this.#checkBoundary(boundary);
        this.#checkGamma(gamma);
        checkSymmetry(symmetry);
        checkAlignment(curvatureAlignment, symmetry);
        Object.assign(this, { boundary, gamma, symmetry, curvatureAlignment });
      } catch (err) {
        settingsError = err.message;
      }
      if (design) {
        try {
          this.#apply(design);
        } catch (err) {
          restoreError = err.message;
        }
      }
      const { positions, triangles, edges } = this.mesh;
      const info = { vertices: positions.length / 3, faces: triangles.length / 3, edges: edges.length / 2,
        folds: { suggestedFeatureAngle: this.suggestedFeatureAngle } };
      const cornerUVs = new Float32Array(0);
      // The worker sends the Surface it built (its arrays, Surface.arrays()); before that change it sent the
      // mesh arrays and the page built the Surface. Both forms, so the fake speaks either protocol.
      const surface = typeof Surface.prototype.arrays === 'function' ? new Surface(positions, triangles, edges).arrays() : undefined;
      return { info, settingsError, restoreError, embeddedDesign: false, surface, cornerUVs, mesh: { positions, triangles, edges, cornerUVs } };
    },
    add: (spec) => {
      const id = this.#add(spec);
      return { value: id, changed: [id] };
    },
    remove: (id) => {
      this.#remove(id);
      return { value: true, changed: [] };
    },
    setWeight: (id, w) => this.#setParameter('weight', id, w),
    setStrength: (id, s) => this.#setParameter('strength', id, s),
    setBoundary: (bc) => {
      this.#checkBoundary(bc);
      this.boundary = bc;
      return { value: true, changed: null };
    },
    setGamma: (g) => {
      this.#checkGamma(g);
      this.gamma = g;
      return { value: true, changed: null };
    },
    setCurvatureAlignment: (s) => {
      checkAlignment(s, this.symmetry);
      this.curvatureAlignment = s;
      return { value: true, changed: null };
    },
    // As the worker runs it (core/setting-ops.js): the listed constraints removed, the alignment set aside, the
    // new N (refused while a vector-field notion is left), the alignment it gets, the specs added under it.
    setSymmetry: (n, { remove = [], curvatureAlignment = 0, add = [] } = {}) => {
      for (const id of remove) this.#remove(id);
      this.curvatureAlignment = 0;
      checkSymmetry(n);
      const kept = this.ids.map((id) => this.specs.get(id)).find((spec) => VECTOR_NOTIONS[spec.type] && n >= 2);
      if (kept) throw new Error(`symmetry: the design has ${VECTOR_NOTIONS[kept.type]}, which a field of symmetry ${n} cannot have`);
      for (const spec of this.specs.values())
        if (spec.type === 'singularity') this.#checkSingularity(spec.vertex, spec.index, n, [...this.specs].find(([, x]) => x === spec)[0]);
      this.symmetry = n;
      checkAlignment(curvatureAlignment, n);
      this.curvatureAlignment = curvatureAlignment;
      return { value: add.map((spec) => this.#add(spec)), changed: null };
    },
    addSingularity: (vertex, index) => {
      this.#checkSingularity(vertex, index, this.symmetry);
      const id = this.#add({ type: 'singularity', vertex, index });
      return { value: id, changed: [id] };
    },
    // As the worker's: a refusal of any takes back those added before it.
    addSingularities: (list) => {
      const ids = [];
      try {
        for (const [vertex, index] of list) {
          this.#checkSingularity(vertex, index, this.symmetry);
          ids.push(this.#add({ type: 'singularity', vertex, index }));
        }
      } catch (err) {
        ids.forEach((id) => this.#remove(id));
        throw err;
      }
      return { value: ids, changed: ids };
    },
    removeConstraints: (ids) => {
      ids.forEach((id) => this.#remove(id));
      return { value: true, changed: [] };
    },
    moveSingularity: (id, vertex) => {
      const spec = this.#constraint(id);
      if (spec.type !== 'singularity') throw new Error(`move singularity: ${id} is not a singularity`);
      this.#checkSingularity(vertex, spec.index, this.symmetry, id);
      spec.vertex = vertex;
      return { value: true, changed: [id] };
    },
    setFeatures: (features = {}) => {
      const next = { ...this.features, ...structuredClone(features) };
      this.#checkFeatures(next);
      this.features = next;
      return { value: true, changed: null };
    },
    setExactSingularities: (exact) => {
      if (typeof exact !== 'boolean') throw new Error('exactSingularities must be true or false');
      this.exactSingularities = exact;
      return { value: true, changed: null };
    },
    applyDesign: (design) => {
      this.#apply(design);
      return { value: true, changed: null };
    },
    read: () => this.document(),
    // Directional's .sing as core-export.js reads it (the core's reader: io/sing_file.h): "N count", then
    // "vertex k" per singularity of index k / N.
    readSing: (text) => {
      const lines = text.split('\n').filter((l) => l.trim()).map((l) => l.trim().split(/\s+/).map(Number));
      const [[n, count], ...entries] = lines;
      if (!(n >= 1) || entries.length !== count) throw new Error('line 1: expected "N count"');
      return { symmetry: n, singularities: entries.map(([vertex, k]) => ({ vertex, index: k / n })) };
    },
  };

  #remove(id) {
    this.#constraint(id);
    this.specs.delete(id);
    this.ids = this.ids.filter((x) => x !== id);
  }

  #setParameter(kind, id, value) {
    const spec = this.#constraint(id);
    if (!(kind in spec)) throw new Error(`a ${spec.type} has no ${kind}`);
    (kind === 'weight' ? checkWeight : checkStrength)(value);
    spec[kind] = value;
    return { value: true, changed: [id] };
  }

  // As the worker's snapshot(): field arrays, stats, and the design as a change (changed ids) or the whole
  // document (changed null). The field's first face vector encodes (constraints, γ, version), so a test can
  // tell which state of the core a field belongs to.
  #snapshot(changed) {
    this.version++;
    const nF = this.mesh.triangles.length / 3, nV = this.mesh.positions.length / 3;
    const faceVectors = new Float64Array(3 * nF);
    faceVectors.set([this.ids.length, this.gamma, this.version]);
    if (this.nonFinite) faceVectors[3] = NaN;
    const design = changed
      ? { ids: [...this.ids], changed: changed.filter((id) => this.specs.has(id)).map((id) => [id, structuredClone(this.specs.get(id))]) }
      : { ids: [...this.ids], document: this.document(), specs: this.ids.map((id) => structuredClone(this.specs.get(id))) };
    // The prescribed singularities as the core reads them out (the fake's field has no others), and what they
    // leave to the field on this closed mesh (V - E + F); the feature edges in use are the added ones.
    const singular = this.ids.map((id) => this.specs.get(id)).filter((spec) => spec?.type === 'singularity');
    const chi = nV - this.mesh.edges.length / 2 + nF;
    const prescribedIndex = singular.reduce((sum, { index }) => sum + index, 0);
    const mode = !singular.length ? 'none' : Math.abs(chi - prescribedIndex) < 1e-9 ? 'exact' : 'free';
    const topology = { singularityMode: mode, eulerCharacteristic: chi, prescribedIndex, freeIndex: chi - prescribedIndex };
    return {
      version: this.version,
      symmetry: this.symmetry,
      faceVectors,
      vertexVectors: new Float64Array(3 * nV),
      oneForm: new Float64Array(this.mesh.edges.length / 2),
      stats: { constraints: this.ids.length, ...topology, featureEdges: this.features.add.length },
      design,
      singularities: singular.length ? singular.map(({ vertex, index }) => ({ vertex, index, prescribed: true })) : null,
      featureEdges: Int32Array.from(this.features.add.flat()),
    };
  }

  async call(op, args = []) {
    if (this.terminated) throw new Error('the designer was disposed');
    this.log.push([op, structuredClone(args)]);
    this.maxInFlight = Math.max(this.maxInFlight, ++this.inFlight);
    try {
      args = structuredClone(args);
      // Replies arrive later than the request, by a varying number of tasks.
      for (let k = this.log.length % 3; k >= 0; k--) await new Promise((resolve) => setTimeout(resolve, 0));
      if (!this.#ops[op]) throw new Error(`unknown operation ${op}`);
      if (!NO_MESH_NEEDED.has(op) && !this.mesh) throw new Error('no mesh loaded');
      const saved = this.mesh && {
        ids: [...this.ids],
        specs: structuredClone(this.specs),
        boundary: this.boundary,
        gamma: this.gamma,
        symmetry: this.symmetry,
        curvatureAlignment: this.curvatureAlignment,
        features: structuredClone(this.features),
      };
      let out;
      try {
        out = this.#ops[op](...args);
      } catch (err) {
        const reply = { ok: false, error: err.message, fatal: false };
        if (MUTATING.has(op) && this.mesh) {
          // The core takes back whatever the failed edit got to; the worker does that for a design by
          // applying the previous one again, whose constraints then have fresh ids.
          if (RESTORES_DESIGN.has(op)) {
            Object.assign(this, saved);
            this.#apply({ ...this.document(), mesh: undefined });
          }
          reply.snapshot = this.#snapshot(null);
        }
        const error = new Error(err.message);
        error.reply = structuredClone(reply);
        throw error;
      }
      if (op === 'loadMesh') return structuredClone({ ok: true, value: out, snapshot: this.#snapshot(null) });
      if (!MUTATING.has(op)) return structuredClone({ ok: true, value: out });
      return structuredClone({ ok: true, value: out.value, snapshot: this.#snapshot(out.changed) });
    } finally {
      this.inFlight--;
    }
  }

  recycle() {}

  cancel() {
    return false;
  }

  terminate() {
    this.terminated = true;
  }
}

// ------------------------------------------------------------------------------------------ web storage

export class FakeLocalStorage {
  constructor({ quota = Infinity } = {}) {
    this.map = new Map();
    this.quota = quota; // characters, as browsers count them
  }

  getItem(key) {
    return this.map.has(String(key)) ? this.map.get(String(key)) : null;
  }

  setItem(key, value) {
    const used = [...this.map].reduce((n, [k, v]) => n + (k === String(key) ? 0 : k.length + v.length), 0);
    if (used + String(key).length + String(value).length > this.quota) {
      const err = new Error('The quota has been exceeded.');
      err.name = 'QuotaExceededError';
      throw err;
    }
    this.map.set(String(key), String(value));
  }

  removeItem(key) {
    this.map.delete(String(key));
  }

  get length() {
    return this.map.size;
  }
}

// ------------------------------------------------------------------------------------------ IndexedDB

// An in-memory IndexedDB with what the autosave uses: open with an upgrade, object stores with an
// auto-incremented key path, an index, get / getAll / getAllKeys / add / delete, readonly and readwrite
// transactions.
// As in browsers: requests complete asynchronously and in order; a transaction commits on its own once a
// task ends with none of its requests pending, after which it accepts no more (TransactionInactiveError);
// values are stored and returned as structured clones; a failed request aborts its transaction and rolls it
// back.

function domError(name, message) {
  const err = new Error(message);
  err.name = name;
  return err;
}

class FakeRequest {
  constructor(source = null, transaction = null) {
    this.source = source;
    this.transaction = transaction;
    this.result = undefined;
    this.error = null;
    this.readyState = 'pending';
    this.onsuccess = null;
    this.onerror = null;
    this.onupgradeneeded = null;
    this.onblocked = null;
  }
}

class FakeTransaction {
  constructor(db, names, mode) {
    this.db = db;
    this.mode = mode;
    this.names = names;
    this.pending = 0;
    this.queued = []; // requests made before the transaction started
    this.finished = false;
    this.error = null;
    this.oncomplete = null;
    this.onabort = null;
    this.onerror = null;
    this.work = null;
    // As browsers schedule them: a transaction starts once every earlier one whose scope overlaps it has
    // finished, unless both only read.
    const all = db.data.transactions;
    this.blockers = all.filter((t) => !t.finished && (t.mode !== 'readonly' || mode !== 'readonly') && t.names.some((n) => names.includes(n)));
    all.push(this);
    if (mode === 'versionchange') this.#start();
    else setTimeout(() => this.#tryStart(), 0);
  }

  #tryStart() {
    if (this.work || this.finished || this.blockers.some((t) => !t.finished)) return;
    this.#start();
    for (const run of this.queued.splice(0)) setTimeout(run, 0);
    setTimeout(() => this.#maybeCommit(), 0);
  }

  // A readwrite transaction works on a copy of its stores, which replaces them when it commits.
  #start() {
    this.work = new Map(this.names.map((n) => [n, this.db.data.stores.get(n)[this.mode === 'readonly' ? 'self' : 'snapshot']()]));
  }

  objectStore(name) {
    if (!this.names.includes(name)) throw domError('NotFoundError', `the transaction does not include ${name}`);
    return new FakeObjectStore(this, name);
  }

  request(source, fn) {
    if (this.finished) throw domError('TransactionInactiveError', 'the transaction has finished');
    const req = new FakeRequest(source, this);
    this.pending++;
    const run = () => {
      this.pending--;
      if (this.finished) return;
      try {
        req.result = fn(this.work);
        req.readyState = 'done';
        req.onsuccess?.({ target: req });
      } catch (err) {
        req.error = err;
        req.readyState = 'done';
        req.onerror?.({ target: req });
        this.abort(err);
        return;
      }
      // Requests made by the success handler (and the promise callbacks it resolved) keep it open.
      setTimeout(() => this.#maybeCommit(), 0);
    };
    if (this.work) setTimeout(run, 0);
    else this.queued.push(run);
    return req;
  }

  #maybeCommit() {
    if (this.finished || this.pending || !this.work) return;
    if (this.mode === 'readwrite') for (const [name, store] of this.work) this.db.data.stores.set(name, store);
    this.#finish();
    this.oncomplete?.({ target: this });
  }

  #finish() {
    this.finished = true;
    const all = this.db.data.transactions;
    all.splice(all.indexOf(this), 1);
    for (const t of all) setTimeout(() => t.#tryStart(), 0);
  }

  abort(err = domError('AbortError', 'aborted')) {
    if (this.finished) return;
    this.#finish();
    this.error = err;
    this.onerror?.({ target: this });
    this.onabort?.({ target: this });
  }
}

class StoreData {
  constructor(keyPath, autoIncrement) {
    this.keyPath = keyPath;
    this.autoIncrement = autoIncrement;
    this.nextKey = 1;
    this.records = new Map();
    this.indexes = new Map(); // name → key path
  }

  self() {
    return this;
  }

  snapshot() {
    const copy = new StoreData(this.keyPath, this.autoIncrement);
    copy.nextKey = this.nextKey;
    copy.records = new Map(this.records);
    copy.indexes = new Map(this.indexes);
    return copy;
  }
}

const sortedByKey = (records) => [...records].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([, v]) => structuredClone(v));

class FakeObjectStore {
  constructor(tx, name) {
    this.transaction = tx;
    this.name = name;
  }

  #data(work) {
    return work.get(this.name);
  }

  #writable() {
    if (this.transaction.mode !== 'readwrite') throw domError('ReadOnlyError', 'the transaction is read-only');
  }

  add(value) {
    this.#writable();
    const stored = structuredClone(value);
    return this.transaction.request(this, (work) => {
      if (this.transaction.db.data.factory.failWrites) throw domError('QuotaExceededError', 'the quota has been exceeded');
      const data = this.#data(work);
      let key = stored[data.keyPath];
      if (key === undefined) {
        if (!data.autoIncrement) throw domError('DataError', 'no key');
        key = data.nextKey++;
        stored[data.keyPath] = key;
      } else if (typeof key === 'number' && key >= data.nextKey) data.nextKey = Math.floor(key) + 1;
      if (data.records.has(key)) throw domError('ConstraintError', `key ${key} exists`);
      data.records.set(key, stored);
      return key;
    });
  }

  get(key) {
    return this.transaction.request(this, (work) => {
      const record = this.#data(work).records.get(key);
      if (record !== undefined) this.transaction.db.data.factory.valuesRead++;
      return record === undefined ? undefined : structuredClone(record);
    });
  }

  getAll() {
    return this.transaction.request(this, (work) => {
      this.transaction.db.data.factory.valuesRead += this.#data(work).records.size;
      return sortedByKey(this.#data(work).records);
    });
  }

  delete(key) {
    this.#writable();
    return this.transaction.request(this, (work) => {
      this.#data(work).records.delete(key);
      return undefined;
    });
  }

  createIndex(name, keyPath) {
    if (!this.transaction.upgrade) throw domError('InvalidStateError', 'indexes are made in an upgrade only');
    this.#data(this.transaction.work).indexes.set(name, keyPath);
    return this.index(name);
  }

  index(name) {
    const schema = this.transaction.work?.get(this.name) ?? this.transaction.db.data.stores.get(this.name);
    const keyPath = schema.indexes.get(name);
    if (keyPath === undefined) throw domError('NotFoundError', `no index ${name}`);
    const store = this;
    return {
      // Records whose key path equals `key`, in primary-key order (one index key).
      getAll: (key) =>
        store.transaction.request(store, (work) => {
          const matching = [...store.#data(work).records].filter(([, r]) => key === undefined || r[keyPath] === key);
          store.transaction.db.data.factory.valuesRead += matching.length;
          return sortedByKey(matching);
        }),
      // Their primary keys, ascending: no value is read.
      getAllKeys: (key) =>
        store.transaction.request(store, (work) =>
          [...store.#data(work).records]
            .filter(([, r]) => key === undefined || r[keyPath] === key)
            .map(([k]) => k)
            .sort((a, b) => (a < b ? -1 : a > b ? 1 : 0)),
        ),
    };
  }
}

class FakeDatabase {
  constructor(data) {
    this.data = data;
    this.closed = false;
    this.onversionchange = null;
    this.upgradeTx = null;
  }

  get name() {
    return this.data.name;
  }

  get version() {
    return this.data.version;
  }

  get objectStoreNames() {
    return [...this.data.stores.keys()];
  }

  createObjectStore(name, { keyPath = null, autoIncrement = false } = {}) {
    if (!this.upgradeTx) throw domError('InvalidStateError', 'object stores are made in an upgrade only');
    if (this.data.stores.has(name)) throw domError('ConstraintError', `store ${name} exists`);
    const store = new StoreData(keyPath, autoIncrement);
    this.data.stores.set(name, store);
    this.upgradeTx.work.set(name, store);
    this.upgradeTx.names.push(name);
    return this.upgradeTx.objectStore(name);
  }

  transaction(names, mode = 'readonly') {
    if (this.closed) throw domError('InvalidStateError', 'the database connection is closed');
    const list = Array.isArray(names) ? names : [names];
    for (const n of list) if (!this.data.stores.has(n)) throw domError('NotFoundError', `no object store ${n}`);
    return new FakeTransaction(this, list, mode);
  }

  close() {
    this.closed = true;
  }
}

export class FakeIndexedDB {
  constructor() {
    this.databases = new Map(); // name → {name, version, stores: Map(name → StoreData)}
    this.opened = 0;
    this.failWrites = false; // every add fails, as on a full disk
    this.valuesRead = 0; // records read out (get, getAll), for tests of what a request reads
  }

  open(name, version = 1) {
    const req = new FakeRequest();
    setTimeout(() => {
      let data = this.databases.get(name);
      if (data && version < data.version) {
        req.error = domError('VersionError', 'the requested version is older');
        return req.onerror?.({ target: req });
      }
      const fresh = !data;
      if (fresh) this.databases.set(name, (data = { name, version: 0, stores: new Map(), transactions: [], factory: this }));
      const db = new FakeDatabase(data);
      this.opened++;
      req.result = db;
      if (version > data.version) {
        const oldVersion = data.version;
        data.version = version;
        const tx = new FakeTransaction(db, [], 'versionchange');
        tx.upgrade = true;
        db.upgradeTx = tx;
        req.transaction = tx;
        req.onupgradeneeded?.({ target: req, oldVersion, newVersion: version });
        db.upgradeTx = null;
        // The upgrade only makes stores and indexes here: it completes at once.
        data.transactions.splice(data.transactions.indexOf(tx), 1);
        tx.finished = true;
      }
      req.readyState = 'done';
      req.onsuccess?.({ target: req });
    }, 0);
    return req;
  }
}

// A Surface over a fake mesh ({positions, triangles, edges}, e.g. grid()).
export const surfaceOf = (m) => new Surface(m.positions, m.triangles, m.edges);

// Per-vertex and per-face fields of angle θ(x, y) in the z = 0 plane, each turned by its own random 2πk/N: an
// N-field whose representatives a consumer must match before it can use them.
export function scrambledField(s, N, theta, random) {
  const V = new Float64Array(3 * s.nV), F = new Float64Array(3 * s.nF);
  const put = (out, i, [x, y]) => {
    const a = theta(x, y) + (2 * Math.PI * Math.floor(random() * N)) / N;
    out.set([Math.cos(a), Math.sin(a), 0], 3 * i);
  };
  for (let v = 0; v < s.nV; v++) put(V, v, s.vertex(v));
  for (let f = 0; f < s.nF; f++) put(F, f, s.centroid(f));
  return { V, F };
}
