// SPDX-License-Identifier: GPL-2.0-or-later
// Stripe patterns on the page (docs/stripes.md): the options (frequency, profile, spacing by magnitude, colours),
// whether the stripes are shown, and when the core's pattern is asked for — once per field version the views
// draw while they are shown, the newest field winning when edits come faster than patterns; an edit's first
// solved where its field changed, the whole pattern of it asked for once the edits pause. The pattern itself
// is the core's (core/design/design_stripes.h), made in the worker (worker-ops.js) and drawn by stripe-model.js.
// Owns its StripeModel; imports views/ (through stripe-model.js) and its own folder.
import { DEFAULT_WIDTHS, PROFILES, TWO_FAMILY_PROFILES } from './profiles.js';
import { StripeModel } from './stripe-model.js';

const DEFAULT_LIGHT = 0xece4d4;
const DEFAULT_DARK = 0x342c28;
// An edit's pattern is first solved where its field changed (the core's local update: the stripes elsewhere stay
// put); the whole pattern, the energy's eigenvector, follows once the edits pause this long.
const SETTLE_MS = 400;
// Up to this many faces the stripes are drawn at once, in the task that takes them, as a field is (view-sync.js):
// bunny00's (75k faces) upload and frame take that task 2-4 ms. A bigger model's go to the next animation frame,
// a task of their own (armadillo-sub2's 832k faces: 20 MB of corner attributes).
const DRAW_AT_ONCE_FACES = 200_000;
// A field change whose stripes follow it within this many ms (the last edit's) is drawn with them (followsWithin).
const FOLLOW_MS = 250;
// Default spacing: this many stripes across the model's bounding-box diagonal, but no period under four mean
// edge lengths (a narrower one is more than the mesh can show).
const STRIPES_PER_DIAGONAL = 40;
const MIN_PERIOD_EDGES = 4;

const twoSignificant = (x) => Number(x.toPrecision(2));
const hex = (c) => `#${c.toString(16).padStart(6, '0')}`;

function colourOf(value, what) {
  if (typeof value === 'number' && Number.isInteger(value) && value >= 0 && value <= 0xffffff) return value;
  if (typeof value === 'string' && /^#[0-9a-f]{6}$/i.test(value)) return parseInt(value.slice(1), 16);
  throw new Error(`setStripes: ${what} must be a colour '#rrggbb' (got ${JSON.stringify(value)})`);
}

// The default frequency (stripes per unit length) of a Surface.
export function defaultFrequency(surface) {
  const p = surface.positions, lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3)
    for (let c = 0; c < 3; c++) {
      lo[c] = Math.min(lo[c], p[i + c]);
      hi[c] = Math.max(hi[c], p[i + c]);
    }
  const diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  return twoSignificant(Math.min(STRIPES_PER_DIAGONAL / diagonal, 1 / (MIN_PERIOD_EDGES * (surface.meanEdge || 1))));
}

export class StripesController {
  // viewer: the page's Viewer; call(op, args): the worker's op, resolving to its value (null when the field
  // version asked for is no longer the worker's); notify(message): a word for the worker outside its requests
  // (stripes/worker-ops.js makes each edit's stripes ahead until told the page no longer shows them);
  // getField(): {version, component, key, symmetry, surface, preview} of
  // the field the views draw, or null; onChange(): the state changed (the panel redraws); onError(err);
  // onShow(shown): the stripes are about to show (true), or have just gone (false): another stand-in for the
  // surface (the synthesized texture) makes way or comes back.
  constructor({
    viewer, call, notify = () => {}, getField, onChange = () => {}, onError = () => {}, onShow = () => {},
  }) {
    this.viewer = viewer;
    this.call = call;
    this.notify = notify;
    this.getField = getField;
    this.onChange = onChange;
    this.onError = onError;
    this.onShow = onShow;
    this.model = new StripeModel(viewer);
    this.options = {
      frequency: null, profile: null, magnitudeSpacing: 0, adaptSpacing: true, across: false, width: null,
      light: DEFAULT_LIGHT, dark: DEFAULT_DARK,
    };
    this.visible = false;
    this.surface = null; // the Surface the model's geometry was built from
    this.shown = null; // what the stripes on screen are of: their field's key, component and options, as JSON
    this.stats = null;
    this.error = null;
    this.running = null; // the update in flight
    this.again = false;
    this.settled = true; // the stripes shown are a whole pattern, not an edit's local update
    this.settleTimer = null;
    this.settleNow = false; // the next update makes the whole pattern of the stripes shown
    this.frameWaited = 0; // ms the last field change's frame could wait for its stripes (followsWithin)
    this.localFollowMs = null; // the last edit's local update made ahead: from the page's request to its frame
  }

