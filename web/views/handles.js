// Constraint handles drawn on the surface — stroke ribbons, vector arrows, and markers for sources (red),
// sinks (green) and vortices (blue) — plus the live preview arrow of the vector tool. Handles are picked in
// screen space (nearest anchor within a few pixels that is not hidden behind the surface). Ribbons and their
// chevrons are a fixed width in pixels (screen-ribbon.js): they read on a fine mesh as on a coarse one.
import { DoubleSide, Group, Matrix4, Mesh, MeshBasicMaterial, Vector3 } from 'three';
import { worldPerPixel } from '../geometry/arrow-sampling.js';
import { arrowGeometry, fixSpriteScales, markerSprite } from './markers.js';
import { BandMaterial, bandGeometry, bandMesh, chevronGeometry } from './screen-ribbon.js';

const COLORS = { stroke: 0xff7a1a, vector: 0xfbbf24, selected: 0xffffff, preview: 0xfde68a, chevron: 0x431407 };
const MARKERS = {
  source: { fill: '#ef4444', text: '+' },
  sink: { fill: '#22c55e', text: '\u2212' },
  vortex: { fill: '#3b82f6', text: null }, // ↺ or ↻ by the sign of the strength
};
const LIFT = 0.12; // × mean edge length
const PICK_PX = 12;
export const RIBBON_PX = 6; // the ribbons' width on screen (CSS pixels)
const CHEVRON = { length: 1.5, width: 0.84 }; // × the ribbon's width
const CHEVRON_SPACING = 0.1; // × the model's radius (about 30 px in the framed view), at least one per stroke

export class HandlesView {
  constructor(scene, labels) {
    this.labels = labels;
    this.group = new Group();
    this.markers = new Group();
    scene.add(this.group, this.markers);
    this.items = new Map(); // uid → {spec, object, anchors: [[x,y,z], ...]}
    this.selected = null;
    this.preview = null;
    this.scene = scene;
  }

  setSurface(surface) {
    this.surface = surface;
    this.setConstraints([]);
    this.hidePreview();
  }

  // list: [{uid, spec}] with spec in the design format. A handle whose spec is the very object it was built
  // from is kept (the session's copy of the design replaces the entries an edit touched, and only those), so
  // an edit builds the handles of the constraints it changed, not all of them.
  setConstraints(list) {
    const kept = new Map();
    for (const { uid, spec } of list) {
      const old = this.items.get(uid);
      if (old && old.spec === spec) {
        kept.set(uid, old);
        this.items.delete(uid);
        continue;
      }
      const item = this.#build(spec);
      if (!item) continue;
      item.object.userData.uid = uid;
      kept.set(uid, item);
    }
    for (const item of this.items.values()) this.#disposeItem(item);
    this.items = kept;
    this.#paintSelection();
  }

  setSelected(uid) {
    this.selected = uid;
    this.#paintSelection();
  }

