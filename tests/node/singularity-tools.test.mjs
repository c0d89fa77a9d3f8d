// The Singularity and Feature tools' gestures (web/tools/), on a flat grid seen from above through a fake viewer
// (screen pixel = 100 x model unit, every point in sight), with the real marker and feature views: what each
// press, drag and release reports to the actions, the ghosts and the preview while dragging; and the Field
// panel's sentence for what the prescribed singularities leave to the field.
import assert from 'node:assert/strict';
import test from 'node:test';
import { Scene } from 'three';
import { grid } from './fakes.mjs';
import { Surface } from '../../web/geometry/surface.js';
import { singularitySummaryText } from '../../web/element/panels.js';
import { FeatureTool } from '../../web/tools/feature-tool.js';
import { SingularityTool } from '../../web/tools/singularity-tool.js';
import { FeaturesView } from '../../web/views/features-view.js';
import { LabelTextures } from '../../web/views/markers.js';
import { SingularitiesView } from '../../web/views/singularities-view.js';

// Label textures draw on a canvas: in node, one that takes every call and draws nothing.
globalThis.document ??= {
  createElement: () => ({ getContext: () => new Proxy({}, { get: () => () => {}, set: () => true }) }),
};

const N = 6; // grid squares per side; vertex (i, j) is j (N + 1) + i
const at = (i, j) => j * (N + 1) + i;
const px = (i, j) => ({ clientX: (100 * i) / N, clientY: (100 * j) / N });

function fakeViewer() {
  const m = grid(N, 1);
  const surface = new Surface(m.positions, m.triangles, m.edges);
  const scene = new Scene();
  const viewer = {
    surface,
    singularities: new SingularitiesView(scene, new LabelTextures()),
    features: new FeaturesView(scene),
    requestRender() {},
    projectToScreen: ([x, y]) => ({ x: 100 * x, y: 100 * y }),
    isVisible: () => true,
    pick(x, y) {
      const p = [x / 100, y / 100, 0];
      for (let f = 0; f < surface.nF; f++) {
        const bary = surface.bary2d(f, surface.to2d(f, p));
        if (bary.every((b) => b >= -1e-12)) return { face: f, bary, point: p };
      }
      return null;
    },
  };
  viewer.singularities.setSurface(surface);
  viewer.features.setSurface(surface);
  return viewer;
}

// A gesture as the ToolController runs it: claims, down, moves, up (a click when it moved under 6 px).
function gesture(tool, points, modifiers = {}) {
  const events = points.map((p) => ({ ...p, ...modifiers }));
  const claim = tool.claims(events[0]);
  if (!claim) return false;
  tool.down(events[0], claim);
  const seen = [];
  for (const e of events.slice(1)) {
    tool.move(e);
    seen.push(tool.viewer.singularities?.ghosts?.map((g) => ({ ...g })) ?? []);
  }
  const last = events[events.length - 1];
  tool.up(last, Math.hypot(last.clientX - events[0].clientX, last.clientY - events[0].clientY) < 6);
  return seen;
}

function recorder() {
  const calls = [];
  const record = (name) => (...args) => calls.push([name, ...args]);
  return { calls, actions: { onAdd: record('add'), onMove: record('move'), onPair: record('pair'),
    onSelect: record('select'), onFeatures: record('features'), symmetry: () => 4, removing: () => false } };
}

test('Singularity tool: a click places at the nearest vertex, a drag moves a marker, from empty surface a pair', () => {
  const viewer = fakeViewer(), { calls, actions } = recorder();
  const tool = new SingularityTool(viewer, actions);
  // A click a little off vertex (2, 3): that vertex.
  const near = { clientX: px(2, 3).clientX + 3, clientY: px(2, 3).clientY - 2 };
  gesture(tool, [near, near]);
  assert.deepEqual(calls, [['add', at(2, 3)]]);

  // A marker there: a press on it selects it, a drag moves it, with a ghost at the vertex under the pointer.
  calls.length = 0;
  viewer.singularities.setPrescribed([{ vertex: at(2, 3), index: 0.25, id: 7 }], 4);
  const ghosts = gesture(tool, [px(2, 3), px(3, 3), px(4, 4)]);
  assert.deepEqual(calls, [['select', 7], ['move', 7, at(4, 4)]]);
  assert.deepEqual(ghosts.at(-1), [{ vertex: at(4, 4), index: 0.25 }]);
  assert.deepEqual(viewer.singularities.ghosts, [], 'no ghost after the release');
  const drawn = viewer.singularities.drawn();
  assert.deepEqual(drawn.map(({ vertex, prescribed }) => [vertex, prescribed]), [[at(2, 3), true]]);

  // A click on the marker only selects it; a drag back onto its own vertex moves nothing.
  calls.length = 0;
  gesture(tool, [px(2, 3), px(2, 3)]);
  gesture(tool, [px(2, 3), px(3, 3), px(2, 3)]);
  assert.deepEqual(calls, [['select', 7], ['select', 7]]);

  // From empty surface: +1/N at the press, -1/N at the release, shown as two ghosts while dragging.
  calls.length = 0;
  const pair = gesture(tool, [px(5, 1), px(5, 3), px(5, 5)]);
  assert.deepEqual(calls, [['pair', at(5, 1), at(5, 5)]]);
  assert.deepEqual(pair.at(-1), [{ vertex: at(5, 1), index: 0.25 }, { vertex: at(5, 5), index: -0.25 }]);

  // Off the model: not claimed (the press orbits).
  assert.equal(gesture(tool, [{ clientX: 150, clientY: 50 }]), false);
});