  // The options in force: the frequency and profile the model and field choose when none was set.
  effective() {
    const f = this.getField();
    const symmetry = f?.symmetry ?? 1;
    let profile = this.options.profile ?? (symmetry === 4 ? 'grid' : 'stripes');
    if (symmetry === 4 && !TWO_FAMILY_PROFILES.includes(profile)) profile = 'grid';
    const frequency = this.options.frequency ?? (f ? defaultFrequency(f.surface) : 1);
    const magnitudeSpacing = symmetry === 1 ? this.options.magnitudeSpacing : 0;
    const across = symmetry !== 4 && this.options.across; // a cross field's grid has both directions
    return { frequency, profile, magnitudeSpacing, adaptSpacing: this.options.adaptSpacing, across };
  }

  // The lines' width drawn: the one asked for, or the profile's own. Only how the phase is drawn, so it is not in
  // effective() (whose options the pattern is computed with).
  width() {
    return this.options.width ?? DEFAULT_WIDTHS[this.effective().profile];
  }

  state() {
    const { frequency, profile, magnitudeSpacing, adaptSpacing, across } = this.effective();
    return {
      visible: this.visible,
      frequency,
      profile,
      magnitudeSpacing,
      adaptSpacing,
      across,
      width: this.width(),
      light: hex(this.options.light),
      dark: hex(this.options.dark),
      stats: this.stats ? { ...this.stats } : null,
      settled: this.settled,
      error: this.error,
    };
  }

  // opts: any of {visible, frequency (> 0, or null: the default), profile, magnitudeSpacing (0..1), adaptSpacing,
  // across (a vector or line field's stripes across it), width (0 < width <= 1: the lines' share of a period, or
  // null: the profile's own), light, dark}; checked before anything changes. Resolves with state() once the stripes
  // shown are of these options.
  async setStripes(opts = {}) {
    const next = { ...this.options };
    if ('frequency' in opts) {
      const f = opts.frequency;
      if (f !== null && !(typeof f === 'number' && f > 0 && Number.isFinite(f)))
        throw new Error(`setStripes: frequency must be a positive number of stripes per unit length (got ${f})`);
      next.frequency = f;
    }
    if ('profile' in opts) {
      if (opts.profile !== null && !PROFILES.includes(opts.profile))
        throw new Error(`setStripes: unknown profile ${JSON.stringify(opts.profile)}; one of ${PROFILES.join(', ')}`);
      next.profile = opts.profile;
    }
    if ('magnitudeSpacing' in opts) {
      const m = opts.magnitudeSpacing;
      if (!(typeof m === 'number' && m >= 0 && m <= 1))
        throw new Error(`setStripes: magnitudeSpacing must be a number in [0, 1] (got ${m})`);
      next.magnitudeSpacing = m;
    }
    if ('adaptSpacing' in opts) {
      if (typeof opts.adaptSpacing !== 'boolean')
        throw new Error(`setStripes: adaptSpacing must be true or false (got ${JSON.stringify(opts.adaptSpacing)})`);
      next.adaptSpacing = opts.adaptSpacing;
    }
    if ('across' in opts) {
      if (typeof opts.across !== 'boolean')
        throw new Error(`setStripes: across must be true or false (got ${JSON.stringify(opts.across)})`);
      next.across = opts.across;
    }
    if ('width' in opts) {
      const w = opts.width;
      const what = "a share of a period in (0, 1], or null for the profile's own";
      if (w !== null && !(typeof w === 'number' && w > 0 && w <= 1))
        throw new Error(`setStripes: width must be ${what} (got ${w})`);
      next.width = w;
    }
    if ('light' in opts) next.light = colourOf(opts.light, 'light');
    if ('dark' in opts) next.dark = colourOf(opts.dark, 'dark');
    this.options = next;
    const wasVisible = this.visible;
    if ('visible' in opts) this.visible = !!opts.visible;
    this.#style();
    if (this.visible && !wasVisible) this.onShow(true);
    this.model.setVisible(this.visible);
    if (!this.visible && wasVisible) {
      this.notify({ stripesUnfollow: true });
      this.onShow(false);
    }
    this.onChange();
    if (this.visible) await this.update();
    return this.state();
  }

