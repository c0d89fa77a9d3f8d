// The Singularity and Feature tools in the page (issue 44, items 2 and 3), with the mouse, against the real
// wasm core in its worker, on small meshes made here: a cross field on an icosphere (320 faces, chi = 2)
// takes 8 x +1/4 by clicks and then has exactly those singularities, all prescribed (checked by the page's
// read-out and by indices this file computes from the face vectors); a drag moves one (a ghost shows where
// while dragging), Delete removes the selected one, a drag from empty surface adds a +/- pair (one step), undo
// and redo walk back and forth through each step, the design JSON keeps them; a boundary vertex and a second
// singularity on one vertex are refused with a message and change nothing; prescribed and free markers are
// told apart by their pixels. On a box (a 4 x 4 grid per side) the Field panel's feature angle sets how many
// edges are features (counted here from the dihedral angles), and the Feature tool adds and removes edges by
// clicks and by a drag, one undoable step per gesture. One page for the file; the tests run in order.
import { expect, test } from '@playwright/test';
import { icosphereOff } from '../icosphere.mjs';
import { cross, dot, norm, openDesignerPage, readMesh, sub, vertex } from './helpers.mjs';

// A cross field with the page's new-design feature angle (a document without one means none).
const CROSS = { boundary: 'free', gamma: 0, symmetry: 4, featureAngle: 35, constraints: [] };
const CYAN = (r, g, b) => r < 130 && g > 150 && b > 180; // the prescribed marker's ring (#22d3ee)
const YELLOW = (r, g, b) => r > 200 && g > 170 && b < 190 && r - b > 60; // a +1/4 disc (the index ramp)
const PINK = (r, g, b) => r > 200 && g < 150 && b > 140; // a feature line (#f472b6)

