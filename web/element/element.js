// <tangent-field-designer>: the designer as a custom element (docs/embedding.md). Each element owns one
// Designer (designer.js: the composition of its session, canvas, panels, tools and texture) in an open shadow
// root; attributes are reflected to properties, the API of docs/js-api.md (api.js) is on the element, and
// events fire on the element whose field or constraints changed.
//
// Importing this module has no side effects and touches no DOM globals at the top level, so it loads in node
// and during server-side rendering; define() registers the element.
import { TEXTURE_METHODS, api } from './api.js';
import { DEFAULT_VIEWS, parseBoundary, parseSetting, parseViews } from './attribute-values.js';
import css from './element.css';
import { Designer } from './designer.js';
import { DEFAULT_WEIGHT } from '../session/session.js';
import { TEMPLATE } from './template.js';
import { TOOLS } from '../tools/tools.js';

export const TAG_NAME = 'tangent-field-designer';
// Reflected string attributes: property name → attribute name.
const STRING_ATTRIBUTES = {
  src: 'src',
  design: 'design',
  boundary: 'boundary',
  tool: 'tool',
  views: 'views',
  controls: 'controls',
  autosave: 'autosave',
  exemplar: 'exemplar',
  assetBase: 'asset-base',
};
// Reflected number attributes: property name → attribute name; NUMBER_DEFAULTS: the property without it.
const NUMBER_ATTRIBUTES = {
  gamma: 'gamma',
  symmetry: 'symmetry',
  curvatureAlignment: 'curvature-alignment',
};
const NUMBER_DEFAULTS = Object.freeze({ gamma: 0, symmetry: 1, curvatureAlignment: 0 });
// The settings the element writes back into their attributes whenever the design's change (the panel, the API,
// an undo, a loaded design), as it does the tool into `tool`: the attribute and the selector always agree.
const REFLECTED_SETTINGS = ['symmetry', 'curvatureAlignment'];
const propertyOf = (attr) =>
  Object.entries({ ...STRING_ATTRIBUTES, ...NUMBER_ATTRIBUTES }).find(([, a]) => a === attr)?.[0] ?? attr;
// Tells the element it is the app page's designer (index.html): the page's keyboard shortcuts and the
// ?bench=1 benchmark. Not for embedding pages.
export const APP_PAGE = Symbol('tangent-field-designer app page');

// In node (no DOM) the class still has to be definable: extend an empty class there.
const Base = globalThis.HTMLElement ?? class {};

export class TangentFieldDesigner extends Base {
  // Folder (URL string) holding the package's entry module, core-worker.js and wasm/; null = next to this
  // module (import.meta.url). Set it before the first element connects when the module was bundled.
  static assetBase = null;
  static DEFAULT_WEIGHT = DEFAULT_WEIGHT;

  static get observedAttributes() {
    return [...Object.values(STRING_ATTRIBUTES), ...Object.values(NUMBER_ATTRIBUTES), 'readonly'];
  }

  #designer = null;
  #ready;
  #settle = null; // {resolve, reject} of #ready while the first start-up is under way
  #connecting = false;
  #appPage = false;

  constructor() {
    super();
    const root = this.attachShadow({ mode: 'open' });
    const sheet = new CSSStyleSheet();
    sheet.replaceSync(css);
    root.adoptedStyleSheets = [sheet];
    this.#resetReady();
  }

  get DEFAULT_WEIGHT() {
    return DEFAULT_WEIGHT;
  }

  // Resolves when the core is up and, with `src`, that model is loaded and factored (and `design` applied).
  // Rejects with the reason otherwise; the element also fires `error`.
  get ready() {
    return this.#ready;
  }

