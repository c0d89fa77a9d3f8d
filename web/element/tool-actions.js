// Tool results → edits: each pointer gesture becomes one constraint spec (design format) with the options in
// the toolbar, added as one command. Never in readonly mode (the tools stay on orbit/select then).
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
  };
}