test.describe.serial('singularity and feature tools', () => {
  let page, errors, mesh, placed; // placed: vertex → page id of the prescribed singularities

  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const singularities = () => evaluate(() => window.tvf.singularities());
  const prescribedSet = async () =>
    (await singularities()).filter((s) => s.prescribed).map((s) => `${s.vertex}:${s.index}`).sort();
  const summary = () => evaluate(() => window.tvf.singularitySummary());
  const useTool = (name) => page.getByRole('button', { name, exact: true }).click();
  const screenOf = (p) => evaluate((p) => window.tvf.projectToScreen(p), p);
  const statusText = () => page.locator('#status').textContent();
  const key = (combo) => page.locator('#view').focus().then(() => page.keyboard.press(combo));

  async function loadOff(text, name) {
    await evaluate(([text, name]) => window.tvf.loadModel(new TextEncoder().encode(text), { name, restore: false }), [
      text,
      name,
    ]);
    await evaluate((d) => window.tvf.loadDesign(d), CROSS);
    mesh = await readMesh(page);
  }

  // Where vertex v is on screen, when the canvas (not a panel) is there and a click there lands on a face of
  // v with v its nearest corner (what the tool snaps to); else null.
  async function clickable(v) {
    const p = vertex(mesh, v);
    return evaluate(([p, v]) => {
      const at = window.tvf.projectToScreen(p);
      const root = document.querySelector('tangent-field-designer').shadowRoot;
      if (root.elementFromPoint(at.x, at.y)?.id !== 'view') return null;
      const hit = window.tvf.pick(at.x, at.y);
      if (!hit) return null;
      const m = window.tvf.mesh();
      let best = -1, bestD = Infinity;
      for (let k = 0; k < 3; k++) {
        const w = m.triangles[3 * hit.face + k];
        const d = Math.hypot(...[0, 1, 2].map((c) => m.positions[3 * w + c] - hit.point[c]));
        if (d < bestD) (bestD = d), (best = w);
      }
      return best === v ? at : null;
    }, [p, v]);
  }

  // Vertices facing the camera and clickable, spread out: each next one the farthest from those taken.
  async function spreadVertices(count, avoid = []) {
    const cam = await evaluate(() => window.tvf.camera());
    const candidates = [];
    for (let v = 0; v < mesh.positions.length / 3; v++) {
      const p = vertex(mesh, v), toEye = sub(cam.position, p);
      if (dot(p, toEye) / (norm(p) * norm(toEye)) < 0.55) continue;
      const at = await clickable(v);
      if (at) candidates.push({ v, p, at });
    }
    const taken = avoid.map((v) => ({ p: vertex(mesh, v) }));
    const out = [];
    while (out.length < count) {
      let best = null, bestD = -1;
      for (const c of candidates) {
        if (out.includes(c) || avoid.includes(c.v)) continue;
        const d = Math.min(...[...taken, ...out].map((t) => norm(sub(t.p, c.p))), Infinity);
        if (d > bestD) (bestD = d), (best = c);
      }
      expect(best, `${count} clickable vertices`).not.toBeNull();
      out.push(best);
    }
    return out;
  }

  async function dragScreen(from, to) {
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(to.x, to.y, { steps: 12 });
    await page.mouse.up();
  }

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    await loadOff(icosphereOff(2), 'sphere.off');
  });
  test.afterAll(async () => {
    await page?.close();
  });

  test('Singularity tool: 8 clicks of +1/4 on a sphere give exactly those singularities, all prescribed', async () => {
    const chi = mesh.positions.length / 3 - mesh.edges.length / 2 + mesh.triangles.length / 3;
    expect(chi).toBe(2);
    await expect(page.locator('#show-singularities')).not.toBeChecked();
    await useTool('Singularity');
    await expect(page.locator('#show-singularities'), 'the tool shows where the field puts the rest').toBeChecked();
    await expect(page.locator('#singularity-index option')).toHaveCount(8); // +-1/4, +-1/2, +-3/4, +-1
    await page.locator('#singularity-index').selectOption('1');
    const targets = await spreadVertices(8);
    placed = new Map();
    for (const [k, { v, at }] of targets.entries()) {
      await page.mouse.click(at.x, at.y);
      await expect.poll(async () => (await prescribedSet()).length).toBe(k + 1);
      if (k === 5) {
        // chi = 2, prescribed 6/4 = 3/2: the field places the last +1/2 itself.
        expect(await summary()).toMatchObject({ mode: 'free', eulerCharacteristic: 2 });
        await expect(page.locator('#singularity-summary')).toHaveText(
          'χ = 2, prescribed 3/2: the field places +1/2 itself.',
        );
      }
      // The new one is selected (for Delete).
      const previous = placed.get(targets[k - 1]?.v);
      await expect.poll(() => evaluate(() => window.tvf.selected()), 'selected').not.toBe(previous);
      placed.set(v, await evaluate(() => window.tvf.selected()));
    }
    const want = targets.map(({ v }) => `${v}:0.25`).sort();
    expect(await prescribedSet()).toEqual(want);
    const all = await singularities();
    expect(all.every((s) => s.prescribed), 'no singularity the field placed itself').toBe(true);
    expect(await summary()).toMatchObject({ mode: 'exact', eulerCharacteristic: 2, freeIndex: 0 });
    // The field's own indices, from its face vectors: those 8 and no other.
    expect(await fieldIndices()).toEqual(want);
    // Listed with the constraints, each with its vertex and index.
    await expect(page.locator('#constraint-list li')).toHaveCount(8);
    await expect(page.locator('#constraint-list li').first()).toContainText(`vertex ${targets[0].v} · index +1/4`);
    expect(errors).toEqual([]);
  });

  test('a drag moves a prescribed singularity, with a ghost where it goes; the field follows', async () => {
    const [from] = placed.keys();
    const [to] = await spreadVertices(1, [...placed.keys()]);
    const id = placed.get(from);
    const start = await clickable(from);
    await page.mouse.move(start.x, start.y);
    await page.mouse.down();
    await page.mouse.move(to.at.x, to.at.y, { steps: 12 });
    const ghosts = await evaluate(() => window.tvf.singularityMarkers().filter((m) => m.ghost).map((m) => m.vertex));
    expect(ghosts, 'the preview while dragging').toEqual([to.v]);
    await page.mouse.up();
    await expect.poll(async () => (await prescribedSet()).includes(`${to.v}:0.25`)).toBe(true);
    const moved = (await singularities()).find((s) => s.vertex === to.v);
    expect(moved).toMatchObject({ prescribed: true, id });
    expect((await singularities()).some((s) => s.vertex === from)).toBe(false);
    placed.delete(from);
    placed.set(to.v, id);
    placed.moved = { from, to: to.v };
    expect(await fieldIndices()).toEqual([...placed.keys()].map((v) => `${v}:0.25`).sort());
    expect(await evaluate(() => window.tvf.history().undo.at(-1))).toMatch(/move/i);
  });

  test('Delete removes the selected singularity; the field then places the rest itself', async () => {
    const [, victim] = placed.keys();
    const at = await clickable(victim);
    await page.mouse.click(at.x, at.y);
    await expect.poll(() => evaluate(() => window.tvf.selected())).toBe(placed.get(victim));
    expect((await prescribedSet()).length, 'a click on a marker selects it, adds nothing').toBe(8);
    await key('Delete');
    await expect.poll(async () => (await prescribedSet()).length).toBe(7);
    expect((await prescribedSet()).some((s) => s.startsWith(`${victim}:`))).toBe(false);
    expect(await summary()).toMatchObject({ mode: 'free', prescribedIndex: 1.75, freeIndex: 0.25 });
    await expect(page.locator('#singularity-summary')).toHaveText(
      'χ = 2, prescribed 7/4: the field places +1/4 itself.',
    );
    const free = (await singularities()).filter((s) => !s.prescribed);
    expect(free.reduce((sum, s) => sum + s.index, 0)).toBeCloseTo(0.25, 9);
    placed.delete(victim);
    placed.victim = victim;
  });

  test('prescribed markers are ringed in cyan, free ones are not (pixels read back)', async ({}, testInfo) => {
    // Arrows off: a unit cross field's arrows are the top of the ramp, a yellow of their own.
    await evaluate(() => window.tvf.setViews({ singularities: true, arrows: false }));
    const free = (await singularities()).find((s) => !s.prescribed && s.index > 0);
    expect(free, 'the +1/4 the field placed').toBeTruthy();
    const pinned = [...placed.keys()][0];
    const look = async (v) => {
      const p = vertex(mesh, v);
      await evaluate((p) => window.tvf.setCamera({ position: p.map((x) => 3.2 * x), target: [0, 0, 0] }), p);
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      return pixelsNear(await screenOf(p), 18);
    };
    const atFree = await look(free.vertex);
    await page.screenshot({ path: testInfo.outputPath('free.png') });
    const atPinned = await look(pinned);
    await page.screenshot({ path: testInfo.outputPath('prescribed.png') });
    console.log('pixels near the free marker', atFree, 'near a prescribed one', atPinned);
    expect(atFree.yellow, 'the free +1/4 disc is drawn').toBeGreaterThan(100);
    expect(atFree.cyan, 'without a ring').toBeLessThan(5);
    expect(atPinned.cyan, 'the prescribed one has its ring').toBeGreaterThan(100);
    expect(atPinned.yellow, 'around its +1/4 disc').toBeGreaterThan(50);
    await evaluate(() => window.tvf.setViews({ singularities: false, arrows: true }));
    await evaluate(() => window.tvf.frame());
  });

  test('undo and redo walk back through the delete and the move, and forward again', async () => {
    const now = await prescribedSet();
    await key('Control+z'); // the delete
    await expect.poll(async () => (await prescribedSet()).length).toBe(8);
    expect(await prescribedSet()).toContain(`${placed.victim}:0.25`);
    await key('Control+z'); // the move
    const { from, to } = placed.moved;
    await expect.poll(() => prescribedSet()).toContain(`${from}:0.25`);
    expect(await prescribedSet()).not.toContain(`${to}:0.25`);
    await key('Control+Shift+z');
    await key('Control+Shift+z');
    await expect.poll(() => prescribedSet()).toEqual(now);
    // The field keeps every prescribed one and places the remaining +1/4 itself.
    const found = await fieldIndices();
    for (const p of now) expect(found).toContain(p);
    const extra = found.filter((x) => !now.includes(x)).map((x) => Number(x.split(':')[1]));
    expect(extra.reduce((a, b) => a + b, 0)).toBeCloseTo(0.25, 9);
  });

  test('a drag from empty surface adds a +1/4, -1/4 pair; undo takes it back', async () => {
    const before = await prescribedSet();
    const steps = (await evaluate(() => window.tvf.history())).undo.length;
    const [a, b] = await spreadVertices(2, [...placed.keys()]);
    await dragScreen(a.at, b.at);
    await expect.poll(async () => (await prescribedSet()).length).toBe(before.length + 2);
    const after = await prescribedSet();
    expect(after).toContain(`${a.v}:0.25`);
    expect(after).toContain(`${b.v}:-0.25`);
    expect((await evaluate(() => window.tvf.history())).undo.length, 'one undoable step').toBe(steps + 1);
    await key('Control+z');
    await expect.poll(() => prescribedSet()).toEqual(before);
    await key('Control+Shift+z');
    await expect.poll(() => prescribedSet()).toEqual(after);
  });

  test('the design JSON keeps the prescribed singularities through a save and a load', async () => {
    const want = await prescribedSet();
    const design = await evaluate(() => window.tvf.saveDesign());
    expect(design.singularities.map((s) => `${s.vertex}:${s.index}`).sort()).toEqual(want);
    await evaluate((d) => window.tvf.loadDesign(d), CROSS);
    expect(await prescribedSet()).toEqual([]);
    await evaluate((d) => window.tvf.loadDesign(d), design);
    expect(await prescribedSet()).toEqual(want);
    expect(await fieldIndices()).toEqual((await singularities()).map((s) => `${s.vertex}:${s.index}`).sort());
  });

  test('refused: a second singularity on a vertex, and a boundary vertex; nothing changes', async () => {
    const design = JSON.stringify(await evaluate(() => window.tvf.saveDesign()));
    const [v] = placed.keys();
    const message = await evaluate((v) => window.tvf.addSingularity(v, -0.25).then(() => '', (e) => e.message), v);
    expect(message, 'refused, with the reason').toMatch(/singularit|already|vertex/i);
    expect(JSON.stringify(await evaluate(() => window.tvf.saveDesign()))).toBe(design);

    // An open model: a flat grid. A click next to a boundary corner snaps to it; the core refuses it.
    await loadOff(gridOff(6), 'grid.off');
    await evaluate(() => window.tvf.setCamera({ position: [0, 0, 2.5], target: [0, 0, 0] }));
    await useTool('Singularity');
    const corner = 0; // (0, 0): on the boundary
    const inside = vertex(mesh, 8); // (1, 1), diagonal neighbour
    const p = vertex(mesh, corner).map((x, c) => x + 0.2 * (inside[c] - x));
    const at = await screenOf(p);
    await page.mouse.click(at.x, at.y);
    await expect.poll(statusText).toMatch(/boundary/i);
    await expect(page.locator('#error-banner')).toContainText(/boundary/i);
    expect(await prescribedSet()).toEqual([]);
    expect(await evaluate(() => window.tvf.constraints())).toEqual([]);
    expect(errors).toEqual([]);
  });

  test('box: the feature angle sets the feature edges; the Feature tool adds, removes some', async ({}, testInfo) => {
    await loadOff(boxOff(4), 'box.off');
    const angle = page.locator('#feature-angle');
    await expect(angle).toHaveValue('35');
    const count = (deg) => sharpEdgeCount(mesh, deg);
    expect(count(35)).toBe(48); // 12 creases of 4 edges
    await expect.poll(async () => (await evaluate(() => window.tvf.features())).edges.length).toBe(count(35));
    await expect(page.locator('#feature-count')).toHaveText(`${count(35)} feature edges`);
    for (const deg of [0, 95, 35]) {
      await angle.fill(String(deg));
      await angle.press('Enter');
      await expect.poll(async () => (await evaluate(() => window.tvf.features())).angle).toBe(deg);
      expect((await evaluate(() => window.tvf.features())).edges.length).toBe(count(deg));
    }

    // Three sides in view; the Feature tool on an edge of the +z side's grid and on the +z/+x crease.
    await evaluate(() => window.tvf.setCamera({ position: [2.2, 1.6, 3.4], target: [0, 0, 0] }));
    await useTool('Feature');
    const mid = (a, b) => vertex(mesh, a).map((x, c) => (x + vertex(mesh, b)[c]) / 2);
    const flat = gridEdge(mesh, 1, 2); // from (-0.5, 0, 1) to (0, 0, 1)
    let at = await screenOf(mid(...flat));
    await page.mouse.click(at.x, at.y);
    await expect.poll(async () => (await evaluate(() => window.tvf.features())).edges.length).toBe(49);
    expect((await evaluate(() => window.tvf.features())).add).toEqual([flat]);
    const crease = creaseEdge(mesh);
    at = await screenOf(mid(...crease));
    // The crease is drawn as a line; a flat edge is not (until it is a feature).
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    expect((await pixelsNear(at, 6)).pink, 'a feature line on the crease').toBeGreaterThan(4);
    expect((await pixelsNear(await screenOf(mid(...gridEdge(mesh, 1, 3))), 6)).pink, 'none on a flat edge').toBe(0);
    await page.keyboard.down('Alt');
    await page.mouse.click(at.x, at.y);
    await page.keyboard.up('Alt');
    await expect.poll(async () => (await evaluate(() => window.tvf.features())).edges.length).toBe(48);
    expect((await evaluate(() => window.tvf.features())).remove).toEqual([crease]);

    // A drag along a grid line of the +z side: its two edges, in one step.
    const steps = (await evaluate(() => window.tvf.history())).undo.length;
    const [e0, e1] = [gridEdge(mesh, 1, 1), gridEdge(mesh, 2, 1)];
    const start = e0.find((v) => vertex(mesh, v)[0] < -0.4), end = e1.find((v) => vertex(mesh, v)[0] > 0.4);
    await dragScreen(await screenOf(vertex(mesh, start)), await screenOf(vertex(mesh, end)));
    await expect.poll(async () => (await evaluate(() => window.tvf.features())).edges.length).toBe(50);
    const { add } = await evaluate(() => window.tvf.features());
    const keyOf = ([a, b]) => `${Math.min(a, b)},${Math.max(a, b)}`;
    expect(add.map(keyOf).sort()).toEqual([flat, e0, e1].map(keyOf).sort());
    expect((await evaluate(() => window.tvf.history())).undo.length).toBe(steps + 1);
    await page.screenshot({ path: testInfo.outputPath('box-features.png') });
    await key('Control+z');
    await expect.poll(async () => (await evaluate(() => window.tvf.features())).edges.length).toBe(48);
    expect(errors).toEqual([]);
  });

  // ---- what the test computes itself

  // "vertex:index" of every vertex where the field's face vectors turn (with the angle defect) by a nonzero
  // multiple of 2 pi / N: the field's singularities from the definition, not from the page's read-out.
  async function fieldIndices() {
    const { F, N } = await evaluate(() => ({
      F: Array.from(window.tvf.faceVectors()),
      N: window.tvf.settings().symmetry,
    }));
    const T = mesh.triangles, nV = mesh.positions.length / 3, nF = T.length / 3;
    const normal = (f) => {
      const [a, b, c] = [0, 1, 2].map((k) => vertex(mesh, T[3 * f + k]));
      const n = cross(sub(b, a), sub(c, a));
      return n.map((x) => x / norm(n));
    };
    const faceOf = new Map(), turning = new Float64Array(nV), defect = new Float64Array(nV).fill(2 * Math.PI);
    const boundary = new Set();
    for (let f = 0; f < nF; f++) {
      for (let k = 0; k < 3; k++) {
        const a = T[3 * f + k], b = T[3 * f + ((k + 1) % 3)], c = T[3 * f + ((k + 2) % 3)];
        faceOf.set(`${a},${b}`, f);
        const u = sub(vertex(mesh, b), vertex(mesh, a)), w = sub(vertex(mesh, c), vertex(mesh, a));
        defect[a] -= Math.acos(Math.max(-1, Math.min(1, dot(u, w) / (norm(u) * norm(w)))));
      }
    }
    for (let f = 0; f < nF; f++) {
      for (let k = 0; k < 3; k++) {
        const a = T[3 * f + k], b = T[3 * f + ((k + 1) % 3)], g = faceOf.get(`${b},${a}`);
        if (g === undefined) {
          boundary.add(a).add(b);
          continue;
        }
        if (g < f) continue;
        // Each face's vector as a complex number in the frame of the edge b -> a and its own normal: the ratio
        // of the two is the field's turn across the edge (unfolding keeps both numbers).
        const e = sub(vertex(mesh, a), vertex(mesh, b)), u = F.slice(3 * f, 3 * f + 3), v = F.slice(3 * g, 3 * g + 3);
        const [fr, fi] = [dot(e, u), dot(cross(e, u), normal(f))];
        const [gr, gi] = [dot(e, v), dot(cross(e, v), normal(g))];
        let jump = Math.atan2(gi * fr - gr * fi, gr * fr + gi * fi);
        jump -= ((2 * Math.PI) / N) * Math.round((N * jump) / (2 * Math.PI));
        turning[b] += jump;
        turning[a] -= jump;
      }
    }
    const out = [];
    for (let v = 0; v < nV; v++) {
      if (boundary.has(v)) continue;
      const k = Math.round((N * (turning[v] + defect[v])) / (2 * Math.PI));
      if (k !== 0) out.push(`${v}:${k / N}`);
    }
    return out.sort();
  }

  // Pixels of the canvas within r CSS pixels of a client point: how many look like the prescribed ring
  // (cyan), like a +1/4 disc (pale yellow) and like a feature line (pink).
  function pixelsNear(at, r) {
    return evaluate(
      ([at, r, cyan, yellow, pink]) => {
        const [isCyan, isYellow, isPink] = [cyan, yellow, pink].map((f) => new Function(`return ${f}`)());
        const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
        const rect = src.getBoundingClientRect(), sx = src.width / rect.width, sy = src.height / rect.height;
        const c = document.createElement('canvas');
        c.width = src.width;
        c.height = src.height;
        const g = c.getContext('2d', { willReadFrequently: true });
        g.drawImage(src, 0, 0);
        const x0 = Math.round((at.x - rect.left - r) * sx), y0 = Math.round((at.y - rect.top - r) * sy);
        const w = Math.round(2 * r * sx), h = Math.round(2 * r * sy);
        const data = g.getImageData(x0, y0, w, h).data;
        const out = { cyan: 0, yellow: 0, pink: 0 };
        for (let i = 0; i < data.length; i += 4) {
          if (isCyan(data[i], data[i + 1], data[i + 2])) out.cyan++;
          if (isYellow(data[i], data[i + 1], data[i + 2])) out.yellow++;
          if (isPink(data[i], data[i + 1], data[i + 2])) out.pink++;
        }
        return out;
      },
      [at, r, CYAN.toString(), YELLOW.toString(), PINK.toString()],
    );
  }
});

