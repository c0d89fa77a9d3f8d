// Tool results → edits: each pointer gesture becomes one constraint spec (design format) with the options in
// the toolbar, added as one command; the Singularity and Feature tools' gestures go to the session's field
// topology (session/field-topology.js: addSingularity, moveSingularity, setFeatures), one undoable step each.
// Never in readonly mode (the tools stay on orbit/select then).
import { pointSpec, strokeSpec, vectorSpec } from '../session/specs.js';

export function toolActions(d) {
  const s = d.session;
  // The tool options, or null (with the reason in the banner) when a box holds an invalid number.
  const options = () => {
    try {
      return d.ui.toolOptions();
    } catch (err) {
      d.ui.showError(err.message);
      return null;
    }
  };
  // The model the gesture was made on, and the options; null when either is missing.
  const start = () => {
    const serial = s.models.boundSerial();
    if (serial === null) return null;
    const opts = options();
    return opts ? { serial, opts } : null;
  };
  return {
    flash: (text, ms) => d.ui.flash(text, ms),
    onStroke: (points) => {
      const go = start();
      if (!go) return void d.viewer.clearStroke();
      const { strength, weight } = go.opts;
      d.edit('stroke', s.addConstraint(strokeSpec(points, { strength, weight }), go.serial)).finally(() => {
        if (!d.tools.tools.stroke.drawing) d.viewer.clearStroke();
      });
    },
    onVector: (face, vector) => {
      const go = start();
      if (go) d.edit('vector', s.addConstraint(vectorSpec(face, vector, { weight: go.opts.weight }), go.serial));
    },
    onPlace: (kind, hit) => {
      const go = start();
      if (!go) return;
      const { strength, orientation } = go.opts;
      const spec =
        kind === 'vortex'
          ? pointSpec('vortex', hit.face, orientation === 'cw' ? -strength : strength)
          : pointSpec(kind, s.surface.nearestCorner(hit.face, hit.point), strength);
      d.edit(kind, s.addConstraint(spec, go.serial));
    },
    onSelect: (uid) => s.select(uid),
    singularity: singularityActions(d),
    feature: featureActions(d),
  };
}

// A tool's edit that the core may refuse (a boundary vertex, a vertex that has a singularity, an edge that is
// not a mesh edge): the reason in the status line as well as the banner, and the design as it was.
function toolEdit(d, name, run) {
  const serial = d.session.models.boundSerial();
  if (serial === null) return;
  const refused = (err) => {
    d.ui.flash(err.message, 6000);
    throw err;
  };
  let promise;
  try {
    promise = Promise.resolve(run(serial)).catch(refused);
  } catch (err) {
    promise = Promise.reject(err).catch(refused);
  }
  return d.edit(name, promise);
}

// The new singularity is selected, so Delete takes it back at once (and a drag moves it).
function singularityActions(d) {
  const s = d.session, t = s.topology;
  return {
    symmetry: () => s.field?.symmetry ?? 1,
    onSelect: (id) => s.select(id),
    onAdd: (vertex) =>
      toolEdit(d, 'singularity', async (serial) => {
        s.select(await t.addSingularity(vertex, d.ui.singularityIndex(), serial));
      }),
    onMove: (id, vertex) => toolEdit(d, 'moveSingularity', () => t.moveSingularity(id, vertex)),
    // +1/N at the press, -1/N at the release: the total index unchanged.
    onPair: (plus, minus) => {
      const N = s.field?.symmetry ?? 1;
      return toolEdit(d, 'singularityPair', (serial) => addPair(t, [plus, 1 / N], [minus, -1 / N], serial));
    },
  };
}

// A +/- pair: one undoable step where the session has a compound edit for it, else two.
async function addPair(t, [v0, k0], [v1, k1], serial) {
  if (typeof t.addSingularityPair === 'function') return t.addSingularityPair([v0, k0], [v1, k1], serial);
  await t.addSingularity(v0, k0, serial);
  return t.addSingularity(v1, k1, serial);
}

// A Feature gesture's edges ([a, b], lower vertex first) added to or taken from the features in use: one
// SetFeatures step with the angle kept, or a passing note when the gesture changes nothing.
function featureActions(d) {
  const key = ([a, b]) => (a < b ? `${a},${b}` : `${b},${a}`);
  return {
    removing: () => d.ui.featureRemoving(),
    onFeatures: (edges, remove) => {
      const now = d.session.topology.features();
      const inUse = new Set(now.edges.map(key)), added = new Set(now.add.map(key));
      const removed = new Set(now.remove.map(key)), touched = new Set(edges.map(key));
      let add = now.add, rem = now.remove;
      if (remove) {
        add = now.add.filter((e) => !touched.has(key(e)));
        rem = [...now.remove, ...edges.filter((e) => inUse.has(key(e)) && !added.has(key(e)) && !removed.has(key(e)))];
      } else {
        rem = now.remove.filter((e) => !touched.has(key(e)));
        add = [...now.add, ...edges.filter((e) => !inUse.has(key(e)) && !removed.has(key(e)) && !added.has(key(e)))];
      }
      if (add.length === now.add.length && rem.length === now.remove.length) {
        const what = edges.length === 1 ? 'That edge is' : 'Those edges are';
        return void d.ui.flash(`${what} ${remove ? 'not a feature' : 'a feature'} already.`, 3000);
      }
      return toolEdit(d, 'features', () => d.session.topology.setFeatures({ add, remove: rem }));
    },
  };
}
