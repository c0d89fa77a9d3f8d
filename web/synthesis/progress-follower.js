// SPDX-License-Identifier: GPL-2.0-or-later
// How the Texture panel's progress bar follows a synthesis run (controller.js). Owns nothing.

// The panel follows the progress at most ten times a second (every change of it is a frame the GPU draws beside
// the synthesis), the first step past 0 at once, and a change held back by that limit when the limit ends: a
// long wait (the field's raster, a slow slice) must not leave the bar behind. current(): {fraction} or null;
// show(): the panel's update. Returns follow(), with follow.stop() for the run's end.
export function progressFollower(current, show) {
  let shown = 0, shownAt = -Infinity, timer = null;
  const percent = () => Math.floor(100 * (current()?.fraction ?? 0));
  const showNow = () => {
    shown = percent();
    shownAt = performance.now();
    show();
  };
  const follow = () => {
    if (!current() || percent() === shown || timer) return;
    const wait = shown === 0 ? 0 : shownAt + 100 - performance.now();
    if (wait <= 0) showNow();
    else
      timer = setTimeout(() => {
        timer = null;
        if (current() && percent() !== shown) showNow();
      }, wait);
  };
  follow.stop = () => clearTimeout(timer);
  return follow;
}
