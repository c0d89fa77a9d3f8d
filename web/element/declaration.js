// SPDX-License-Identifier: GPL-2.0-or-later
// The public API of <tangent-field-designer>, declared once: every attribute, property, method and event
// with its TypeScript type and a one-line description. Data only (no code; it imports only its own parts): the
// methods are in declaration-design-methods.js and declaration-view-methods.js, the types their signatures use
// in declaration-types.d.ts. scripts/gen-api.mjs writes custom-elements.json, types/element.d.ts and the
// summary at the end of docs/js-api.md from them (`npm run gen:api`), and tests/node/api-declaration.test.mjs
// checks that the element as it runs (element.js, the api table and TEXTURE_METHODS of api.js, the events
// designer.js dispatches) and docs/js-api.md's prose declare the same names.
//
// A method's `source` says who installs it: 'api' (the api table of api.js), 'texture' (TEXTURE_METHODS,
// web/synthesis/index.js) or 'element' (element.js itself). `internal`: a test hook (the debug* methods),
// declared like the others and marked @internal. `signatures`: one entry per overload, [params, returns] in
// TypeScript; the first is the one the manifest lists.
import { DESIGN_METHODS } from './declaration-design-methods.js';
import { VIEW_METHODS } from './declaration-view-methods.js';

export const TAG_NAME = 'tangent-field-designer';
export const CLASS_NAME = 'TangentFieldDesigner';
export const DESCRIPTION = 'Interactive design of smooth tangent vector fields on a triangle mesh (docs/embedding.md).';

// String unions the declarations below refer to by name (the manifest spells them out).
export const ENUMS = {
  Tool: ['orbit', 'select', 'stroke', 'vector', 'source', 'sink', 'vortex', 'singularity', 'feature'],
  Controls: ['full', 'minimal', 'none'],
  ErrorCode: ['model', 'design', 'texture', 'stripes', 'core', 'setting', 'attribute', 'autosave'],
  CoreFailureKind: ['ended', 'error', 'trap', 'silent', 'cancelled'],
  MaterialPreset: ['brushed metal', 'satin'],
};

// Attributes, each reflected to a property. `type`: the property's type.
export const ATTRIBUTES = [
  {
    name: 'src',
    property: 'src',
    type: 'string | null',
    description: 'Model URL (.glb, .gltf, .obj, .off, .ply). Changing it loads that model; a failure keeps the ' +
      'current one. Without it nothing is loaded.',
  },
  {
    name: 'design',
    property: 'design',
    type: 'string | null',
    description: 'URL of a design JSON (docs/design-format.md), applied after the model loads.',
  },
  {
    name: 'boundary',
    property: 'boundary',
    type: 'string | null',
    default: 'free',
    description: 'Boundary condition: free, tangential, normal, or an angle in radians.',
  },
  { name: 'gamma', property: 'gamma', type: 'number', default: '0', description: 'Bi-Laplacian smoothness γ ≥ 0.' },
  {
    name: 'symmetry',
    property: 'symmetry',
    type: 'number',
    default: '1',
    description: "The field's symmetry N, a whole number 1–6: 1 a vector field, " +
      '2 a line field (a direction without ' +
      'sign), 4 a cross field (four directions at right angles). Follows the design: the Symmetry selector, ' +
      'setSymmetry(), undo and loaded designs write it back.',
  },
  {
    name: 'curvature-alignment',
    property: 'curvatureAlignment',
    type: 'number',
    default: '0',
    description: 'How strongly a line or cross field (even N) is pulled toward the principal curvature directions, ' +
      '≥ 0 (0: off). Follows the design, as symmetry does.',
  },
  { name: 'tool', property: 'tool', type: 'Tool | null', default: 'orbit', description: 'The active mouse tool.' },
  {
    name: 'views',
    property: 'views',
    type: 'string | null',
    default: 'arrows',
    description: 'Space-separated subset of: arrows streamlines lic magnitude singularities texture stripes ' +
      '(lic: the ' +
      'flow texture; stripes: the stripe pattern, setStripes()). Reading the property gives the views() method; ' +
      'assigning a string sets the attribute.',
  },
  {
    name: 'controls',
    property: 'controls',
    type: 'Controls | null',
    default: 'minimal',
    description: 'full = the studio panels, minimal = toolbar only, none = canvas only.',
  },
  {
    name: 'readonly',
    property: 'readonly',
    type: 'boolean',
    default: 'false',
    description: 'No edits from the tools or panels (the script API still edits).',
  },
  {
    name: 'autosave',
    property: 'autosave',
    type: 'string | null',
    description: 'Autosave the design (IndexedDB, the last versions per model, with a localStorage copy) under this ' +
      'key and the model, and restore it on load. Off unless given.',
  },
  {
    name: 'exemplar',
    property: 'exemplar',
    type: 'string | null',
    default: 'stripes',
    description: "Texture exemplar for the texture view: 'stripes', 'scales', 'weave', 'brushed' (streaks for line " +
      'fields) or an image URL.',
  },
  {
    name: 'asset-base',
    property: 'assetBase',
    type: 'string | null',
    description: 'Folder (URL) with core-worker.js and wasm/; overrides TangentFieldDesigner.assetBase.',
  },
];

