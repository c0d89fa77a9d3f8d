// Stripe patterns in the page (issue 45; docs/stripes.md, docs/js-api.md "Stripe patterns"), against the real
// wasm core in its worker and the real WebGL view: the pictures are read back from the canvas and measured here.
// A flat square with a constant field shows straight stripes at exactly the asked frequency (the transitions'
// spacing down the picture against the projection of the model's units; the adapted spacing, on by default, has
// nothing to adapt there), a line width asked for as the dark share of the picture and of the baked GLB, stripes
// across the field turned a quarter, and its GLB carries the phase as TEXCOORD_1; on the default model the stripes show,
// follow an edit (a new pattern for the new field), new patterns leave no WebGL buffer behind, and the GLB
// bakes them into its base colour; a cross field takes grid, bricks or weave only, and bad options are refused
// by name with nothing changed; after an edit whose stripes came as a local update made ahead, the next edit's
// field and stripes are drawn in one frame, and no frame is drawn again after theirs. On a sphere's
// smoothest line field the stripes' own direction, read from the pixels, turns by pi round each +1/2 singularity
// (one stripe ends there, the others turn round it) and not at all where the field is calm; a cross field's
// grid turns by pi/2 round each of its eight +1/4 (three of its lines meet there) (stripe-topology.mjs). On a
// torus whose field crosses both loops, the frequency is fitted to them, reported and said in the panel.
import { expect, test } from '@playwright/test';
import { icosphereOff } from '../icosphere.mjs';
import { fieldTurnedAt, openDesignerPage, readCanvasGrey } from './helpers.mjs';
import { directionTurns } from './stripe-topology.mjs';

// A flat n × n grid over the unit square in z = 0, as OFF text.
function flatSquareOff(n) {
  const v = [], f = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) v.push(`${i / n} ${j / n} 0`);
  const at = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      f.push(`3 ${at(i, j)} ${at(i + 1, j)} ${at(i + 1, j + 1)}`, `3 ${at(i, j)} ${at(i + 1, j + 1)} ${at(i, j + 1)}`);
    }
  return `OFF\n${v.length} ${f.length} 0\n${v.join('\n')}\n${f.join('\n')}\n`;
}

// The canvas's grey values down pixel column x (drawing-buffer pixels), top first.
const greyColumn = (img, x) => Array.from({ length: img.h }, (_, y) => img.grey[y * img.w + Math.round(x)]);

// Where the grey crosses the middle of its neighbourhood's range (±half a window), by linear interpolation.
function crossings(grey, from, to, window) {
  const mid = (y) => {
    const lo = Math.max(from, y - window), hi = Math.min(to, y + window);
    let min = Infinity, max = -Infinity;
    for (let k = lo; k <= hi; k++) [min, max] = [Math.min(min, grey[k]), Math.max(max, grey[k])];
    return { m: 0.5 * (min + max), contrast: max - min };
  };
  const out = [];
  for (let y = from; y < to; y++) {
    const { m, contrast } = mid(y);
    if (contrast < 60) continue;
    const a = grey[y] - m, b = grey[y + 1] - m;
    if (a < 0 !== b < 0) out.push(y + a / (a - b));
  }
  return out;
}