  // How long (ms) the view's frame of a field change about to be drawn may wait for its stripes, so that both show
  // in one frame (0: drawn at once; the stripes' own frame draws it, view-sync.js). With software GL each frame
  // is rasterized on the CPU, and the stripes' frame came after the field's: a bunny00 stroke's stripes were on
  // screen 127-156 ms after it, 81-114 ms with one frame for both (docs/stripes.md). Only for a new field while
  // nothing is in flight (not a big model's preview, whose stripes come with the exact field), when the last
  // edit's stripes came as a local update made ahead by the worker within FOLLOW_MS (this.followMs, a test's)
  // of their request (the next edit's likely come alike, whether the whole pattern settled between them or
  // not): twice that. Asked before the change is drawn.
  followsWithin() {
    this.frameWaited = 0;
    const field = this.getField(), t = this.stats, took = this.localFollowMs, budget = this.followMs ?? FOLLOW_MS;
    if (!this.visible || this.running || !field || !t || this.error || took === null || !(took < budget)) return 0;
    if (this.surface !== field.surface || t.fieldKey === field.key || field.preview) return 0;
    return (this.frameWaited = Math.min(budget, 2 * took));
  }

  // The field drawn changed (a new version or another component): new stripes when they are shown.
  fieldChanged() {
    if (this.visible) this.update().catch((err) => this.onError(err));
  }

  // Another model: its geometry is built on the next update.
  modelChanged() {
    this.notify({ stripesUnfollow: true });
    this.shown = null;
    this.stats = null;
    this.localFollowMs = null;
    if (this.visible) this.update().catch((err) => this.onError(err));
  }

  // Brings the stripes up to the field drawn and the options; one update at a time, the newest state winning.
  update() {
    if (this.running) {
      this.again = true;
      return this.running;
    }
    this.running = (async () => {
      try {
        do {
          this.again = false;
          await this.#updateOnce();
        } while (this.again && this.visible);
      } finally {
        this.running = null;
      }
    })();
    return this.running;
  }