// Properties that are no attribute's.
export const PROPERTIES = [
  {
    name: 'ready',
    type: 'Promise<void>',
    readonly: true,
    description: 'Resolves when the core is up and, with src, the model is loaded and factored (and design applied); ' +
      'rejects with the reason.',
  },
  {
    name: 'DEFAULT_WEIGHT',
    type: 'number',
    readonly: true,
    description: '1e4, the weight strokes, vectors and edges get by default.',
  },
];

export const STATIC_PROPERTIES = [
  {
    name: 'assetBase',
    type: 'string | null',
    description: 'Folder (URL) with the package entry module, core-worker.js and wasm/ for elements that start ' +
      'afterwards; null = next to the module.',
  },
  {
    name: 'DEFAULT_WEIGHT',
    type: 'number',
    readonly: true,
    description: '1e4, the weight strokes, vectors and edges get by default.',
  },
];

// Methods, in the order of docs/js-api.md's sections (`group`).
export const METHODS = [...DESIGN_METHODS, ...VIEW_METHODS];

// Events: CustomEvents that bubble and are composed, fired on the element. `detail`: [field, type, doc?].
export const EVENTS = [
  {
    name: 'load',
    detailType: 'LoadEventDetail',
    detail: [['info', 'MeshInfo']],
    description: 'A model is loaded and factored.',
  },
  {
    name: 'error',
    detailType: 'ErrorEventDetail',
    detail: [
      [
        'code',
        'ErrorCode',
        'What failed: a model, a design, the texture, the core, a setting, an attribute, the autosave.',
      ],
      ['message', 'string'],
    ],
    description: 'Something failed; code names what. The element also shows message in its banner.',
  },
  {
    name: 'fieldchange',
    detailType: 'FieldChangeEventDetail',
    detail: [['version', 'number'], ['stats', 'Record<string, number | string>']],
    description: 'After every completed change of the field (an edit, undo, redo, a model load).',
  },
  {
    name: 'constraintschange',
    detailType: 'ConstraintsChangeEventDetail',
    detail: [['constraints', 'Constraint[]']],
    description: 'The constraint list changed.',
  },
  {
    name: 'progress',
    detailType: 'ProgressEventDetail',
    detail: [
      ['phase', 'string', "The core operation: 'loadMesh', 'add', 'remove', 'setBoundary', 'applyDesign', ..."],
      ['fraction', 'number', '0 when it starts, 1 when it ends.'],
    ],
    description: 'A core operation started (fraction 0) or ended (fraction 1).',
  },
  {
    name: 'corerestart',
    detailType: 'CoreRestartEventDetail',
    detail: [['kind', 'CoreFailureKind'], ['detail', 'string']],
    description: 'The core worker was replaced (it ended, failed, trapped, went silent, or was cancelled) and the ' +
      'model and design are back.',
  },
  {
    name: 'autosaveconflict',
    detailType: 'AutosaveConflictEventDetail',
    detail: [['model', 'string']],
    description: 'Another tab is editing the same model; both keep their autosave versions.',
  },
];

export const CSS_PROPERTIES = [
  { name: '--tfd-background', default: '#1b1d21', description: 'Background of the element and its bars' },
  { name: '--tfd-panel', default: '#24272d', description: 'Toolbar, status bar' },
  { name: '--tfd-control', default: '#2d3139', description: 'Buttons and inputs' },
  { name: '--tfd-border', default: '#3a3f48', description: 'Borders' },
  { name: '--tfd-text', default: '#dfe3ea', description: 'Text' },
  { name: '--tfd-muted', default: '#9aa2ae', description: 'Secondary text' },
  { name: '--tfd-accent', default: '#ff7a1a', description: 'Active tool, focus ring, progress' },
  { name: '--tfd-error', default: '#b42318', description: 'Error banner' },
  { name: '--tfd-font', default: '13px/1.4 system-ui, sans-serif', description: 'Font shorthand' },
];

export const CSS_PARTS = [
  { name: 'root', description: 'The whole inside' },
  { name: 'toolbar', description: 'The tool bar' },
  { name: 'brand', description: 'The name in the tool bar (controls="full")' },
  { name: 'viewport', description: 'The area holding the canvas and the floating panels' },
  { name: 'canvas', description: 'The WebGL canvas' },
  { name: 'panel', description: 'Both floating panels' },
  { name: 'side-panel', description: 'Field, views and texture panel' },
  { name: 'constraints-panel', description: 'Constraint list' },
  {
    name: 'panels-toggle',
    description: 'The Panels button that opens the panels as drawers (below 900 px of element width)',
  },
  { name: 'status', description: 'Status bar' },
  { name: 'error', description: 'Error banner' },
  { name: 'progress', description: 'Progress bar' },
];