  #build(spec) {
    const s = this.surface;
    const lift = LIFT * s.meanEdge;
    const liftedOn = (face, p) => {
      const n = s.normal(face);
      return [p[0] + lift * n[0], p[1] + lift * n[1], p[2] + lift * n[2]];
    };
    switch (spec.type) {
      case 'stroke': {
        const pts = spec.points.map((q) => liftedOn(q.face, s.pointFromBary(q.face, q.bary)));
        const normals = spec.points.map((q) => s.normal(q.face));
        const mesh = ribbon(pts, normals, COLORS.stroke);
        // Chevrons along the ribbon, in the stroke's direction (the direction it asks of the field).
        const cues = chevronsAlong(pts, normals, CHEVRON_SPACING * s.radius);
        if (cues.length) {
          const marks = bandMesh(
            chevronGeometry(cues, CHEVRON),
            new BandMaterial({ color: COLORS.chevron, widthPx: RIBBON_PX, liftPx: 3 }),
          );
          marks.renderOrder = 3;
          mesh.add(marks);
        }
        this.group.add(mesh);
        return { spec, object: mesh, anchors: pts, cues };
      }
      case 'vector': {
        const n = s.normal(spec.face);
        const c = liftedOn(spec.face, s.centroid(spec.face));
        const v = projectOut(spec.vector, n);
        const l = Math.hypot(...v);
        const len = 3 * s.meanEdge;
        const mesh = new Mesh(
          arrowGeometry({ shaftW: 0.07, headW: 0.22, headL: 0.35, centred: false }),
          basic(COLORS.vector),
        );
        if (l > 0) {
          const x = new Vector3(...v).multiplyScalar(len / l);
          const z = new Vector3(...n);
          const y = new Vector3().crossVectors(z, x);
          mesh.applyMatrix4(new Matrix4().makeBasis(x, y, z).setPosition(...c));
        }
        mesh.renderOrder = 2;
        this.group.add(mesh);
        const tip = l > 0 ? c.map((x, k) => x + (v[k] * len) / l) : c;
        return { spec, object: mesh, anchors: [c, tip, c.map((x, k) => (x + tip[k]) / 2)] };
      }
      case 'edge': {
        const [i, j] = spec.edge;
        const pts = [s.vertex(i), s.vertex(j)];
        const nrm = [0, 1].map((k) => [...s.vertexNormals.subarray(3 * spec.edge[k], 3 * spec.edge[k] + 3)]);
        const lifted = pts.map((p, k) => p.map((x, c) => x + lift * nrm[k][c]));
        const mesh = ribbon(lifted, nrm, COLORS.stroke);
        this.group.add(mesh);
        return { spec, object: mesh, anchors: lifted };
      }
      case 'source':
      case 'sink':
      case 'vortex': {
        const onVertex = spec.type !== 'vortex';
        const p = onVertex ? s.vertex(spec.vertex) : s.centroid(spec.face);
        const n = onVertex ? [...s.vertexNormals.subarray(3 * spec.vertex, 3 * spec.vertex + 3)] : s.normal(spec.face);
        const at = p.map((x, k) => x + 4 * lift * n[k]);
        const sprite = markerSprite(markerTexture(this.labels, spec, false), 22);
        sprite.position.set(...at);
        this.markers.add(sprite);
        return { spec, object: sprite, anchors: [at], marker: true };
      }
      default:
        return null;
    }
  }

  #paintSelection() {
    for (const [uid, item] of this.items) {
      const on = uid === this.selected;
      if (item.marker) {
        item.object.material.map = markerTexture(this.labels, item.spec, on);
        item.object.material.needsUpdate = true;
        item.object.userData.px = on ? 28 : 22;
      } else {
        item.object.material.color.set(on ? COLORS.selected : COLORS[item.spec.type] ?? COLORS.stroke);
      }
    }
  }

  #disposeItem(item) {
    item.object.parent?.remove(item.object);
    for (const child of item.object.children) {
      child.geometry?.dispose();
      child.material?.dispose();
    }
    item.object.geometry?.dispose();
    item.object.material.dispose();
  }

  // Direction cues on the stroke ribbons as drawn in the current view: uid → [{tip, back}] (model units).
  cues() {
    const out = [];
    for (const [uid, item] of this.items) {
      if (!item.cues) continue;
      const cues = item.cues.map(({ centre, tangent }) => {
        const wpp = this.view
          ? worldPerPixel(this.view.camera, new Vector3(...centre), this.view.heightPx)
          : this.surface.meanEdge / RIBBON_PX;
        const half = (0.5 * CHEVRON.length * RIBBON_PX * wpp) / (Math.hypot(...tangent) || 1);
        return { tip: centre.map((x, c) => x + half * tangent[c]), back: centre.map((x, c) => x - half * tangent[c]) };
      });
      out.push({ uid, cues });
    }
    return out;
  }

  updateScale(camera, renderer) {
    fixSpriteScales(this.markers, camera, renderer);
    this.view = { camera, heightPx: renderer.domElement.clientHeight || renderer.domElement.height || 1 };
  }

  // The handle under a client pixel: nearest anchor within PICK_PX on screen that the surface does not hide.
  pickAt(viewer, clientX, clientY) {
    const candidates = [];
    for (const [uid, item] of this.items) {
      let best = Infinity, bestAnchor = null;
      for (const a of item.anchors) {
        const q = viewer.projectToScreen(a);
        const d = Math.hypot(q.x - clientX, q.y - clientY);
        if (d < best) {
          best = d;
          bestAnchor = a;
        }
      }
      if (best <= PICK_PX) candidates.push({ uid, d: best, anchor: bestAnchor, marker: !!item.marker });
    }
    candidates.sort((a, b) => a.d - b.d);
    for (const c of candidates.slice(0, 6)) {
      // Markers float above the surface: check the point beneath them instead.
      if (viewer.isVisible(c.anchor, c.marker ? 6 : 2)) return c.uid;
    }
    return null;
  }

  // Vector tool preview: an arrow from `from` to `to` in the plane with normal n.
  showPreview(from, to, n) {
    const s = this.surface;
    const v = projectOut([to[0] - from[0], to[1] - from[1], to[2] - from[2]], n);
    const l = Math.hypot(...v);
    if (!this.preview) {
      this.preview = new Mesh(
        arrowGeometry({ shaftW: 0.06, headW: 0.2, headL: 0.3, centred: false }),
        basic(COLORS.preview),
      );
      this.preview.renderOrder = 4;
      this.preview.matrixAutoUpdate = false;
      this.scene.add(this.preview);
    }
    this.preview.visible = l > 0;
    if (!(l > 0)) return;
    const lift = 2 * LIFT * s.meanEdge;
    const x = new Vector3(...v);
    const z = new Vector3(...n);
    const y = new Vector3().crossVectors(z, x).normalize().multiplyScalar(2.5 * s.meanEdge);
    this.preview.matrix
      .makeBasis(x, y, z)
      .setPosition(from[0] + lift * n[0], from[1] + lift * n[1], from[2] + lift * n[2]);
  }

  hidePreview() {
    if (this.preview) this.preview.visible = false;
  }
}

