// The views' handling of N-fields that needs no GL: the singularity markers and their fraction tags (where
// they are, what they say, that a vector field's markers are as before), and the flow texture's corner field
// (per corner, matched and combed: a scrambled constant cross field reaches the GPU as one direction).
import assert from 'node:assert/strict';
import test from 'node:test';
import { PerspectiveCamera, Scene, Vector3 } from 'three';
import { grid } from './fakes.mjs';
import { Surface } from '../../web/geometry/surface.js';
import { randomSequence } from '../../web/geometry/arrow-sampling.js';
import { LabelTextures } from '../../web/views/markers.js';
import { SingularitiesView } from '../../web/views/singularities-view.js';
import { lineGeometry, setLineField } from '../../web/views/lic-lines.js';

// Label textures draw on a canvas: in node, one that takes every call and draws nothing; the texts drawn are
// recorded.
function stubDocument() {
  const texts = [];
  const context = new Proxy({ fillText: (t) => texts.push(t) }, { get: (o, k) => (k in o ? o[k] : () => {}), set: (o, k, v) => ((o[k] = v), true) });
  globalThis.document = { createElement: () => ({ getContext: () => context }) };
  return texts;
}

function viewOf(s) {
  const view = new SingularitiesView(new Scene(), new LabelTextures());
  view.setSurface(s);
  view.setVisible(true);
  return view;
}

const camera = () => {
  const c = new PerspectiveCamera(40, 1, 0.01, 100);
  c.position.set(0.3, -0.4, 2);
  c.lookAt(0.5, 0.5, 0);
  c.updateMatrixWorld();
  return c;
};

test('singularity view: an N-field\'s markers carry their index as a fraction, on tags that stay put on screen', () => {
  const texts = stubDocument();
  const m = grid(6, 1), s = new Surface(m.positions, m.triangles, m.edges);
  const view = viewOf(s);
  view.setSingularities([{ vertex: 10, index: 0.5 }, { vertex: 20, index: -0.25 }, { vertex: 24, index: 1 }], 4);
  assert.deepEqual(view.drawnTags(), [{ vertex: 10, label: '+1/2' }, { vertex: 20, label: '\u22121/4' }, { vertex: 24, label: '+1' }]);
  assert.equal(view.drawn().length, 3, 'a disc for each');
  assert.ok(texts.includes('+1/2') && texts.includes('\u22121/4'), `drawn: ${texts}`);
  const cam = camera();
  view.updateScale(cam, { domElement: { clientHeight: 720 } });
  for (const tag of view.tags.children) {
    // Pulled towards the eye along the view ray: the anchor projects where the vertex does.
    const vertex = new Vector3(...s.vertex(tag.userData.vertex)).project(cam), anchor = tag.position.clone().project(cam);
    assert.ok(Math.hypot(vertex.x - anchor.x, vertex.y - anchor.y) < 0.01, 'where the vertex is on screen');
    assert.ok(tag.position.distanceTo(cam.position) < new Vector3(...s.vertex(tag.userData.vertex)).distanceTo(cam.position), 'nearer the eye');
    assert.ok(tag.center.x < 0, 'beside the disc, not on it');
    assert.ok(Math.abs(tag.scale.x / tag.scale.y - 2.5) < 1e-12);
  }
  // A vector field: the index on the disc, as before, and no tags.
  texts.length = 0;
  view.setSingularities([{ vertex: 10, index: 1 }, { vertex: 20, index: -1 }]);
  assert.deepEqual(view.drawnTags(), []);
  assert.equal(view.drawn().length, 2);
  assert.deepEqual(texts.sort(), ['+1', '\u22121']);
  // Hidden: nothing built.
  view.setVisible(false);
  view.setSingularities([{ vertex: 10, index: 0.5 }], 2);
  assert.deepEqual(view.drawnTags(), []);
});

test('flow texture of N-fields: per-corner vectors, matched and combed, one direction for a constant field', () => {
  const m = grid(8, 1), s = new Surface(m.positions, m.triangles, m.edges), random = randomSequence(2);
  const geometry = lineGeometry(s);
  assert.equal(geometry.getAttribute('position').count, 3 * s.nF, 'unindexed: three corners per face');
  assert.equal(geometry.index, null);
  const normals = geometry.getAttribute('licNormal').array;
  for (let i = 0; i < normals.length; i += 3) assert.ok(Math.abs(normals[i]) + Math.abs(normals[i + 1]) + Math.abs(normals[i + 2] - 1) < 1e-7);
  for (const N of [2, 4]) {
    const V = new Float64Array(3 * s.nV), F = new Float64Array(3 * s.nF);
    const put = (out, i) => {
      const a = 0.9 + (2 * Math.PI * Math.floor(random() * N)) / N;
      out.set([Math.cos(a), Math.sin(a), 0], 3 * i);
    };
    for (let v = 0; v < s.nV; v++) put(V, v);
    for (let f = 0; f < s.nF; f++) put(F, f);
    setLineField(geometry, s, V, F, N);
    const C = geometry.getAttribute('licField').array;
    for (let i = 0; i < C.length; i += 3) {
      assert.ok(Math.abs(C[i] - C[0]) < 1e-6 && Math.abs(C[i + 1] - C[1]) < 1e-6 && Math.abs(C[i + 2]) < 1e-6, `N=${N}, corner ${i / 3}`);
    }
    const a = Math.atan2(C[1], C[0]) - 0.9, step = (2 * Math.PI) / N;
    assert.ok(Math.abs(a / step - Math.round(a / step)) < 1e-6, 'one of the field\'s directions');
  }
});
