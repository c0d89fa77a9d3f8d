// SPDX-License-Identifier: GPL-2.0-or-later
// When a field change is a quick edit (controller.js fieldChanged): the texture follows quick edits with a
// preview (one level short of the finest, a quarter of the work) and is made in full once they stop for
// QUICK_EDIT_MS; any other change gets the full texture at once, and may have the view's frame of the field wait
// for it (followsWithin). Owns nothing.
import { FIELD_UPLOAD_PHASE } from './phase-clock.js';

export const QUICK_EDIT_MS = 400;

// c: the controller (runsQueued, pendingField, settleTimer, lastFieldChange). A change is quick while something is
// dragged (interactive), or when it comes within QUICK_EDIT_MS of the change before and the texture has not
// caught up with that one yet (its run, or its settle, still to come). A change after the texture caught up is
// on its own however soon it came: on a real GPU a stroke's texture took 0.12 s, and strokes drawn 0.15 s apart
// waited 0.43 s more for a settle timer. The exact field of a big model landing after its preview never is.
export function isQuickEdit(c, { interactive, landing, now }) {
  if (interactive) return true;
  if (landing) return false;
  const behind = c.runsQueued > 0 || c.pendingField || c.settleTimer !== null;
  return behind && now - c.lastFieldChange < QUICK_EDIT_MS;
}

// A field change whose texture follows it within this many ms (its last update's time) is shown with it.
export const FOLLOW_MS = 250;

// How long (ms) the view's frame of a field change about to be drawn may wait for its texture, so that both show
// in one frame (0: drawn at once). With software GL each frame of a textured model costs the GPU process 45-60 ms
// that the texture's update then waited for; on a GPU the wait is the update's own few milliseconds. Only a change
// on its own (the texture caught up), answered by a local update like the last one, which took under FOLLOW_MS
// (c.followMs where a test set another): twice that update's time. After a whole texture the next run is local
// with no time of its own to go by: half the budget (bunny00 with software GL: the first stroke after its texture
// waited 58-82 ms for the field's frame, then took 178-206 ms in all against 84-136 for the third to sixth),
// unless the whole run's field upload, which a local run makes again, took over a quarter of it (armadillo-sub2:
// 204 ms, its updates 0.5 s; bunny00 27 ms). Never for a big model's preview field (c.isPreviewField()): its
// exact field follows, and its texture later.
export function followsWithin(c) {
  if (!c.active || !c.options.autoUpdate || !c.stats || c.stats.preview || c.isPreviewField?.()) return 0;
  const behind = c.runsQueued > 0 || c.pendingField || c.settleTimer !== null;
  const version = c.getFieldVersion();
  if (behind || version === undefined || version === c.lastFieldVersion) return 0;
  const budget = c.followMs ?? FOLLOW_MS;
  if (!c.stats.local) return c.stats.localNext && wholeUpload(c.stats) < budget / 4 ? budget / 2 : 0;
  const took = c.stats.wallMs;
  return took < budget ? Math.min(budget, 2 * took) : 0;
}

// A whole run's time taking the field to the GPU (its phase; Infinity where it was not timed).
const wholeUpload = (stats) => stats.phases?.[FIELD_UPLOAD_PHASE] ?? Infinity;
