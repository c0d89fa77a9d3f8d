// The Stripes panel's controller (web/stripes/controller.js) against a worker stand-in: a pattern the worker
// abandoned for a newer request ({interrupted: true}: an edit, an export, a texture step went first) is asked
// for again at once, of the field drawn then, and shown; a reply for a field that is no longer drawn is not
// shown. The model's drawing is replaced by a recorder (the WebGL side is the page tests').
import assert from 'node:assert/strict';
import test from 'node:test';
import { StripesController } from '../../web/stripes/controller.js';
import { icosphere, surfaceOf } from './fakes.mjs';

const pattern = (version) => ({
  families: 1,
  phase: new Float32Array(6),
  branch: new Int8Array(6),
  stats: { version },
});

function controllerWith(replies) {
  const surface = surfaceOf(icosphere(1));
  let field = { version: 1, component: 'whole', key: 'k1', symmetry: 2, surface };
  const asked = [];
  const controller = new StripesController({
    viewer: {},
    call: async (op, [version]) => {
      asked.push(version);
      return replies.shift()?.(version) ?? pattern(version);
    },
    getField: () => field,
  });
  const shown = [];
  controller.model = {
    setGeometry: async () => {},
    setPattern: (reply) => shown.push(reply.stats.version),
    setStyle: () => {},
    setVisible: () => {},
    dispose: () => {},
  };
  return { controller, asked, shown, setField: (f) => (field = { ...field, ...f }) };
}

test('an interrupted pattern is asked for again and shown', async () => {
  const { controller, asked, shown } = controllerWith([() => ({ interrupted: true })]);
  const state = await controller.setStripes({ visible: true });
  assert.deepEqual(asked, [1, 1], 'asked twice: the interrupted ask, then again');
  assert.deepEqual(shown, [1]);
  assert.equal(state.stats.version, 1);
});

test('an interruption by an edit asks for the new field', async () => {
  const fixture = controllerWith([]);
  const { controller, asked, shown, setField } = fixture;
  // The first ask is interrupted by an edit whose field is drawn by the time the reply comes.
  fixture.controller.call = async (op, [version]) => {
    asked.push(version);
    if (asked.length === 1) {
      setField({ version: 2, key: 'k2' });
      return { interrupted: true };
    }
    return pattern(version);
  };
  await controller.setStripes({ visible: true });
  assert.deepEqual(asked, [1, 2]);
  assert.deepEqual(shown, [2]);
});

// An edit's local update (the core solved where the field changed: stats.localUpdate) is shown at once and
// followed by the whole pattern of the same field, asked for with localUpdate false: once the edits pause, or
// at once for whenIdle({settled: true}) (the export bakes that one).
test('a local update is followed by the whole pattern', async () => {
  const { controller, shown } = controllerWith([]);
  const options = [];
  controller.call = async (op, [version, , asked]) => {
    options.push(asked.localUpdate);
    return { ...pattern(version), stats: { version, localUpdate: asked.localUpdate !== false } };
  };
  await controller.setStripes({ visible: true });
  assert.equal(controller.state().settled, false, 'a local update shown');
  const state = await controller.whenIdle({ settled: true });
  assert.equal(state.settled, true);
  assert.deepEqual(options, [undefined, false], 'then the whole pattern, of the same field');
  assert.deepEqual(shown, [1, 1]);
  await controller.whenIdle({ settled: true });
  assert.equal(options.length, 2, 'nothing more to settle');
  controller.dispose();
});

test('the whole pattern follows by itself once the edits pause', async () => {
  const { controller, shown, setField } = controllerWith([]);
  const options = [];
  controller.call = async (op, [version, , asked]) => {
    options.push(asked.localUpdate);
    return { ...pattern(version), stats: { version, localUpdate: asked.localUpdate !== false } };
  };
  await controller.setStripes({ visible: true });
  setField({ version: 2, key: 'k2' }); // an edit before the pause: its own local update, the settle later
  controller.fieldChanged();
  await controller.whenIdle();
  assert.deepEqual(shown, [1, 2]);
  await new Promise((resolve) => setTimeout(resolve, 600));
  await controller.whenIdle();
  assert.deepEqual(shown, [1, 2, 2]);
  assert.deepEqual(options, [undefined, undefined, false]);
  assert.equal(controller.state().settled, true);
  controller.dispose();
});

