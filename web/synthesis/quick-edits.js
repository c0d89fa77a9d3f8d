// SPDX-License-Identifier: GPL-2.0-or-later
// When a field change is a quick edit (controller.js fieldChanged): the texture follows quick edits with a
// preview (one level short of the finest, a quarter of the work) and is made in full once they stop for
// QUICK_EDIT_MS; any other change gets the full texture at once. Owns nothing.
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
