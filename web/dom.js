// SPDX-License-Identifier: GPL-2.0-or-later
// The one element builder the panels that build their own markup share (export/panel.js,
// synthesis/panel.js), the canvases synthesis draws into off screen, and counts written for people: at the root
// of web/ so that every layer may use them. Imports nothing.

// el('button', {id, text, class, ...attributes}, ...children): `text` sets the text, `class` the class list,
// everything else is an attribute.
export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'text') e.textContent = v;
    else if (k === 'class') e.className = v;
    else e.setAttribute(k, v);
  }
  e.append(...children);
  return e;
}

// e's text, written only when it changes: writing the same text again replaces its text node, a layout and paint
// of its panel (with software GL a raster and read-back of the panel's tiles in the GPU process, 15-32 ms for the
// side panel, which a stroke's texture update waited for).
export function setText(e, text) {
  if (e.textContent !== text) e.textContent = text;
}

// A <canvas> element of width × height pixels.
export function canvasElement(width, height) {
  const c = document.createElement('canvas');
  c.width = width;
  c.height = height;
  return c;
}

// A canvas of width × height pixels for drawing off screen: an OffscreenCanvas where there is one (a worker has
// no document), a <canvas> element otherwise.
export function scratchCanvas(width, height) {
  return typeof OffscreenCanvas !== 'undefined' ? new OffscreenCanvas(width, height) : canvasElement(width, height);
}

// 832000 → "832,000" (a whole number, rounded). Not toLocaleString: its first call loads the locale's data, a
// 72 ms task in the middle of a big model's load, and 182 ms when armadillo-sub2's quad mesh arrived (profiles of
// the page).
export const grouped = (n) => String(Math.round(n)).replace(/\B(?=(\d{3})+(?!\d))/g, ',');
