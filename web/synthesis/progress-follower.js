// SPDX-License-Identifier: GPL-2.0-or-later
// How the Texture panel's progress bar follows a synthesis run (controller.js). Owns nothing.

// A run that ends within this many ms shows no bar at all: with software GL each change of the panel is a raster
// and a read-back of its tiles in the GPU process (15-32 ms a change for bunny00's side panel), which a stroke's
// texture update (~100 ms, three changes: the bar, a step, the stats) waited for.
export const BAR_DELAY_MS = 200;

// The panel follows the progress once the run has lasted delayMs (then at once), at most ten times a second
// (every change of it is a frame the GPU draws beside the synthesis), the first step past 0 at once, and a change
// held back by that limit when the limit ends: a long wait (the field's raster, a slow slice) must not leave the
// bar behind. current(): {fraction} or null; show(): the panel's update. Returns follow(), with follow.stop() for
// the run's end.
export function progressFollower(current, show, { delayMs = 0 } = {}) {
  let shown = 0, shownAt = -Infinity, timer = null, due = delayMs <= 0;
  const percent = () => Math.floor(100 * (current()?.fraction ?? 0));
  const showNow = () => {
    shown = percent();
    shownAt = performance.now();
    show();
  };
  const reveal = due ? null : setTimeout(() => {
    due = true;
    if (current()) showNow();
  }, delayMs);
  const follow = () => {
    if (!due || !current() || percent() === shown || timer) return;
    const wait = shown === 0 ? 0 : shownAt + 100 - performance.now();
    if (wait <= 0) showNow();
    else
      timer = setTimeout(() => {
        timer = null;
        if (current() && percent() !== shown) showNow();
      }, wait);
  };
  follow.stop = () => {
    clearTimeout(timer);
    clearTimeout(reveal);
  };
  return follow;
}
