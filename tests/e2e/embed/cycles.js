// Creates a designer, waits until its model is loaded, removes it; n times. Counts the WebGL contexts the
// elements' canvases lose (a disposed designer gives its context back at once).
import { TangentFieldDesigner } from './node_modules/tangent-field-designer/lib/tangent-field-designer.standalone.js';

const state = { created: 0, contextsLost: 0, live: [] };

async function create(src) {
  const el = new TangentFieldDesigner();
  el.setAttribute('src', src);
  el.setAttribute('controls', 'none');
  document.body.append(el);
  await el.ready;
  el.shadowRoot.querySelector('canvas').addEventListener('webglcontextlost', () => state.contextsLost++);
  state.created++;
  return el;
}

window.__cycles = {
  state,
  async run(n, src) {
    for (let k = 0; k < n; k++) {
      const el = await create(src);
      el.remove();
    }
    await new Promise((r) => setTimeout(r, 50)); // removal disposes a microtask later
    return { created: state.created, contextsLost: state.contextsLost };
  },
  async keep(src) {
    const el = await create(src);
    state.live.push(el);
    return el.info().faces;
  },
};
