// SPDX-License-Identifier: GPL-2.0-or-later
// The one element builder the panels that build their own markup share (export/panel.js,
// synthesis/panel.js): at the root of web/ so that every layer may use it.

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
