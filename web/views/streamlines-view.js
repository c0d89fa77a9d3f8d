// Streamlines drawn as line segments over the surface, with chevrons pointing downstream. The lines come
// traced (geometry/streamlines.js, in the worker); this view only draws them. The lines of an N-field
// (N ≥ 2) have no downstream: they are drawn plain.
import { BufferAttribute, BufferGeometry, LineBasicMaterial, LineSegments } from 'three';
import { symmetryOf } from '../geometry/nfield.js';

// Streamlines run along the field (the tracer orders each line's points that way), so each carries chevrons
// pointing downstream: a "V" lying on the surface every CUE_EVERY points.
const CUE_EVERY = 6; // points between chevrons (the tracer takes about 4 per streamline spacing)
const CUE_SIZE = 1.6; // chevron length, × the line's step

export class StreamlinesView {
  constructor(scene) {
    this.scene = scene;
    this.lines = null;
    this.polylines = [];
    this.cues = []; // {tip, back} per chevron, model units
    this.normalAt = null; // (x, y, z) → unit surface normal near that point, set by the viewer
  }

  setSurface() {
    this.setLines([]);
  }

  // polylines: Float32Array per line (x, y, z per point); symmetry: the field's N (chevrons only for 1).
  setLines(polylines, symmetry = 1) {
    this.polylines = polylines;
    const oriented = symmetryOf(symmetry) === 1;
    this.cues = this.normalAt && oriented ? polylines.flatMap((l) => chevrons(l, this.normalAt)) : [];
    let segments = 2 * this.cues.length;
    for (const l of polylines) segments += Math.max(0, l.length / 3 - 1);
    const pos = new Float32Array(6 * segments);
    let o = 0;
    for (const l of polylines) {
      for (let k = 0; k + 3 < l.length; k += 3) {
        pos.set(l.subarray(k, k + 6), o);
        o += 6;
      }
    }
    for (const { tip, wings } of this.cues) {
      for (const w of wings) {
        pos.set(w, o);
        pos.set(tip, o + 3);
        o += 6;
      }
    }
    if (!this.lines) {
      this.lines = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: 0x111827 }));
      this.lines.frustumCulled = false;
      this.lines.renderOrder = 1;
      this.scene.add(this.lines);
    }
    this.lines.geometry.dispose();
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(pos, 3));
    this.lines.geometry = g;
    this.lines.visible = segments > 0;
  }
}

function chevrons(line, normalAt) {
  const out = [];
  const n = line.length / 3;
  const at = (k) => [line[3 * k], line[3 * k + 1], line[3 * k + 2]];
  for (let k = CUE_EVERY / 2; k + 1 < n; k += CUE_EVERY) {
    const tip = at(k + 1), prev = at(k);
    const t = [tip[0] - prev[0], tip[1] - prev[1], tip[2] - prev[2]];
    const step = Math.hypot(...t);
    if (!(step > 0)) continue;
    const size = CUE_SIZE * step;
    const u = t.map((x) => x / step);
    const nrm = normalAt(tip[0], tip[1], tip[2]);
    // Across the line, in the surface: n × t.
    const side = [nrm[1] * u[2] - nrm[2] * u[1], nrm[2] * u[0] - nrm[0] * u[2], nrm[0] * u[1] - nrm[1] * u[0]];
    const back = tip.map((x, c) => x - size * u[c]);
    const wings = [1, -1].map((sgn) => back.map((x, c) => x + sgn * 0.55 * size * side[c]));
    out.push({ tip, back, wings });
  }
  return out;
}
