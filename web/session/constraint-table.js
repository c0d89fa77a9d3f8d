// The page's mirror of the design the core holds (docs/design-format.md), kept in step from the replies' design
// changes, and the page ids of its constraints. Page ids ("uids") are what the API, the panels and the
// history name; they survive a delete and its undo, whereas the core hands out a fresh id whenever it re-adds
// a constraint. Specs are kept exactly as the core sent them (the core validated and stored them). A prescribed
// singularity is a constraint here ({type: 'singularity', vertex, index}: listed, removed and undone as any
// other), although the document lists them apart, as "singularities": [{vertex, index}].

// The design's settings as a document without them means them (docs/design-format.md): symmetry 1 is a
// vector field, curvature alignment 0 is off, and with no singularity prescribed the field places its own.
const DEFAULT_SETTINGS = Object.freeze({
  boundary: 'free',
  gamma: 0,
  symmetry: 1,
  curvatureAlignment: 0,
  exactSingularities: false,
});
// A new design's feature angle on a creased surface (the core's suggestion, mesh/feature_edges.h: edges sharper
// than this many degrees are features where the surface folds sharply along a few edges and hardly elsewhere;
// none, 0, on a faceted curved surface). A document without "featureAngle" means 0, as the core reads it.
export const CREASED_FEATURE_ANGLE = 35;

// The feature angle a model is loaded with: the design's own where it differs from the current model's
// suggestion (the user's choice, carried to the next model), else 'auto' (the next model's own suggestion).
// suggested: the current model's info.folds.suggestedFeatureAngle (undefined before the first model).
export function featureAngleForNextModel(angle, suggested) {
  return suggested === undefined || angle === suggested ? 'auto' : angle;
}

const isSingularity = (spec) => spec?.type === 'singularity';

// The design's constraints and singularities as the document lists them, from the specs in the core's order
// (each singularity's keys in the core's order too, so that the design's text does not depend on the route).
function documentLists(specs) {
  const singularities = specs.filter(isSingularity).map(({ vertex, index }) => ({ index, vertex }));
  return { constraints: specs.filter((spec) => !isSingularity(spec)), singularities };
}

export class ConstraintTable {
  constructor() {
    this.design = { ...DEFAULT_SETTINGS, constraints: [] };
    this.specByCore = new Map(); // core id → spec
    this.coreOrder = []; // core ids in the core's order (that of design.constraints)
    this.uids = new Map(); // uid → core id
    this.nextUid = 1;
  }

  get size() {
    return this.uids.size;
  }

  has(uid) {
    return this.uids.has(Number(uid));
  }

  // A new model: constraint numbers restart.
  restart() {
    this.uids.clear();
    this.nextUid = 1;
    this.mapDocument(null);
  }

  // The worker sends the whole document after loads, settings, designs and failed edits, with every spec in
  // the ids' order (`specs`; without them the document's constraints are those specs); after a constraint edit
  // only the entries it touched and the id order.
  apply({ ids, document, changed, specs }) {
    if (document) {
      this.design = document;
      const all = specs ?? document.constraints;
      this.specByCore = new Map(ids.map((id, k) => [id, all[k]]));
    } else {
      for (const [id, spec] of changed) this.specByCore.set(id, spec);
      const missing = ids.find((id) => !this.specByCore.has(id));
      if (missing !== undefined)
        throw new Error(`internal error: the core has constraint ${missing}, which the page never saw`);
      this.specByCore = new Map(ids.map((id) => [id, this.specByCore.get(id)]));
      const { constraints, singularities } = documentLists(ids.map((id) => this.specByCore.get(id)));
      this.design = { ...this.design, constraints, singularities };
      if (!singularities.length) delete this.design.singularities; // as the core writes a design without any
    }
    this.coreOrder = ids;
    for (const [uid, coreId] of this.uids) if (!this.specByCore.has(coreId)) this.uids.delete(uid);
  }

  // Core constraints no page id points at (a loaded design, an autosave) get fresh ids in the core's order.
  adoptUnmapped() {
    const mapped = new Set(this.uids.values());
    for (const coreId of this.coreOrder) if (!mapped.has(coreId)) this.uids.set(this.nextUid++, coreId);
  }

  // After a document replaced the core's list: give its constraints the page ids `uids` (same order).
  mapDocument(uids) {
    this.uids.clear();
    const ids = this.coreOrder;
    if (uids && uids.length === ids.length) uids.forEach((uid, k) => this.uids.set(uid, ids[k]));
    // Page ids from elsewhere (a deserialized command's) are taken: new ones are numbered after them.
    for (const uid of this.uids.keys()) if (uid >= this.nextUid) this.nextUid = uid + 1;
    this.adoptUnmapped();
  }

  uidsInCoreOrder() {
    const byCore = new Map([...this.uids].map(([uid, coreId]) => [coreId, uid]));
    return this.coreOrder.map((id) => byCore.get(id));
  }

  coreIdOf(uid) {
    const coreId = this.uids.get(Number(uid));
    if (coreId === undefined) throw new Error(`no constraint with id ${uid}`);
    return coreId;
  }

  specOf(uid) {
    return this.specByCore.get(this.coreIdOf(uid));
  }

  // Every constraint with its page id, in page-id order (copies).
  list() {
    return structuredClone(this.views());
  }

  // The same without the copies, sharing the table's specs: for reads that keep and change nothing (the panels;
  // an edit replaces a spec, never changes it). Deep copies of 300 constraints took ~5 ms an edit over three calls.
  views() {
    const uids = [...this.uids.keys()].sort((a, b) => a - b);
    return uids.map((uid) => ({ id: uid, ...this.specOf(uid) }));
  }

  // [{uid, spec}] for the views (the specs themselves, not copies).
  entries() {
    return [...this.uids.keys()].map((uid) => ({ uid, spec: this.specOf(uid) }));
  }

  // {boundary, gamma, symmetry, curvatureAlignment, exactSingularities}, the defaults where the document leaves
  // one out.
  settings() {
    const d = this.design;
    return Object.fromEntries(Object.entries(DEFAULT_SETTINGS).map(([key, fallback]) => [key, d[key] ?? fallback]));
  }

  // The sharp features {angle (degrees; 0: none detected), add, remove ([[a, b], ...] vertex pairs)}.
  features() {
    const { featureAngle = 0, featureEdges = {} } = this.design;
    return { angle: featureAngle, add: featureEdges.add ?? [], remove: featureEdges.remove ?? [] };
  }

  // The features as the document writes them (a key only where not the default): what a cleared design keeps.
  featureKeys() {
    const { featureAngle, featureEdges } = this.design;
    return { ...(featureAngle ? { featureAngle } : {}), ...(featureEdges ? { featureEdges } : {}) };
  }

  // The design's content as text, to tell unsaved edits (undoing back to the saved state counts as none).
  key() {
    const { constraints, singularities = [] } = this.design;
    const prescribed = singularities.map(({ vertex, index }) => [vertex, index]);
    return JSON.stringify({ ...this.settings(), constraints, prescribed, features: this.features() });
  }
}

// Whether two views() lists show the same constraints: entry by entry the same values (a spec left as it was),
// or else the same JSON (a document sent again with its specs anew).
export function sameConstraints(a, b) {
  const same = (x, y) => {
    const keys = Object.keys(x);
    return keys.length === Object.keys(y).length && keys.every((key) => x[key] === y[key]);
  };
  return a.length === b.length && a.every((x, k) => same(x, b[k]) || JSON.stringify(x) === JSON.stringify(b[k]));
}