// The field's frame waits for its stripes (followsWithin, asked by view-sync.js before it draws a field change)
// only after an edit whose stripes came as a local update made ahead by the worker, for twice the time that
// took (at most the budget), whether the whole pattern settled since or not; never for the field already shown,
// while an update is in flight, for a preview field, after a whole pattern alone or one not made ahead, or after
// a slow edit.
test("the field's frame waits for its stripes after a quick local update made ahead", async () => {
  const { controller, setField } = controllerWith([]);
  let reply = { localUpdate: true, madeAhead: true }, delay = 5;
  controller.call = async (op, [version, , asked]) => {
    await new Promise((resolve) => setTimeout(resolve, delay));
    const whole = asked.localUpdate === false;
    return { ...pattern(version), stats: { version, ...(whole ? { localUpdate: false } : reply) } };
  };
  const edit = async (version) => {
    setField({ version, key: `k${version}` });
    const wait = controller.followsWithin();
    controller.fieldChanged();
    await controller.whenIdle();
    return wait;
  };
  reply = { localUpdate: false };
  await controller.setStripes({ visible: true }); // a first pattern: whole
  assert.equal(await edit(2), 0, 'after a whole pattern: drawn at once');
  reply = { localUpdate: true, madeAhead: true };
  assert.equal(await edit(3), 0, 'the edit before was whole');
  const took = controller.state().stats.roundTripMs;
  assert.ok(took > 0);
  assert.equal(controller.followsWithin(), 0, 'the field shown already: nothing to wait for');
  const wait = await edit(4);
  assert.ok(Math.abs(wait - 2 * took) < 1e-9, `twice the last edit's time (${wait} for ${took})`);
  assert.equal(controller.state().stats.fieldFrameWaited, wait, 'the stripes say how long their field could wait');
  await controller.whenIdle({ settled: true });
  assert.ok((await edit(5)) > 0, 'after the whole pattern settled, the next edit still waits');
  setField({ version: 6, key: 'k6' });
  controller.fieldChanged();
  assert.equal(controller.followsWithin(), 0, 'an update in flight');
  await controller.whenIdle();
  reply = { localUpdate: true, madeAhead: false };
  await edit(7);
  assert.equal(await edit(8), 0, 'the edit before was not made ahead');
  reply = { localUpdate: true, madeAhead: true };
  delay = 300;
  await edit(9);
  assert.equal(await edit(10), 0, 'the edit before took longer than the budget');
  delay = 5;
  controller.followMs = 1000; // a test's budget (debugStripesFollowMs)
  await edit(11);
  assert.ok((await edit(12)) > 0);
  setField({ version: 13, key: 'k13', preview: true });
  assert.equal(controller.followsWithin(), 0, "a big model's preview field: its stripes come with the exact one");
  await controller.setStripes({ visible: false });
  setField({ version: 14, key: 'k14', preview: false });
  assert.equal(controller.followsWithin(), 0, 'hidden');
  controller.dispose();
});

// The lines' width is how the phase is drawn: a width asked for (or the profile's own) goes to the model's style
// and to the export, and no new pattern is asked for; a width outside (0, 1] is refused before anything changes.
test('a line width restyles the pattern shown without asking for another', async () => {
  const { controller, asked } = controllerWith([]);
  const styles = [];
  controller.model.setStyle = (style) => styles.push(style);
  let state = await controller.setStripes({ visible: true, profile: 'stripes' });
  assert.equal(state.width, 0.5, "the stripes' own width");
  state = await controller.setStripes({ width: 0.2 });
  assert.equal(state.width, 0.2);
  assert.deepEqual(asked, [1], 'one pattern for both');
  assert.equal(styles.at(-1).width, 0.2);
  await assert.rejects(controller.setStripes({ width: 0 }), /width must be a share of a period/);
  await assert.rejects(controller.setStripes({ width: 1.5, profile: 'grid' }), /width must be a share of a period/);
  assert.equal(controller.state().profile, 'stripes', 'a refused call changes nothing');
  assert.equal((await controller.exportStripes()).width, 0.2);
  state = await controller.setStripes({ width: null, profile: 'grid' });
  assert.equal(state.width, 0.12, "the grid's own width");
  assert.equal(styles.at(-1).width, 0.12);
});

// Across the field changes the pattern (the core computes it of the field turned a quarter): a new one is asked for
// with across in its options; a cross field has both directions, so it asks for nothing new there.
test('stripes across the field ask for a new pattern, except of a cross field', async () => {
  const { controller, setField } = controllerWith([]);
  const options = [];
  controller.call = async (op, [version, , asked]) => {
    options.push(asked.across);
    return pattern(version);
  };
  await controller.setStripes({ visible: true });
  let state = await controller.setStripes({ across: true });
  assert.equal(state.across, true);
  assert.deepEqual(options, [false, true]);
  await assert.rejects(controller.setStripes({ across: 'yes' }), /across must be true or false/);
  setField({ version: 2, key: 'k2', symmetry: 4 });
  state = await controller.setStripes({ profile: 'grid' });
  assert.equal(state.across, false, 'a cross field has both directions');
  assert.deepEqual(options, [false, true, false]);
  await controller.setStripes({ across: false });
  assert.deepEqual(options, [false, true, false], 'nothing new to ask for');
});

// A field zero everywhere has no direction to follow: the worker says so, the pattern shown goes (the surface
// shows), nothing is baked, and the next field's pattern shows again.
test('a zero field shows no pattern and bakes none', async () => {
  const { controller, shown, setField } = controllerWith([() => ({ zeroField: true })]);
  let cleared = 0;
  controller.model.clearPattern = () => cleared++;
  let state = await controller.setStripes({ visible: true });
  assert.equal(state.stats.zeroField, true);
  assert.equal(state.stats.families, 0);
  assert.equal(cleared, 1);
  assert.deepEqual(shown, []);
  assert.equal(await controller.exportStripes(), null);
  setField({ version: 2, key: 'k2' });
  state = await controller.whenIdle({ settled: true }).then(() => controller.update()).then(() => controller.state());
  assert.equal(state.stats.zeroField, undefined);
  assert.deepEqual(shown, [2]);
});