  #resetReady() {
    this.#ready = new Promise((resolve, reject) => (this.#settle = { resolve, reject }));
    this.#ready.catch(() => {}); // the `error` event reports it; no "uncaught" duplicate in the console
  }

  [APP_PAGE]() {
    this.#appPage = true;
  }

  // ------------------------------------------------------------------------------------------ lifecycle

  connectedCallback() {
    if (this.#designer || this.#connecting) return; // moved within the document: keep everything
    this.#connecting = true;
    // A microtask later: attributes set right after insertion, and the app page's marker, are in place.
    queueMicrotask(() => {
      this.#connecting = false;
      if (this.isConnected && !this.#designer) this.#start();
    });
  }

  disconnectedCallback() {
    // A move (remove + insert in the same task) keeps the session; a removal ends it.
    queueMicrotask(() => {
      if (!this.isConnected) this.dispose();
    });
  }

  // Ends the worker, frees the WebGL contexts and clears the shadow root. Inserting the element again starts
  // a fresh designer.
  dispose() {
    const designer = this.#designer;
    if (!designer) return;
    this.#designer = null;
    designer.dispose();
    this.#settle?.reject(new Error('the designer was disposed'));
    this.#resetReady();
  }

  #assetBase() {
    const base =
      this.getAttribute('asset-base') ?? TangentFieldDesigner.assetBase ?? new URL('./', import.meta.url).href;
    const url = new URL(base, document.baseURI);
    if (!url.pathname.endsWith('/')) url.pathname += '/';
    return url;
  }

  #start() {
    const root = this.shadowRoot;
    root.innerHTML = TEMPLATE;
    const d = new Designer({
      host: this,
      root,
      assetBase: this.#assetBase(),
      autosave: this.getAttribute('autosave'),
      bench: this.#appPage,
      onTool: (tool) => {
        if (this.getAttribute('tool') !== tool && (tool !== 'orbit' || this.hasAttribute('tool')))
          this.setAttribute('tool', tool);
      },
      onSettings: (settings) => this.#reflectSettings(settings),
    });
    this.#designer = d;
    if (this.#appPage) d.ui.listenTo(window);
    d.session.readonly = this.hasAttribute('readonly');
    this.#applyAttribute('tool');
    this.#applyAttribute('views');
    for (const prop of ['boundary', ...Object.keys(NUMBER_ATTRIBUTES)]) this.#applyAttribute(prop);
    const settle = this.#settle;
    const started = d.start();
    const src = this.getAttribute('src');
    const loaded = started.then(() => (src ? this.#loadSrc(d, src) : null));
    loaded.then(
      () => settle.resolve(),
      (err) => settle.reject(err),
    );
    this.#settle = null;
  }

  // ------------------------------------------------------------------------------------------ attributes

  attributeChangedCallback(name, oldValue, value) {
    if (oldValue === value || !this.#designer) return;
    this.#applyAttribute(propertyOf(name));
  }

  // Applies the current value of one attribute (by property name) to the running session.
  #applyAttribute(prop) {
    const d = this.#designer;
    const s = d.session;
    const attr = STRING_ATTRIBUTES[prop] ?? NUMBER_ATTRIBUTES[prop] ?? prop;
    const value = this.getAttribute(attr);
    try {
      switch (prop) {
        case 'src':
          if (value) {
            const loaded = this.#loadSrc(d, value);
            loaded.catch(() => {}); // reported by the `error` event
            this.#ready = loaded;
          }
          break;
        case 'design':
          if (value && s.info) this.#loadDesignUrl(d, value).catch(() => {});
          break;
        case 'boundary':
        case 'gamma':
        case 'symmetry':
        case 'curvatureAlignment':
          this.#applySetting(s, prop, value);
          break;
        case 'tool':
          if (!TOOLS.includes(value ?? 'orbit')) throw new Error(`unknown tool "${value}" (tools: ${TOOLS.join(' ')})`);
          d.ui.setTool(value ?? 'orbit');
          break;
        case 'views':
          this.#applyViews(d, parseViews(value ?? DEFAULT_VIEWS));
          break;
        case 'readonly':
          s.readonly = value !== null;
          if (s.readonly && !['orbit', 'select'].includes(d.tools.tool)) d.ui.setTool('orbit');
          break;
        case 'autosave':
          s.autosave.name = value;
          break;
        case 'exemplar':
          if (value && d.textureView && s.info) d.textureApi.setExemplar(value).catch((err) => s.fail('texture', err));
          break;
        default: // controls: CSS only; asset-base: read at the next start
      }
    } catch (err) {
      s.fail('attribute', err);
    }
  }

  #applySetting(s, kind, value) {
    if (value === null) return;
    const setting = kind === 'boundary' ? parseBoundary(value) : parseSetting(kind, NUMBER_ATTRIBUTES[kind], value);
    // Before the first model, the setting waits in the session's design and goes in with the mesh.
    if (!s.info) {
      s.design = { ...s.design, [kind]: setting };
      return;
    }
    // The value in force already (also: the element's own reflection of a change made elsewhere).
    if (kind !== 'boundary' && s.settings()[kind] === setting) return;
    s.setSetting(kind, setting).catch((err) => s.fail('setting', err));
  }

  // Called after every change: the attribute is written only when it is there already or the value is not the
  // default, so an element nobody configured keeps a clean tag.
  #reflectSettings(settings) {
    for (const prop of REFLECTED_SETTINGS) {
      const attr = NUMBER_ATTRIBUTES[prop], text = String(settings[prop]);
      if (!this.hasAttribute(attr) && settings[prop] === NUMBER_DEFAULTS[prop]) continue;
      if (this.getAttribute(attr) !== text) this.setAttribute(attr, text);
    }
  }

  #applyViews(d, on) {
    const s = d.session;
    d.viewSync.set({
      arrows: on.has('arrows'),
      streamlines: on.has('streamlines'),
      lic: on.has('lic'),
      colorMap: on.has('magnitude'),
      singularities: on.has('singularities'),
    });
    if (on.has('stripes') !== d.stripes.visible)
      d.stripes.setStripes({ visible: on.has('stripes') }).catch((err) => s.fail('stripes', err));
    const texture = on.has('texture');
    if (texture === d.textureView) return;
    d.textureView = texture;
    if (texture && !s.info) return; // synthesized once the model is loaded (#loadSrc)
    const run = texture ? this.#synthesize(d) : d.textureApi.clearTexture();
    run.catch((err) => s.fail('texture', err));
  }

  // The texture view: the `exemplar` attribute's exemplar (the default one without it) along the field.
  async #synthesize(d) {
    const exemplar = this.getAttribute('exemplar');
    if (exemplar) await d.textureApi.setExemplar(exemplar);
    return d.textureApi.synthesize();
  }

  // Loads `src` (restoring the autosave only when the element asked for one), then `design`.
  async #loadSrc(d, src) {
    await d.session.loadModel(src);
    const design = this.getAttribute('design');
    if (design && this.#designer === d) await this.#loadDesignUrl(d, design);
    if (d.textureView && this.#designer === d) this.#synthesize(d).catch((err) => d.session.fail('texture', err));
  }

  async #loadDesignUrl(d, href) {
    const s = d.session;
    try {
      const url = new URL(href, document.baseURI);
      const res = await fetch(url);
      if (!res.ok) throw new Error(`could not fetch ${url.href}: HTTP ${res.status}`);
      const design = await res.json();
      // The boundary and gamma attributes, when given, win over the document's own settings; its symmetry and
      // curvature alignment are its own (they say what its constraints mean: a design with sources is a vector
      // field's) and the attributes follow them.
      if (design && typeof design === 'object') {
        if (this.hasAttribute('boundary')) design.boundary = parseBoundary(this.getAttribute('boundary'));
        if (this.hasAttribute('gamma')) design.gamma = Number(this.getAttribute('gamma'));
      }
      await s.replaceDesign(design, 'load design');
    } catch (err) {
      throw s.fail('design', new Error(`Could not load the design: ${err.message}`));
    }
  }

  // ------------------------------------------------------------------------------------------ properties

  get readonly() {
    return this.hasAttribute('readonly');
  }

  set readonly(on) {
    this.toggleAttribute('readonly', !!on);
  }

  // remove(id) removes a constraint (the documented API); remove() with no argument is still the DOM's
  // ChildNode.remove(), which takes the element out of the page (and so disposes it).
  remove(...args) {
    if (args.length === 0) return super.remove();
    return api.remove(this.#require(), ...args);
  }

  #require() {
    if (!this.#designer) throw new Error('the designer is not in a document (or was disposed)');
    return this.#designer;
  }

  static {
    for (const [prop, attr] of Object.entries(STRING_ATTRIBUTES)) {
      if (prop === 'views') continue; // also the views() method, below
      Object.defineProperty(this.prototype, prop, {
        get() {
          return this.getAttribute(attr);
        },
        set(value) {
          if (value == null) this.removeAttribute(attr);
          else this.setAttribute(attr, String(value));
        },
        configurable: true,
      });
    }
    for (const [prop, attr] of Object.entries(NUMBER_ATTRIBUTES)) {
      Object.defineProperty(this.prototype, prop, {
        get() {
          return Number(this.getAttribute(attr) ?? NUMBER_DEFAULTS[prop]);
        },
        set(value) {
          this.setAttribute(attr, String(value));
        },
        configurable: true,
      });
    }
    // The public API (api.js) and the texture calls, as methods of every element.
    for (const [name, fn] of Object.entries(api)) {
      if (name === 'remove') continue; // a method of its own, above
      if (name === 'views') continue;
      Object.defineProperty(this.prototype, name, {
        value(...args) {
          return fn(this.#require(), ...args);
        },
        writable: true,
        configurable: true,
      });
    }
    // `views` is both the attribute's property and the views() method of js-api.md: reading it gives the
    // method, assigning a string sets the attribute.
    Object.defineProperty(this.prototype, 'views', {
      get() {
        const element = this;
        return function views() {
          return api.views(element.#require());
        };
      },
      set(value) {
        if (value == null) this.removeAttribute('views');
        else this.setAttribute('views', String(value));
      },
      configurable: true,
    });
    for (const name of TEXTURE_METHODS) {
      Object.defineProperty(this.prototype, name, {
        value(...args) {
          return this.#require().textureApi[name](...args);
        },
        writable: true,
        configurable: true,
      });
    }
  }
}

// Registers the element under tagName (default tangent-field-designer) unless that name is taken; returns
// the constructor registered under it. A second name gets a subclass (a constructor registers only once).
export function define(tagName = TAG_NAME) {
  const registry = globalThis.customElements;
  if (!registry) return TangentFieldDesigner; // node, server-side rendering
  const existing = registry.get(tagName);
  if (existing) return existing;
  const taken = registry.getName?.(TangentFieldDesigner);
  const ctor = taken ? class extends TangentFieldDesigner {} : TangentFieldDesigner;
  registry.define(tagName, ctor);
  return ctor;
}