test.describe.serial('stripe patterns in the page', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const refusal = (fn, arg) => page.evaluate(fn, arg).then(() => 'resolved', (err) => err.message);

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 900, height: 700 } }));
  });
  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page.close();
  });

  test('a flat square with a constant field: straight stripes at exactly the asked frequency', async () => {
    await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'square.off', restore: false }),
      flatSquareOff(40));
    // One vector along x: the constant field fits it with zero energy, so it is the field.
    await evaluate(() => window.tvf.addVector(0, [1, 0, 0]));
    await evaluate(() => window.tvf.setViews({ arrows: false, singularities: false }));
    const frequency = 12;
    const state = await evaluate((frequency) =>
      window.tvf.setStripes({ visible: true, frequency, profile: 'stripes', light: '#ffffff', dark: '#000000' }),
    frequency);
    expect(state.visible).toBe(true);
    expect(state.stats.families).toBe(1);
    await evaluate(() => window.tvf.setCamera({ position: [0.5, 0.5, 1.6], target: [0.5, 0.5, 0] }));
    await page.waitForTimeout(300);
    // The model's y = 0.2 and 0.8 on screen (CSS pixels), scaled to the drawing buffer.
    const [a, b] = await evaluate(() => [window.tvf.projectToScreen([0.5, 0.2, 0]), window.tvf.projectToScreen([0.5, 0.8, 0])]);
    const img = await readCanvasGrey(page);
    const grey = greyColumn(img, (a.x - img.left) * img.scale);
    const ya = (a.y - img.top) * img.scale, yb = (b.y - img.top) * img.scale;
    const pxPerUnit = Math.abs(yb - ya) / 0.6;
    const found = crossings(grey, Math.round(Math.min(ya, yb)), Math.round(Math.max(ya, yb)), Math.round(pxPerUnit / frequency));
    expect(found.length).toBeGreaterThan(10);
    const periods = (found.length - 1) / 2;
    const measured = periods / ((found.at(-1) - found[0]) / pxPerUnit);
    console.log(`[ measured ] flat square: ${found.length} transitions, ${measured.toFixed(3)} stripes per unit (asked ${frequency})`);
    expect(Math.abs(measured - frequency)).toBeLessThan(0.01 * frequency);
    // Straight: the same transitions one fifth of the square to the right.
    const c = await evaluate(() => window.tvf.projectToScreen([0.7, 0.5, 0]));
    const other = crossings(greyColumn(img, (c.x - img.left) * img.scale), Math.round(Math.min(ya, yb)),
      Math.round(Math.max(ya, yb)), Math.round(pxPerUnit / frequency));
    expect(other.length).toBe(found.length);
    for (let k = 0; k < found.length; k++) expect(Math.abs(other[k] - found[k])).toBeLessThan(1.5);
    // The GLB (built anew: an OFF model) carries the phase as TEXCOORD_1: 12 periods across the unit square.
    const span = await evaluate(async () => {
      const glb = await window.tvf.exportGlb({ size: 128 });
      const jsonLength = new DataView(glb.buffer, glb.byteOffset).getUint32(12, true);
      const doc = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
      const bin = glb.subarray(20 + jsonLength + 8);
      const accessor = doc.accessors[doc.meshes[0].primitives[0].attributes.TEXCOORD_1];
      const view = doc.bufferViews[accessor.bufferView];
      const start = bin.byteOffset + (view.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
      const values = new Float32Array(bin.buffer.slice(start, start + 8 * accessor.count));
      const x = values.filter((_, i) => i % 2 === 0);
      return Math.max(...x) - Math.min(...x);
    });
    expect(Math.abs(span - frequency)).toBeLessThan(0.01 * frequency);
    // The lines' width: the dark share of the column, 1/2 at the profile's own, then 0.2 asked for; only drawn
    // again (no new pattern), and the GLB bakes the same share.
    const darkShare = (g) => g.filter((v) => v < 128).length / g.length;
    const column = (image) => greyColumn(image, (a.x - image.left) * image.scale)
      .slice(Math.round(Math.min(ya, yb)), Math.round(Math.max(ya, yb)));
    const own = darkShare(column(img));
    const narrow = await evaluate(() => window.tvf.setStripes({ width: 0.2 }));
    expect(narrow.width).toBe(0.2);
    expect(narrow.stats.drawnAt).toBe(state.stats.drawnAt);
    await page.waitForTimeout(300);
    const drawn = darkShare(column(await readCanvasGrey(page)));
    const baked = await evaluate(async () => {
      const glb = await window.tvf.exportGlb({ size: 512 });
      const jsonLength = new DataView(glb.buffer, glb.byteOffset).getUint32(12, true);
      const doc = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
      const bin = glb.subarray(20 + jsonLength + 8);
      const texture = doc.materials[0].pbrMetallicRoughness.baseColorTexture.index;
      const view = doc.bufferViews[doc.images[doc.textures[texture].source].bufferView];
      const png = bin.slice(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength);
      const bitmap = await createImageBitmap(new Blob([png], { type: 'image/png' }));
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const context = canvas.getContext('2d');
      context.drawImage(bitmap, 0, 0);
      const { data } = context.getImageData(0, 0, bitmap.width, bitmap.height);
      let covered = 0, dark = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (data[i + 3] < 255) continue;
        covered++;
        dark += data[i] < 128;
      }
      return dark / covered;
    });
    console.log(`[ measured ] flat square: dark share ${own.toFixed(3)} at the profile's width, ${drawn.toFixed(3)} ` +
      `at 0.2, baked ${baked.toFixed(3)}`);
    expect(Math.abs(own - 0.5)).toBeLessThan(0.03);
    expect(Math.abs(drawn - 0.2)).toBeLessThan(0.03);
    expect(Math.abs(baked - 0.2)).toBeLessThan(0.03);
    expect(await refusal(() => window.tvf.setStripes({ width: 1.5 }))).toMatch(/width must be a share of a period/);
    expect((await evaluate(() => window.tvf.setStripes({ width: null }))).width).toBe(0.5);
    // The Stripes panel's Line width slider goes through the same call, and shows the width in force.
    const slider = await evaluate(async () => {
      const input = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#stripes-width');
      const shown = input.value;
      input.value = '0.3';
      input.dispatchEvent(new Event('change'));
      await window.tvf.stripesIdle();
      return { shown, width: window.tvf.stripes().width };
    });
    expect(slider).toEqual({ shown: '0.5', width: 0.3 });
    // Across the field: the stripes turn a quarter. A row across the square crosses them at the asked frequency,
    // and the column down it none.
    const across = await evaluate(async () => {
      await window.tvf.setStripes({ across: true, width: null });
      return window.tvf.stripesIdle({ settled: true });
    });
    expect(across.across).toBe(true);
    await page.waitForTimeout(300);
    const turned = await readCanvasGrey(page);
    const [l, r] = await evaluate(() => [window.tvf.projectToScreen([0.2, 0.5, 0]), window.tvf.projectToScreen([0.8, 0.5, 0])]);
    const y = Math.round((l.y - turned.top) * turned.scale);
    const row = Array.from({ length: turned.w }, (_, x) => turned.grey[y * turned.w + x]);
    const xl = (l.x - turned.left) * turned.scale, xr = (r.x - turned.left) * turned.scale;
    const pxPerUnitX = Math.abs(xr - xl) / 0.6;
    const window_ = Math.round(pxPerUnitX / frequency);
    const inRow = crossings(row, Math.round(Math.min(xl, xr)), Math.round(Math.max(xl, xr)), window_);
    const measuredAcross = (inRow.length - 1) / 2 / ((inRow.at(-1) - inRow[0]) / pxPerUnitX);
    const inColumn = crossings(greyColumn(turned, (a.x - turned.left) * turned.scale), Math.round(Math.min(ya, yb)),
      Math.round(Math.max(ya, yb)), Math.round(pxPerUnit / frequency));
    console.log(`[ measured ] flat square across the field: ${inRow.length} transitions along a row, ` +
      `${measuredAcross.toFixed(3)} stripes per unit; ${inColumn.length} down the column`);
    expect(inRow.length).toBeGreaterThan(10);
    expect(Math.abs(measuredAcross - frequency)).toBeLessThan(0.01 * frequency);
    expect(inColumn.length).toBe(0);
  });

  test('on the default model: shown, following an edit, baked into the GLB; bad options refused by name', async () => {
    // WebGL buffers alive (created less deleted), to see that new patterns take the old ones' place.
    await page.addInitScript(() => {
      const count = (window.__glBuffers = { created: 0, deleted: 0 });
      const proto = WebGL2RenderingContext.prototype, create = proto.createBuffer, remove = proto.deleteBuffer;
      proto.createBuffer = function createBuffer() {
        count.created++;
        return create.call(this);
      };
      proto.deleteBuffer = function deleteBuffer(buffer) {
        count.deleted++;
        return remove.call(this, buffer);
      };
    });
    await page.reload();
    await page.waitForFunction(() => window.tvf && window.tvf.ready);
    await evaluate(() => window.tvf.ready);
    await evaluate(() => window.tvf.setViews({ arrows: false }));
    // The new model's vector field is zero: no direction to follow, so no pattern (the Stripes panel says so), and
    // none to bake.
    const before = await evaluate(() => window.tvf.setStripes({ visible: true }));
    expect(before.profile).toBe('stripes');
    expect(before.adaptSpacing).toBe(true);
    expect(before.stats.zeroField).toBe(true);
    expect(before.stats.families).toBe(0);
    expect(await evaluate(() => document.querySelector('tangent-field-designer').shadowRoot
      .querySelector('#stripes-status').textContent)).toMatch(/field is zero everywhere/);
    expect(await refusal(() => window.tvf.exportGlb({ size: 64, stripes: true }))).toMatch(/a field that is not zero/);
    // A stroke: a new field, and the stripes follow it (a new pattern of the new field version).
    const mesh = await evaluate(() => window.tvf.mesh());
    const faces = [0, 1, 2].map((k) => Math.floor(((k + 1) * mesh.triangles.length) / 3 / 4));
    await evaluate((faces) => window.tvf.addStroke(faces.map((face) => ({ face, bary: [1 / 3, 1 / 3, 1 / 3] }))), faces);
    const after = await evaluate(() => window.tvf.stripesIdle());
    expect(after.stats.fieldKey).not.toBe(before.stats.fieldKey);
    expect(after.stats.families).toBe(1);
    // Solved first where the field changed (or whole, where it changed on most of the model), then whole.
    expect(after.settled).toBe(!after.stats.localUpdate);
    const whole = await evaluate(() => window.tvf.stripesIdle({ settled: true }));
    console.log(`[ measured ] the stroke's stripes: local ${after.stats.localUpdate} (${after.stats.localVertices} ` +
      `vertices, ${after.stats.workerMs.toFixed(0)} ms), then whole (${whole.stats.workerMs.toFixed(0)} ms)`);
    expect(whole.settled).toBe(true);
    expect(whole.stats.localUpdate).toBe(false);
    expect(whole.stats.fieldKey).toBe(after.stats.fieldKey);
    expect(whole.stats.residual).toBeLessThan(1e-3);
    // The GLB bakes the stripes shown into its base colour: an image with both colours in it.
    const shades = await evaluate(async () => {
      const glb = await window.tvf.exportGlb({ size: 256 });
      const view = new DataView(glb.buffer, glb.byteOffset);
      const jsonLength = view.getUint32(12, true);
      const doc = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
      const bin = glb.subarray(20 + jsonLength + 8);
      const material = doc.materials[0].pbrMetallicRoughness;
      const image = doc.images[doc.textures[material.baseColorTexture.index].source];
      const bv = doc.bufferViews[image.bufferView];
      const bytes = bin.subarray(bv.byteOffset ?? 0, (bv.byteOffset ?? 0) + bv.byteLength);
      const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
      const c = new OffscreenCanvas(bitmap.width, bitmap.height);
      const ctx = c.getContext('2d');
      ctx.drawImage(bitmap, 0, 0);
      const data = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
      let light = 0, dark = 0, covered = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (data[i + 3] < 255) continue;
        covered++;
        if (Math.abs(data[i] - 0xec) + Math.abs(data[i + 1] - 0xe4) + Math.abs(data[i + 2] - 0xd4) < 12) light++;
        if (Math.abs(data[i] - 0x34) + Math.abs(data[i + 1] - 0x2c) + Math.abs(data[i + 2] - 0x28) < 12) dark++;
      }
      const primitive = doc.meshes[0].primitives[0];
      const phase = primitive.attributes[`TEXCOORD_${primitive.extras?.tangentFieldDesigner?.stripePhaseTexCoord}`];
      return { width: bitmap.width, light: light / covered, dark: dark / covered, phase };
    });
    console.log(`[ measured ] baked stripes: ${JSON.stringify(shades)}`);
    expect(shades.width).toBe(256);
    expect(shades.phase).toBeDefined(); // the phase goes with the baked colour, in the set the primitive names
    expect(shades.light).toBeGreaterThan(0.2);
    expect(shades.dark).toBeGreaterThan(0.2);
    // Six new patterns (six frequencies) drawn: each uploads into the buffers the last one had (10 bytes a
    // corner: 2.3 MB a pattern on bunny00's 75k faces, 25 MB on armadillo-sub2's 832k), where a new attribute
    // each time left the old buffers behind (two a pattern: 12 here, measured before the fix).
    const alive = () => evaluate(() => window.__glBuffers.created - window.__glBuffers.deleted);
    const frames = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await frames();
    const buffersBefore = await alive();
    for (const frequency of [3, 4, 5, 6, 7, 8]) {
      await evaluate((f) => window.tvf.setStripes({ frequency: f }), frequency);
      await evaluate(() => window.tvf.stripesIdle());
      await frames();
    }
    console.log(`[ measured ] WebGL buffers alive: ${buffersBefore} before six patterns, ${await alive()} after`);
    expect((await alive()) - buffersBefore).toBeLessThanOrEqual(1);
    // Refusals name the option and change nothing.
    expect(await refusal(() => window.tvf.setStripes({ profile: 'plaid' }))).toContain('plaid');
    expect(await refusal(() => window.tvf.setStripes({ frequency: -1 }))).toContain('frequency');
    expect(await refusal(() => window.tvf.setStripes({ light: 'red' }))).toContain('light');
    expect(await refusal(() => window.tvf.setStripes({ adaptSpacing: 'yes' }))).toContain('adaptSpacing');
    expect((await evaluate(() => window.tvf.stripes())).profile).toBe('stripes');
    // A cross field draws the profiles that use both its directions: stripes give way to a grid.
    await evaluate(() => window.tvf.setSymmetry(4));
    const cross = await evaluate(() => window.tvf.stripesIdle());
    expect(cross.profile).toBe('grid');
    expect(cross.stats.families).toBe(2);
    await evaluate(() => window.tvf.setStripes({ visible: false }));
  });

  // After an edit whose stripes came as a local update made ahead by the worker, the next edit's field is drawn
  // with its stripes in one frame (StripesController.followsWithin): no frame between the edit and the stripes'
  // arrival (unless they came after the deadline, twice the last edit's time), one with them. The first edit
  // after the stripes are shown (their first pattern is whole) has its field drawn first, as before. The budget
  // is raised to 2 s (debugStripesFollowMs) so that a loaded machine sees the wait too. The edits: the field at
  // a face asked to turn by 30 degrees, which moves it near that face only.
  test('an edit after a local update: its field and its stripes drawn in one frame', async () => {
    await evaluate(() => window.tvf.setSymmetry(2));
    // Vectors at faces spread over the model, each along the field there: the field's shape held, so that an
    // edit moves it near its face only (a local update; on the bare model it moves everywhere: a whole pattern).
    await evaluate(async () => {
      const t = window.tvf, nF = t.mesh().triangles.length / 3, vv = t.faceVectors();
      for (let k = 1; k <= 8; k++) {
        const face = Math.floor((k * nF) / 9);
        await t.addVector(face, [0, 1, 2].map((d) => vv[3 * face + d]));
      }
      await t.settled();
    });
    await evaluate(() => window.tvf.debugStripesFollowMs(2000));
    await evaluate(() => window.tvf.setStripes({ visible: true, profile: 'stripes' }));
    const edit = async (face) => {
      const turned = await fieldTurnedAt(page, face, Math.PI / 6);
      return evaluate(async ({ face, turned }) => {
        const t = window.tvf;
        const frames2 = () => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
        await frames2(); // a frame the last edit's whole pattern left asked for is drawn before the count starts
        const frames = t.debugRecordFrames();
        const t0 = performance.now();
        await t.addVector(face, turned);
        await t.settled();
        const { stats } = await t.stripesIdle();
        await frames2();
        const whole = (await t.stripesIdle({ settled: true })).stats; // the whole pattern, as when the edits pause
        return { t0, frames: frames.slice(), stats, wholeAt: whole.drawnAt - whole.drawMs };
      }, { face, turned });
    };
    await evaluate(() => window.tvf.stripesIdle({ settled: true }));
    const runs = [await edit(1200), await edit(2400), await edit(600)];
    await evaluate(() => window.tvf.debugStripesFollowMs(null));
    await evaluate(() => window.tvf.setStripes({ visible: false }));
    runs.forEach((r, k) => {
      const s = r.stats, repliedAt = s.drawnAt - s.drawMs, asked = s.drawnAt - s.roundTripMs;
      const quick = k > 0 && runs[k - 1].stats.localUpdate && runs[k - 1].stats.madeAhead;
      const early = r.frames.filter((x) => x < repliedAt);
      console.log(`[ measured ] ${JSON.stringify({ local: s.localUpdate, madeAhead: s.madeAhead, quick,
        waited: s.fieldFrameWaited, roundTripMs: Math.round(s.roundTripMs),
        vertices: s.localVertices, frames: r.frames.map((x) => Math.round(x - r.t0)),
        stripes: Math.round(s.drawnAt - r.t0) })}`);
      expect(s.fieldFrameWaited > 0, "the field's frame waited for its stripes").toBe(quick);
      if (quick) expect(early.filter((x) => x < asked + s.fieldFrameWaited - 5), 'frames before the stripes').toEqual([]);
      else expect(early.length, 'the field drawn first').toBeGreaterThan(0);
      expect(r.frames.some((x) => x >= repliedAt), 'the frame with the field and its stripes').toBe(true);
      // No frame drawn again after the stripes' own (viewer.requestRender leaves out one a renderNow drew).
      const beforeWhole = r.frames.filter((x) => x < r.wholeAt).length;
      const inTime = quick && s.roundTripMs < s.fieldFrameWaited;
      expect(beforeWhole, 'frames before the whole pattern').toBeLessThanOrEqual(inTime ? 1 : 2);
    });
    expect(runs.filter((r) => r.stats.fieldFrameWaited > 0).length, 'edits whose frame waited').toBeGreaterThan(0);
  });

  // On a torus a field at a constant angle to the parallels (the angle at which a meridian crosses 0.3 as many
  // stripes as a parallel) takes whole numbers of stripes round both loops only at some frequencies: the asked
  // one puts 20.6 and 6.2 there, and the core fits it (core/direction/stripe_loop_fit.h; the native test
  // StripeLoopFit.* checks the counts). The page reports the factor and says the frequency drawn.
  test('a torus: the frequency fitted to its loops is reported and shown', async () => {
    const [R, r, n, m] = [2, 0.7, 96, 48];
    const beta = Math.atan(r / (0.3 * Math.sqrt(R * R - r * r)));
    const v = [], f = [], constraints = [];
    for (let j = 0; j < m; j++)
      for (let i = 0; i < n; i++) {
        const [u, w] = [(2 * Math.PI * i) / n, (2 * Math.PI * j) / m];
        v.push(`${(R + r * Math.cos(w)) * Math.cos(u)} ${(R + r * Math.cos(w)) * Math.sin(u)} ${r * Math.sin(w)}`);
      }
    const id = (i, j) => (j % m) * n + (i % n);
    for (let j = 0; j < m; j++)
      for (let i = 0; i < n; i++) f.push(`3 ${id(i, j)} ${id(i + 1, j)} ${id(i + 1, j + 1)}`,
        `3 ${id(i, j)} ${id(i + 1, j + 1)} ${id(i, j + 1)}`);
    // Every face's field: cos(beta) along its parallel, sin(beta) along its meridian, at the quad's middle.
    for (let j = 0; j < m; j++)
      for (let i = 0; i < n; i++) {
        const [u, w] = [(2 * Math.PI * (i + 0.5)) / n, (2 * Math.PI * (j + 0.5)) / m];
        const parallel = [-Math.sin(u), Math.cos(u), 0];
        const meridian = [-Math.sin(w) * Math.cos(u), -Math.sin(w) * Math.sin(u), Math.cos(w)];
        const vector = parallel.map((x, k) => Math.cos(beta) * x + Math.sin(beta) * meridian[k]);
        const face = 2 * (j * n + i);
        constraints.push({ type: 'vector', face, vector }, { type: 'vector', face: face + 1, vector });
      }
    await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'torus.off', restore: false }),
      `OFF\n${v.length} ${f.length} 0\n${v.join('\n')}\n${f.join('\n')}\n`);
    await evaluate((design) => window.tvf.loadDesign(design, { ignoreFingerprint: true }),
      { symmetry: 2, constraints });
    const frequency = 20 / (2 * Math.PI * R * Math.sin(beta) * 0.97);
    const state = await evaluate((frequency) =>
      window.tvf.setStripes({ visible: true, frequency, profile: 'stripes' }), frequency);
    const { loopFit, fitMs } = state.stats;
    expect(loopFit, JSON.stringify(state.stats)).not.toBe(1);
    expect(Math.abs(loopFit - 1)).toBeLessThanOrEqual(0.05 + 1e-9);
    expect(fitMs).toBeGreaterThan(0);
    const status = () => evaluate(() => document.querySelector('tangent-field-designer').shadowRoot
      .querySelector('#stripes-status').textContent);
    await expect.poll(status).toContain(`${(frequency * loopFit).toPrecision(3)} per unit, fitted`);
    await evaluate(() => window.tvf.setStripes({ visible: false }));
  });

  test('a sphere: one stripe ends at each +1/2 of a line field, grid lines meet three to a junction at a +1/4',
    async () => {
      await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'ico5.off', restore: false }),
        icosphereOff(5));
      const positions = await evaluate(() => Array.from(window.tvf.mesh().positions));
      const at = (v) => positions.slice(3 * v, 3 * v + 3);
      const frequency = 8;
      // Looks at vertex v from 0.9 above the sphere; returns the canvas, v's pixel and the period in pixels.
      const lookAt = async (v) => {
        const q = at(v), u = q.map((x) => x / Math.hypot(...q));
        await evaluate(([position, target]) => window.tvf.setCamera({ position, target }), [u.map((x) => 1.9 * x), q]);
        await page.waitForTimeout(200);
        const t = Math.abs(u[2]) < 0.9 ? [u[1], -u[0], 0] : [0, u[2], -u[1]], tl = Math.hypot(...t);
        const [s0, s1] = await evaluate(([a, b]) => [window.tvf.projectToScreen(a), window.tvf.projectToScreen(b)],
          [q, q.map((x, k) => x + (0.1 * t[k]) / tl)]);
        const img = await readCanvasGrey(page);
        const period = (Math.hypot(s1.x - s0.x, s1.y - s0.y) * img.scale) / (0.1 * frequency);
        return { img, cx: (s0.x - img.left) * img.scale, cy: (s0.y - img.top) * img.scale, period };
      };
      // The vertex farthest from every singularity: where the stripes only run on.
      const calmest = (singular) => {
        let best = 0, bestD = -1;
        for (let v = 0; v < positions.length / 3; v++) {
          const d = Math.min(...singular.map((s) => Math.hypot(...at(v).map((x, k) => x - at(s.vertex)[k]))));
          if (d > bestD) [best, bestD] = [v, d];
        }
        return best;
      };
      // The stripes' own direction's turn round circles of 1 and 1.5 periods (window: 0.4 of a period).
      const turns = async (v, m) => {
        const { img, cx, cy, period } = await lookAt(v);
        const picture = { width: img.w, height: img.h, grey: img.grey };
        return [1, 1.5].map((R) => directionTurns(picture, cx, cy, R * period, 0.4 * period, m));
      };
      const whole = (list) => list.map((x) => Math.abs(x - Math.round(x)) < 0.2 ? Math.abs(Math.round(x)) : x);

      await evaluate(() => window.tvf.loadDesign({ symmetry: 2, constraints: [] }));
      await evaluate((frequency) => window.tvf.setStripes({ visible: true, frequency, profile: 'stripes',
        light: '#ffffff', dark: '#000000' }), frequency);
      await evaluate(() => window.tvf.setViews({ arrows: false, singularities: false }));
      const halves = await evaluate(() => window.tvf.singularities());
      expect(halves.map((s) => s.index)).toEqual([0.5, 0.5, 0.5, 0.5]);
      for (const s of halves) {
        const t = await turns(s.vertex, 2);
        console.log(`[ measured ] +1/2 at vertex ${s.vertex}: the stripes turn ${t.map((x) => x.toFixed(3))} (x pi)`);
        expect(whole(t)).toEqual([1, 1]);
      }
      const calmLines = await turns(calmest(halves), 2);
      console.log(`[ measured ] line field, where it is calm: the stripes turn ${calmLines.map((x) => x.toFixed(3))}`);
      expect(whole(calmLines)).toEqual([0, 0]);

      await evaluate(() => window.tvf.loadDesign({ symmetry: 4, constraints: [] }));
      const grid = await evaluate((frequency) => window.tvf.setStripes({ frequency, profile: 'grid' }), frequency);
      expect(grid.stats.families).toBe(2);
      const quarters = await evaluate(() => window.tvf.singularities());
      expect(quarters.map((s) => s.index)).toEqual(Array(8).fill(0.25));
      for (const s of quarters) {
        const t = await turns(s.vertex, 4);
        console.log(`[ measured ] +1/4 at vertex ${s.vertex}: the grid turns ${t.map((x) => x.toFixed(3))} (x pi/2)`);
        expect(whole(t)).toEqual([1, 1]);
      }
      const calmGrid = await turns(calmest(quarters), 4);
      console.log(`[ measured ] cross field, where it is calm: the grid turns ${calmGrid.map((x) => x.toFixed(3))}`);
      expect(whole(calmGrid)).toEqual([0, 0]);
      await evaluate(() => window.tvf.setStripes({ visible: false }));
    });
});