// A flat n x n grid of squares, each split in two, in the xy-plane (an open disc: its outer vertices are on
// the boundary). Vertex (i, j) is j (n + 1) + i.
function gridOff(n) {
  const v = [], f = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) v.push([i / n - 0.5, j / n - 0.5, 0]);
  const id = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)], [id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
    }
  }
  return off(v, f);
}

// The cube [-1, 1]^3 with an n x n grid of split squares on each side, welded, outward facing.
function boxOff(n) {
  const v = [], f = [], index = new Map();
  const at = (p) => {
    const k = p.map((x) => Math.round(x * n)).join(',');
    if (!index.has(k)) index.set(k, v.push(p) - 1);
    return index.get(k);
  };
  for (const axis of [0, 1, 2]) {
    for (const sign of [1, -1]) {
      const u = (axis + 1) % 3, w = (axis + 2) % 3;
      const point = (i, j) => {
        const p = [0, 0, 0];
        p[axis] = sign;
        p[u] = (2 * i) / n - 1;
        p[w] = (2 * j) / n - 1;
        return at(p);
      };
      for (let i = 0; i < n; i++) {
        for (let j = 0; j < n; j++) {
          const q = [point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
          if (sign < 0) q.reverse();
          f.push([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
        }
      }
    }
  }
  return off(v, f);
}

function off(v, f) {
  const lines = [...v.map((p) => p.join(' ')), ...f.map((t) => `3 ${t.join(' ')}`)];
  return `OFF\n${v.length} ${f.length} 0\n${lines.join('\n')}\n`;
}

// Interior edges whose two faces' normals differ by more than `degrees` (0: none), from the mesh.
function sharpEdgeCount(mesh, degrees) {
  if (!(degrees > 0)) return 0;
  const T = mesh.triangles, faces = new Map();
  const normal = (f) => {
    const [a, b, c] = [0, 1, 2].map((k) => vertex(mesh, T[3 * f + k]));
    const n = cross(sub(b, a), sub(c, a));
    return n.map((x) => x / norm(n));
  };
  for (let f = 0; f < T.length / 3; f++) {
    for (let k = 0; k < 3; k++) {
      const a = T[3 * f + k], b = T[3 * f + ((k + 1) % 3)], key = a < b ? `${a},${b}` : `${b},${a}`;
      faces.set(key, [...(faces.get(key) ?? []), f]);
    }
  }
  let count = 0;
  for (const pair of faces.values()) {
    if (pair.length !== 2) continue;
    const c = Math.max(-1, Math.min(1, dot(normal(pair[0]), normal(pair[1]))));
    if ((Math.acos(c) * 180) / Math.PI > degrees) count++;
  }
  return count;
}

// The vertex at point p.
function find(mesh, p) {
  for (let v = 0; v < mesh.positions.length / 3; v++) if (norm(sub(vertex(mesh, v), p)) < 1e-9) return v;
  throw new Error(`no vertex at ${p}`);
}

// The mesh edge [a, b] (lower first) from grid point (i, j) to (i + 1, j) of the 4 x 4 grid on the +z side.
function gridEdge(mesh, i, j) {
  const a = find(mesh, [i / 2 - 1, j / 2 - 1, 1]), b = find(mesh, [(i + 1) / 2 - 1, j / 2 - 1, 1]);
  return a < b ? [a, b] : [b, a];
}

// An edge of the crease between the +z and +x sides: from (1, 0, 1) to (1, 0.5, 1), lower vertex first.
function creaseEdge(mesh) {
  const a = find(mesh, [1, 0, 1]), b = find(mesh, [1, 0.5, 1]);
  return a < b ? [a, b] : [b, a];
}
