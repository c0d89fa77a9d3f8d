// Shapes shared by the field views and the constraint handles: the flat arrow, and labelled discs drawn as
// sprites that keep a fixed size in pixels (handles) or as textures laid on the surface (singularities).
import { BufferAttribute, BufferGeometry, CanvasTexture, SRGBColorSpace, Sprite, SpriteMaterial } from 'three';

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

  dispose() {
    for (const tex of this.cache.values()) tex.dispose();
    this.cache.clear();
  }
}

function discTexture(fill, text, { ring = false, textColor = '#111827' } = {}) {
  const size = 64;
  const c = document.createElement('canvas');
  c.width = c.height = size;
  const g = c.getContext('2d');
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 3, 0, 2 * Math.PI);
  g.fillStyle = fill;
  g.fill();
  g.lineWidth = ring ? 6 : 3;
  g.strokeStyle = ring ? '#ffffff' : 'rgba(17, 24, 39, 0.85)';
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

export function markerSprite(texture, px = MARKER_PX) {
  const s = new Sprite(new SpriteMaterial({ map: texture, sizeAttenuation: false, depthTest: true, transparent: true }));
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
