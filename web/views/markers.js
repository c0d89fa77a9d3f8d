// Shapes shared by the field views and the constraint handles: the flat arrow, the N-spoke glyph of an
// N-field, and labelled discs drawn as sprites that keep a fixed size in pixels (handles) or as textures laid
// on the surface (singularities), and text tags beside them.
import { BufferAttribute, BufferGeometry, CanvasTexture, SRGBColorSpace, Sprite, SpriteMaterial } from 'three';
import { spokeAngles } from '../geometry/nfield.js';

// A flat arrow in the xy-plane, unit length along +x, centred on the origin so it sits on its anchor.
export function arrowGeometry({ shaftW = 0.05, headW = 0.2, headL = 0.38, centred = true } = {}) {
  const x0 = centred ? -0.5 : 0, x1 = centred ? 0.5 : 1, xh = x1 - headL;
  // prettier-ignore
  const p = new Float32Array([
    x0, -shaftW, 0,  xh, -shaftW, 0,  xh, shaftW, 0,
    x0, -shaftW, 0,  xh, shaftW, 0,   x0, shaftW, 0,
    xh, -headW, 0,   x1, 0, 0,        xh, headW, 0,
  ]);
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(p, 3));
  return g;
}

// An N-field's glyph in the xy-plane: N spokes of length `length` from the origin at 2πk/N from +x (N = 2, a
// headless segment through the origin; N = 4, a cross), as wide as the arrow's shaft. Triangles (x, y, 0).
export function spokeTriangles(N, { length = 0.5, halfWidth = 0.05 } = {}) {
  const out = [];
  for (const a of spokeAngles(N)) {
    const c = Math.cos(a), s = Math.sin(a), wx = -s * halfWidth, wy = c * halfWidth, ex = c * length, ey = s * length;
    // prettier-ignore
    out.push(
      -wx, -wy, 0,  ex - wx, ey - wy, 0,  ex + wx, ey + wy, 0,
      -wx, -wy, 0,  ex + wx, ey + wy, 0,  wx, wy, 0,
    );
  }
  return new Float32Array(out);
}

// The glyph drawn per sample of an N-field: the arrow for N = 1 (unchanged), N spokes otherwise; both one
// unit across along +x, so the arrows' instance matrices size and turn either.
export function glyphGeometry(N = 1) {
  if (N === 1) return arrowGeometry();
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(spokeTriangles(N), 3));
  return g;
}

// Markers with the index written on them, as sprites: always facing the viewer, hidden behind the surface.
const MARKER_PX = 20;

// Disc textures with a label, cached per viewer (textures belong to one renderer; dispose() frees them).
export class LabelTextures {
  constructor() {
    this.cache = new Map();
  }

  get(key, fill, text, options) {
    let tex = this.cache.get(key);
    if (!tex) this.cache.set(key, (tex = discTexture(fill, text, options)));
    return tex;
  }

  // A text tag (TAG_ASPECT wide per unit high): the text in `color` on a dark rounded box.
  getTag(key, color, text, rim = color) {
    let tex = this.cache.get(key);
    if (!tex) this.cache.set(key, (tex = tagTexture(color, text, rim)));
    return tex;
  }

  dispose() {
    for (const tex of this.cache.values()) tex.dispose();
    this.cache.clear();
  }
}

// ring: a thick rim (white, or ringColor); ringColor alone makes the rim that colour and thicker still (a
// prescribed singularity's pin, singularity-style.js).
function discTexture(fill, text, { ring = false, ringColor = null, textColor = '#111827' } = {}) {
  const size = 64;
  const c = document.createElement('canvas');
  c.width = c.height = size;
  const g = c.getContext('2d');
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 3, 0, 2 * Math.PI);
  g.fillStyle = fill;
  g.fill();
  g.lineWidth = ringColor ? 10 : ring ? 6 : 3;
  g.strokeStyle = ringColor ?? (ring ? '#ffffff' : 'rgba(17, 24, 39, 0.85)');
  g.stroke();
  g.fillStyle = textColor;
  g.font = `bold ${text.length > 2 ? 24 : 30}px system-ui, sans-serif`;
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, size / 2, size / 2 + 2);
  const tex = new CanvasTexture(c);
  tex.colorSpace = SRGBColorSpace;
  return tex;
}

export const TAG_ASPECT = 2.5;

// color: the text and the rim; rim: another colour for the rim (a prescribed singularity's tag).
function tagTexture(color, text, rim = color) {
  const h = 48, w = Math.round(TAG_ASPECT * h);
  const c = document.createElement('canvas');
  c.width = w;
  c.height = h;
  const g = c.getContext('2d');
  g.beginPath();
  if (g.roundRect) g.roundRect(2, 2, w - 4, h - 4, 10);
  else g.rect(2, 2, w - 4, h - 4); // canvases before roundRect (Chromium < 99, Safari < 16)
  g.fillStyle = 'rgba(17, 24, 39, 0.85)';
  g.fill();
  g.lineWidth = rim === color ? 3 : 6;
  g.strokeStyle = rim;
  g.stroke();
  g.fillStyle = color;
  g.font = 'bold 28px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, w / 2, h / 2 + 2);
  const tex = new CanvasTexture(c);
  tex.colorSpace = SRGBColorSpace;
  return tex;
}

export function markerSprite(texture, px = MARKER_PX) {
  const s = new Sprite(
    new SpriteMaterial({ map: texture, sizeAttenuation: false, depthTest: true, transparent: true }),
  );
  s.userData.px = px;
  s.renderOrder = 3;
  return s;
}

// Keeps sprites at a fixed size in pixels: without size attenuation a sprite's scale is in units of the
// view height times tan(fov/2), see three's sprite shader.
export function fixSpriteScales(group, camera, renderer) {
  const h = renderer.domElement.clientHeight || renderer.domElement.height || 1;
  const k = (2 * Math.tan((camera.fov * Math.PI) / 360)) / h;
  for (const s of group.children) if (s.isSprite) s.scale.setScalar(s.userData.px * k);
}
