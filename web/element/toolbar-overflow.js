// One toolbar row on a wide element: where the row does not wrap (element.css: wider than 900 px), whatever
// does not fit goes into the ⋯ menu, in the order of its data-overflow rank, lowest first: the brand (only
// hidden, and placed as if the widest tool options showed, so it does not come and go as tools are chosen),
// then the buttons right of the tool options (choosing a tool never moves the tools), then the file buttons.
// The menu holds stand-ins: choosing one clicks the toolbar button it stands for.
// Keyboard: Enter, Space, ↓ or ↑ on ⋯ opens the menu on its first (last) entry; ↑ ↓ Home End move; Enter or
// Space chooses; Escape closes it and gives the focus back to ⋯; Tab leaves it closed.

// toolbar: the .toolbar element, holding #more-button and #more-menu.
export function bindOverflow(toolbar) {
  const button = toolbar.querySelector('#more-button');
  const menu = toolbar.querySelector('#more-menu');
  const ranked = [...toolbar.querySelectorAll('[data-overflow]')].sort(
    (a, b) => a.dataset.overflow - b.dataset.overflow,
  );
  const seps = [...toolbar.children].filter((el) => el.classList.contains('sep'));
  const groups = [...toolbar.querySelectorAll('.group')];
  let scheduled = 0;

  const shown = (el) => el.getBoundingClientRect().width > 0;
  // Whether the row (with `reserve` more pixels) runs past the toolbar's right padding.
  function over(reserve = 0) {
    const box = toolbar.getBoundingClientRect();
    let right = box.left;
    for (const el of toolbar.children)
      if (el !== menu && shown(el)) right = Math.max(right, el.getBoundingClientRect().right);
    return right + reserve + parseFloat(getComputedStyle(toolbar).paddingRight) > box.left + toolbar.clientWidth + 0.5;
  }
  const options = toolbar.querySelector('.tool-options');
  const entries = () => [...menu.querySelectorAll('[role="menuitem"]')];

  // A separator with nothing shown before it, or only another separator, goes too; so does an empty group.
  function tidy() {
    for (const g of groups) {
      g.classList.remove('overflowed');
      g.classList.toggle('overflowed', ![...g.children].some(shown));
    }
    let last = null;
    for (const el of toolbar.children) {
      if (seps.includes(el)) {
        el.classList.remove('overflowed');
        if (!last || seps.includes(last)) el.classList.add('overflowed');
      }
      if (el !== button && el !== menu && shown(el)) last = el;
    }
    if (last && seps.includes(last)) last.classList.add('overflowed');
  }

  function fit() {
    scheduled = 0;
    if (!toolbar.isConnected || toolbar.clientWidth === 0) return;
    for (const el of [...ranked, ...seps, ...groups]) el.classList.remove('overflowed');
    button.hidden = true;
    if (getComputedStyle(toolbar).flexWrap !== 'nowrap') return tidy(), rebuild();
    // data-overflow-reserve (the brand): placed as if the widest tool options showed.
    const extra = options ? widestOptions(options) - options.getBoundingClientRect().width : 0;
    for (const el of ranked) {
      if (!shown(el)) continue;
      const reserve = 'overflowReserve' in el.dataset ? extra : 0;
      if (!over(reserve)) {
        if (reserve) continue;
        break;
      }
      if (!reserve) button.hidden = false;
      el.classList.add('overflowed');
      tidy();
    }
    tidy();
    rebuild();
    button.hidden = !menu.children.length;
  }

  // The stand-ins, in toolbar order, for the buttons in the menu now.
  function rebuild() {
    const moved = [...toolbar.querySelectorAll('button[data-overflow].overflowed')];
    if (!moved.length) close(false);
    menu.replaceChildren(
      ...moved.map((original) => {
        const item = document.createElement('button');
        item.type = 'button';
        item.setAttribute('role', 'menuitem');
        item.tabIndex = -1;
        item.textContent = original.getAttribute('aria-label') ?? original.textContent;
        item.title = original.title;
        item.disabled = original.disabled;
        item.addEventListener('click', () => {
          close(true);
          original.click();
        });
        return item;
      }),
    );
  }

  function open(at = 0) {
    rebuild();
    const list = entries();
    if (!list.length) return;
    menu.hidden = false;
    button.setAttribute('aria-expanded', 'true');
    list.at(at)?.focus();
  }

  function close(refocus) {
    if (menu.hidden) return;
    menu.hidden = true;
    button.setAttribute('aria-expanded', 'false');
    if (refocus) button.focus();
  }

  button.addEventListener('click', () => (menu.hidden ? open(0) : close(true)));
  button.addEventListener('keydown', (e) => {
    if (e.key === 'ArrowDown' || e.key === 'ArrowUp') {
      e.preventDefault();
      open(e.key === 'ArrowDown' ? 0 : -1);
    }
  });
  menu.addEventListener('keydown', (e) => {
    const list = entries(), i = list.indexOf(e.target);
    const move = { ArrowDown: i + 1, ArrowUp: i - 1, Home: 0, End: list.length - 1 }[e.key];
    if (move !== undefined) {
      e.preventDefault();
      list[(move + list.length) % list.length]?.focus();
    } else if (e.key === 'Escape') {
      e.preventDefault();
      e.stopPropagation(); // not also the element's Escape (deselect, back to Orbit)
      close(true);
    } else if (e.key === 'Tab') close(false);
    e.stopPropagation(); // letters in the menu are not tool shortcuts
  });
  // A press anywhere else on the page closes it, and so does focus moving elsewhere (Tab).
  const outside = (e) => !e.composedPath().some((n) => n === menu || n === button) && close(false);
  const doc = toolbar.ownerDocument;
  doc.addEventListener('pointerdown', outside, true);
  menu.addEventListener(
    'focusout',
    (e) => e.relatedTarget && e.relatedTarget !== button && !menu.contains(e.relatedTarget) && close(false),
  );

  const schedule = () => (scheduled ||= requestAnimationFrame(fit));
  // Sizes change with the element, with the readonly and controls attributes, and with the tool options; a
  // fit on the next frame (not inside the observer: the fit itself resizes what it observes).
  const observer = new ResizeObserver(schedule);
  observer.observe(toolbar);
  for (const el of toolbar.querySelectorAll(':scope > *, .tool-options')) if (el !== menu) observer.observe(el);

  return {
    fit,
    schedule,
    dispose() {
      observer.disconnect();
      cancelAnimationFrame(scheduled);
      doc.removeEventListener('pointerdown', outside, true);
    },
  };
}

// The width of the tool options of the tool with the most of them (0 while they are not shown at all).
function widestOptions(options) {
  const parts = [...options.querySelectorAll('[data-for]')];
  const was = parts.map((p) => p.hidden);
  let widest = 0;
  for (const tool of new Set(parts.flatMap((p) => p.dataset.for.split(' ')))) {
    parts.forEach((p) => (p.hidden = !p.dataset.for.split(' ').includes(tool)));
    widest = Math.max(widest, options.getBoundingClientRect().width);
  }
  parts.forEach((p, i) => (p.hidden = was[i]));
  return widest;
}