function basic(color) {
  return new MeshBasicMaterial({ color, side: DoubleSide });
}

function projectOut(v, n) {
  const d = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  return [v[0] - d * n[0], v[1] - d * n[1], v[2] - d * n[2]];
}

function markerTexture(labels, spec, selected) {
  const m = MARKERS[spec.type];
  const text = m.text ?? (spec.strength >= 0 ? '\u21ba' : '\u21bb');
  return labels.get(`${spec.type}:${text}:${selected}`, m.fill, text, { ring: selected, textColor: '#ffffff' });
}

// A ribbon along a polyline (lifted surface points, the surface normal at each), RIBBON_PX wide on screen.
function ribbon(points, normals, color) {
  const mesh = bandMesh(bandGeometry(points, normals), new BandMaterial({ color, widthPx: RIBBON_PX }));
  mesh.renderOrder = 2;
  return mesh;
}

// Where the chevrons go along a polyline: about every `spacing` of its length and at least one, each a
// centre on the polyline, the surface normal and the direction there.
function chevronsAlong(points, normals, spacing) {
  const n = points.length;
  const cum = [0];
  for (let k = 1; k < n; k++) cum.push(cum[k - 1] + Math.hypot(...points[k].map((x, c) => x - points[k - 1][c])));
  const L = cum[n - 1];
  if (!(L > 0)) return [];
  const count = Math.max(1, Math.floor(L / spacing));
  const out = [];
  let k = 1;
  for (let i = 0; i < count; i++) {
    const at = ((i + 0.5) * L) / count;
    while (k < n - 1 && cum[k] < at) k++;
    const a = points[k - 1], b = points[k], f = (at - cum[k - 1]) / (cum[k] - cum[k - 1] || 1);
    const tangent = b.map((x, c) => x - a[c]);
    out.push({ centre: a.map((x, c) => x + f * tangent[c]), normal: normals[k], tangent });
  }
  return out;
}