test('Feature tool: a click takes the nearest edge, a drag the edges it runs along and no other', () => {
  const viewer = fakeViewer(), { calls, actions } = recorder();
  const tool = new FeatureTool(viewer, actions);
  const mid = (a, b) => ({ clientX: (a.clientX + b.clientX) / 2, clientY: (a.clientY + b.clientY) / 2 + 1 });
  gesture(tool, [mid(px(2, 2), px(3, 2)), mid(px(2, 2), px(3, 2))]);
  assert.deepEqual(calls, [['features', [[at(2, 2), at(3, 2)]], false]]);

  // Along row 3 from (1, 3) to (4, 3), passing its vertices: its three edges, nothing of the diagonals.
  calls.length = 0;
  const along = [];
  for (let k = 0; k <= 30; k++) along.push({ clientX: (100 * (1 + (3 * k) / 30)) / N, clientY: (100 * 3) / N });
  gesture(tool, along);
  const row = [[at(1, 3), at(2, 3)], [at(2, 3), at(3, 3)], [at(3, 3), at(4, 3)]];
  assert.deepEqual(calls, [['features', row, false]]);
  assert.equal(viewer.features.preview.visible, false, 'the preview ends with the gesture');

  // Alt (or Shift) removes; a drag along the boundary takes none of its edges (the boundary condition's).
  calls.length = 0;
  gesture(tool, [mid(px(2, 2), px(3, 2)), mid(px(2, 2), px(3, 2))], { altKey: true });
  const edge = along.map((p) => ({ ...p, clientY: 0.5 }));
  gesture(tool, edge);
  assert.deepEqual(calls, [['features', [[at(2, 2), at(3, 2)]], true], ['features', [], false]]);
  // ... but a click on a boundary edge is reported, for the core to refuse by name.
  calls.length = 0;
  gesture(tool, [{ clientX: 25, clientY: 0.5 }, { clientX: 25, clientY: 0.5 }]);
  assert.deepEqual(calls, [['features', [[at(1, 0), at(2, 0)]], false]]);
});

test('Feature view: the edges drawn as lines lifted off the surface', () => {
  const viewer = fakeViewer();
  viewer.features.setEdges([[at(0, 0), at(1, 0)], [at(1, 1), at(2, 1)]]);
  assert.deepEqual(viewer.features.drawn(), [[at(0, 0), at(1, 0)], [at(1, 1), at(2, 1)]]);
  const p = viewer.features.lines.geometry.getAttribute('position');
  assert.equal(p.count, 4);
  for (let k = 0; k < 4; k++) assert.ok(p.getZ(k) > 0, 'above the surface, along the normal');
  viewer.features.setEdges([]);
  assert.deepEqual(viewer.features.drawn(), []);
});

test('Field panel: what the prescribed indices leave to the field, in words', () => {
  const summary = (mode, p, free) => ({ mode, eulerCharacteristic: 2, prescribedIndex: p, freeIndex: free });
  const text = (...args) => singularitySummaryText(summary(...args));
  assert.equal(text('free', 1.5, 0.5), 'χ = 2, prescribed 3/2: the field places +1/2 itself.');
  assert.equal(text('free', 2.25, -0.25), 'χ = 2, prescribed 9/4: the field places \u22121/4 itself.');
  assert.equal(text('exact', 2, 0), 'χ = 2, prescribed 2: the field has these singularities and no other.');
  assert.equal(singularitySummaryText(summary('none', 0, 2)), '');
  assert.equal(singularitySummaryText({ ...summary('free', -1 / 3, 7 / 3), eulerCharacteristic: 2 }),
    'χ = 2, prescribed \u22121/3: the field places +7/3 itself.');
});
