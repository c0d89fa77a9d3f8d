// Panels fit their width (issue 44, item 7): at 1024x768 and on a 390x844 phone, with every <details> section
// of every panel open, each symmetry and each field component chosen, each tool active and each control of the
// panels focused in turn, no element inside a panel reaches past its right edge, no panel scrolls sideways
// (scrollWidth <= clientWidth + 1, scrollLeft 0) and the panel's first control starts inside its left edge (a
// control wider than the panel made the panel scroll, and focusing it left the whole panel shifted left).
// Panels, sections, tools, options and controls are all read from the page, so controls added later are covered.
import { expect, test } from '@playwright/test';
import { openDesigner, trackErrors } from './helpers.mjs';

const SIZES = [
  ['1024x768', { viewport: { width: 1024, height: 768 } }],
  ['390x844 phone', { viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }],
];
const PANELS = '[part~="panel"]';

// Every way a panel's content sticks out sideways, as readable lines (empty when everything fits). Runs in the page.
function panelProblems(panels) {
  const root = document.querySelector('tangent-field-designer').shadowRoot;
  const problems = [];
  const name = (el) => `${el.tagName.toLowerCase()}${el.id ? `#${el.id}` : ''}`;
  const shown = (el) => el.checkVisibility() && el.getBoundingClientRect().width > 0;
  for (const panel of [...root.querySelectorAll(panels)].filter(shown)) {
    const box = panel.getBoundingClientRect();
    const left = box.left + panel.clientLeft;
    const right = left + panel.clientWidth;
    if (panel.scrollWidth > panel.clientWidth + 1)
      problems.push(`${panel.id}: scrollWidth ${panel.scrollWidth} > clientWidth ${panel.clientWidth}`);
    if (panel.scrollLeft !== 0) problems.push(`${panel.id}: scrolled ${panel.scrollLeft} px sideways`);
    for (const el of panel.querySelectorAll('*')) {
      if (!shown(el)) continue;
      const r = el.getBoundingClientRect();
      if (r.right > right + 1) problems.push(`${panel.id}: ${name(el)} ends ${(r.right - right).toFixed(1)} px past`);
    }
    const first = [...panel.querySelectorAll('summary, h2, label, select, input, button')].find(shown);
    const firstLeft = first?.getBoundingClientRect().left ?? left;
    if (firstLeft < left - 0.5) problems.push(`${panel.id}: ${name(first)} starts ${left - firstLeft} px left of it`);
  }
  return problems;
}

const overflows = (page) => page.evaluate(panelProblems, PANELS);

// Each control brought into view and focused in turn (what a click does first, element.focus() scrolling as the
// browser does), the panels checked after each; in one call, where three round trips per control took most of
// the test's time. Runs in the page: check is panelProblems.
function focusEach(panels, ids, check) {
  const root = document.querySelector('tangent-field-designer').shadowRoot;
  return ids.flatMap((id) => {
    const control = root.getElementById(id);
    control.scrollIntoView({ block: 'nearest', inline: 'nearest' });
    control.focus();
    return check(panels).map((problem) => `#${id} in view and focused: ${problem}`);
  });
}

const overflowsWhenFocused = (page, ids) =>
  page.evaluate(`(${focusEach})(${JSON.stringify(PANELS)}, ${JSON.stringify(ids)}, ${panelProblems})`);

// Opens every collapsible section of the designer; returns how many there are.
function openSections(page) {
  return page.evaluate(() => {
    const sections = document.querySelector('tangent-field-designer').shadowRoot.querySelectorAll('details');
    for (const d of sections) d.open = true;
    return sections.length;
  });
}

// Ids of the enabled, shown controls in the panels that take focus.
function focusableIds(page) {
  return page.evaluate((panels) => {
    const root = document.querySelector('tangent-field-designer').shadowRoot;
    const controls = root.querySelectorAll(`${panels} :is(select, input, button, summary)`);
    return [...controls].filter((c) => c.id && !c.disabled && c.checkVisibility()).map((c) => c.id);
  }, PANELS);
}

// A constraint that every symmetry keeps (a vector in face 0, in its plane), selected so the selection's
// controls show in the constraints panel.
async function addSelectedVector(page) {
  await page.evaluate(async () => {
    const { positions: p, triangles: t } = window.tvf.mesh();
    const [a, b] = [t[0], t[1]];
    const id = await window.tvf.addVector(0, [0, 1, 2].map((k) => p[3 * b + k] - p[3 * a + k]));
    window.tvf.select(id);
  });
}

// What a trackpad's or a finger's sideways swipe over each panel does.
function swipeSideways(page) {
  return page.evaluate((panels) => {
    const root = document.querySelector('tangent-field-designer').shadowRoot;
    for (const panel of root.querySelectorAll(panels)) panel.scrollBy({ left: 400, behavior: 'instant' });
  }, PANELS);
}

const settled = (page) =>
  page.evaluate(async () => {
    await window.tvf.settled();
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  });

for (const [size, options] of SIZES) {
  test(`every panel fits its width at ${size}`, async ({ browser }) => {
    const context = await browser.newContext(options);
    const page = await context.newPage();
    const errors = trackErrors(page);
    await openDesigner(page);
    const toggle = page.locator('#panels-toggle');
    if (await toggle.isVisible()) await toggle.click(); // the drawers of a narrow element
    await expect(page.locator('#side-panel')).toBeVisible();
    await addSelectedVector(page);
    await expect(page.locator('#selection-panel')).toBeVisible();
    expect(await openSections(page)).toBeGreaterThan(1);
    await settled(page);
    expect(await overflows(page), 'opened').toEqual([]);

    const symmetries = await page.locator('#symmetry option:not([hidden])').evaluateAll((os) => os.map((o) => o.value));
    const components = await page.locator('#view-component option').evaluateAll((os) => os.map((o) => o.value));
    const tools = await page.locator('button[data-tool]').evaluateAll((bs) => bs.map((b) => b.dataset.tool));
    expect(symmetries.length).toBeGreaterThanOrEqual(3);
    for (const n of symmetries) {
      await page.locator('#symmetry').selectOption(n);
      await settled(page);
      await openSections(page); // sections added for this symmetry start open too
      const label = `symmetry ${n}`;
      expect(await overflows(page), label).toEqual([]);
      // The Component select is for vector fields only; wait for the panel to say so for this symmetry (the
      // settings can come after settled(): reading isEnabled() at once raced them).
      const vectorField = Number(n) === 1;
      await expect(page.locator('#view-component')).toHaveJSProperty('disabled', !vectorField);
      if (vectorField) {
        for (const c of components) {
          await page.locator('#view-component').selectOption(c);
          await settled(page);
          expect(await overflows(page), `${label}, component ${c}`).toEqual([]);
        }
        await page.locator('#view-component').selectOption(components[0]);
      }
      for (const tool of tools) {
        const button = page.locator(`button[data-tool="${tool}"]`);
        if (!(await button.isVisible()) || (await button.isDisabled())) continue;
        await button.click();
        await settled(page);
        expect(await overflows(page), `${label}, tool ${tool}`).toEqual([]);
      }
      await page.locator('button[data-tool="orbit"]').click();
      // Bringing a control into view (as a click does) or a sideways swipe scrolls a panel that is wider inside
      // than out: its whole content then sits shifted left.
      const ids = await focusableIds(page);
      expect(ids.length).toBeGreaterThan(10);
      expect(await overflowsWhenFocused(page, ids), label).toEqual([]);
      await swipeSideways(page);
      expect(await overflows(page), `${label}, swiped sideways`).toEqual([]);
    }
    expect(errors).toEqual([]);
    await context.close();
  });
}