  async #updateOnce() {
    const field = this.getField();
    if (!field || !this.visible) return;
    if (this.surface !== field.surface) {
      this.surface = field.surface;
      this.shown = null;
      await this.model.setGeometry(field.surface);
    }
    const options = this.effective();
    const wanted = JSON.stringify([field.key, field.component, options]);
    const settling = this.shown === wanted;
    if (settling && (this.settled || !this.settleNow)) return;
    this.#cancelSettle();
    const t0 = performance.now(), fieldFrameWaited = this.frameWaited;
    this.frameWaited = 0;
    let reply;
    try {
      const asked = settling ? { ...options, localUpdate: false } : options;
      reply = await this.call('stripes', [field.version, field.component, asked]);
    } catch (err) {
      this.error = err.message;
      this.onChange();
      throw err;
    }
    if (this.getField()?.key !== field.key || this.surface !== field.surface) {
      this.again = true; // another field came meanwhile
      return;
    }
    if (reply?.interrupted) {
      this.again = true; // a newer request went first (an edit, an export): asked again, of the field then
      return;
    }
    if (!reply) return; // the worker is not at this version (yet): its field's change asks again
    if (reply.zeroField) return this.#showZeroField(wanted, field.key);
    const repliedAt = performance.now();
    this.#style();
    this.model.setPattern(reply);
    const drawnAt = await this.#draw(reply.branch.length / 6);
    this.shown = wanted;
    this.settled = !reply.stats?.localUpdate;
    this.settleNow = false;
    if (!this.settled) this.#scheduleSettle();
    this.error = null;
    const roundTripMs = drawnAt - t0, drawMs = drawnAt - repliedAt;
    if (!settling) this.localFollowMs = reply.stats?.localUpdate && reply.stats.madeAhead ? roundTripMs : null;
    // fieldFrameWaited: ms the field's frame could wait for these stripes (0: it was drawn first).
    this.stats = { ...reply.stats, fieldKey: field.key, roundTripMs, drawMs, drawnAt, fieldFrameWaited };
    this.onChange();
  }

  // A field that is zero everywhere has no direction to follow: no pattern is shown (the surface is), and the
  // status says why, until a field with one comes.
  #showZeroField(wanted, fieldKey) {
    this.model.clearPattern();
    this.shown = wanted;
    this.settled = true;
    this.settleNow = false;
    this.error = null;
    this.stats = { zeroField: true, families: 0, fieldKey };
    this.onChange();
  }

  // Draws the pattern just set; resolves to when its frame was issued (performance.now()).
  #draw(faces) {
    const { viewer } = this;
    if (faces <= DRAW_AT_ONCE_FACES || !viewer.afterRender || viewer.disposed) {
      viewer.renderNow?.();
      return performance.now();
    }
    const drawn = new Promise((resolve) => viewer.afterRender.push(resolve));
    viewer.requestRender();
    return drawn;
  }

  // Resolves once no update is in flight (tests, benchmarks); with `settled`, once the stripes shown are a whole
  // pattern (an edit's local update is followed by it at once).
  async whenIdle({ settled = false } = {}) {
    for (;;) {
      while (this.running) await this.running.catch(() => {});
      if (!settled || this.settled || !this.visible || this.error) return this.state();
      this.#cancelSettle();
      this.settleNow = true;
      await this.update().catch(() => {});
      if (this.settleNow) return this.state(); // nothing to settle: the field is no longer the one shown
    }
  }

  // The whole pattern of the stripes shown, once the edits have paused.
  #scheduleSettle() {
    this.#cancelSettle();
    this.settleTimer = setTimeout(() => {
      this.settleTimer = null;
      this.settleNow = true;
      if (this.visible) this.update().catch((err) => this.onError(err));
    }, SETTLE_MS);
  }

  #cancelSettle() {
    clearTimeout(this.settleTimer);
    this.settleTimer = null;
  }

  // What the one GLB export bakes into the base colour when the stripes are shown: the options the worker
  // draws the core's current pattern with (core-export.js), after bringing it up to the field.
  async exportStripes() {
    if (!this.visible) return null;
    await this.update();
    await this.whenIdle({ settled: true });
    if (this.stats?.zeroField) return null; // nothing to bake
    const { profile } = this.effective();
    const rgb = (c) => [(c >> 16) & 255, (c >> 8) & 255, c & 255];
    return { profile, width: this.width(), light: rgb(this.options.light), dark: rgb(this.options.dark) };
  }

  #style() {
    const { profile } = this.effective();
    this.model.setStyle({ profile, width: this.width(), light: this.options.light, dark: this.options.dark });
  }

  dispose() {
    this.notify({ stripesUnfollow: true });
    this.visible = false;
    this.#cancelSettle();
    this.model.dispose();
  }
}
