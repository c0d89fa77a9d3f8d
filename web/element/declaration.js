// SPDX-License-Identifier: GPL-2.0-or-later
// The public API of <tangent-field-designer>, declared once: every attribute, property, method and event
// with its TypeScript type and a one-line description. Data only (no imports, no code): scripts/gen-api.mjs
// writes custom-elements.json, types/element.d.ts and the summary at the end of docs/js-api.md from it
// (`npm run gen:api`), and tests/node/api-declaration.test.mjs checks that the element as it runs (element.js,
// the api table and TEXTURE_METHODS of api.js, the events designer.js dispatches) and docs/js-api.md's prose
// declare the same names.
//
// A method's `source` says who installs it: 'api' (the api table of api.js), 'texture' (TEXTURE_METHODS,
// web/synthesis/index.js) or 'element' (element.js itself). `internal`: a test hook (the debug* methods),
// declared like the others and marked @internal. `signatures`: one entry per overload, [params, returns] in
// TypeScript; the first is the one the manifest lists.

export const TAG_NAME = 'tangent-field-designer';
export const CLASS_NAME = 'TangentFieldDesigner';
export const DESCRIPTION = 'Interactive design of smooth tangent vector fields on a triangle mesh (docs/embedding.md).';

// String unions the declarations below refer to by name (the manifest spells them out).
export const ENUMS = {
  Tool: ['orbit', 'select', 'stroke', 'vector', 'source', 'sink', 'vortex'],
  Controls: ['full', 'minimal', 'none'],
  ErrorCode: ['model', 'design', 'texture', 'core', 'setting', 'attribute', 'autosave'],
  CoreFailureKind: ['ended', 'error', 'trap', 'silent', 'cancelled'],
  MaterialPreset: ['brushed metal', 'satin'],
};

// The types the signatures use, in TypeScript (copied into types/element.d.ts as they are).
export const TYPES = `/** A point on the surface: barycentric coordinates in a face of the core's welded mesh. */
export interface SurfacePoint {
  face: number;
  bary: [number, number, number];
}

/** Flow map and GLB export options (docs/export.md). */
export interface ExportOptions {
  /** Flow map texels per side (1–8192, default 1024). */
  size: number;
  convention: 'gltf' | 'opengl';
  bits: 8 | 16;
  /** KHR_materials_anisotropy strength and rotation (radians). */
  strength: number;
  rotation: number;
  /** GLB: embed the flow map and the anisotropy material (default true). */
  embedFlowMap?: boolean;
  /** GLB: embed the design, so loadModel() reopens it with its design (default true). */
  embedDesign?: boolean;
  /** GLB: the synthesized texture as base colour — 'auto' (default): when one is shown; true: required; false: never. */
  texture?: 'auto' | boolean;
  /** GLB: the texture image's size in pixels per side (default: 2 pixels per atlas texel). */
  textureResolution?: number;
  /** GLB: pixels per atlas texel of the texture image (default 2). */
  textureMagnification?: number;
}

export type Boundary = 'free' | 'tangential' | 'normal' | { angle: number };

/** The design's settings (settings()). */
export interface Settings {
  boundary: Boundary;
  gamma: number;
  /** 1 a vector field, 2 a line field, 4 a cross field (1–6). */
  symmetry: number;
  /** 0: off. */
  curvatureAlignment: number;
}

export interface MeshInfo {
  vertices: number;
  edges: number;
  faces: number;
  components: number;
  boundaryLoops: number;
  eulerCharacteristic: number;
  genus: number;
  problems: unknown[];
  [key: string]: unknown;
}

export type ConstraintSpec =
  | { type: 'stroke'; points: SurfacePoint[]; strength: number; weight: number }
  | { type: 'vector'; face: number; vector: [number, number, number]; weight: number }
  | { type: 'edge'; edge: [number, number]; value: number; weight: number }
  | { type: 'source' | 'sink'; vertex: number; strength: number }
  | { type: 'vortex'; face: number; strength: number };

/** A constraint with the element's id for it (kept across delete and undo). */
export type Constraint = ConstraintSpec & { id: number };

export interface Design {
  boundary: Boundary;
  gamma: number;
  /** The field's symmetry N: 1 a vector field, 2 a line field, 4 a cross field (1–6; 1 when absent). */
  symmetry?: number;
  /** Pull toward the principal curvature directions, ≥ 0 (0 or absent: off; even N only). */
  curvatureAlignment?: number;
  constraints: ConstraintSpec[];
  [key: string]: unknown;
}

export interface Views {
  arrows: boolean;
  arrowDensity: number;
  arrowsScaled: boolean;
  streamlines: boolean;
  streamlineSpacing: number;
  /** Flow texture: line integral convolution of white noise along the field (screen space, GPU). */
  lic: boolean;
  colorMap: boolean;
  singularities: boolean;
  /** The part of the Hodge decomposition every view draws (singularity markers stay the whole field's): 'exact' curl-free, 'coexact' divergence-free. */
  component: 'whole' | 'exact' | 'coexact' | 'harmonic';
}

export interface LoadModelOptions {
  name?: string;
  format?: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '';
  companions?: File[];
  /** false: do not restore the autosaved design (autosave is only ever on with the \`autosave\` attribute). */
  restore?: boolean;
  /** A mesh with at least this many edges opens with a preview field solved on a coarse copy, the exact field following (default 300000; 0: never). */
  previewEdges?: number;
}

export type ModelSource = string | URL | Blob | ArrayBuffer | ArrayBufferView;

/** One stored autosave version of the current model's design. */
export interface AutosaveVersion {
  id: number;
  /** ISO 8601 time of the save. */
  savedAt: string;
  /** The tab that saved it; \`mine\`: this tab. */
  tab: string;
  mine: boolean;
  /** How many constraints the design has. */
  constraints: number;
}

export interface Supervision {
  /** How often the core's worker was replaced. */
  restarts: number;
  lastFailure: { kind: CoreFailureKind; detail: string; at: number } | null;
}

/** What the core itself holds now, each derived by the core on request (the reference for the page's reads). */
export interface CoreReadout {
  version: number;
  oneForm: Float64Array;
  faceVectors: Float64Array;
  vertexVectors: Float64Array;
  singularities: { vertex: number; index: number }[];
  design: Design;
}

/** The Hodge decomposition c = dα + δβ + h (Eq. 3) of the field; per-edge arrays in oneForm()'s edge order. */
export interface HodgeDecomposition {
  /** dα: the curl-free part, per edge. */
  exact: Float64Array;
  /** δβ: the divergence-free part, per edge. */
  coexact: Float64Array;
  /** h: the rest, both curl- and divergence-free (zero on a sphere), per edge. */
  harmonic: Float64Array;
  /** α per vertex (exact = dα), zero mean per connected component. */
  potential0: Float64Array;
  /** The 2-form potential per face (coexact = P⁻¹ d₁ᵀ potential2), zero mean per closed component. */
  potential2: Float64Array;
  /** |part|² / |c|² in the inner product; they sum to 1 (all 0 for a zero field). */
  energyShares: { exact: number; coexact: number; harmonic: number };
  /** The diagonal inner product P the parts are orthogonal in: one weight per edge. */
  innerProduct: Float64Array;
  /** Which one: 'star1' (the Hodge star ⋆1, when positive on every edge) or 'whitney-mass'. */
  metric: string;
  /** How long the decomposition took in the core's worker, in ms. */
  decomposeMs: number;
}

/** One part of the field as the worker's \`component\` op returns it. */
export interface FieldComponent {
  oneForm: Float64Array;
  faceVectors: Float64Array;
  vertexVectors: Float64Array;
}

export interface SynthesisOptions {
  /** Atlas side, a power of two, or 'auto' (256–1024 by face count). */
  resolution?: number | 'auto';
  /** Texture size on the surface; 'auto': 6–16 exemplar tiles across sqrt(surface area). */
  featureScale?: number | 'auto';
  /** Resynthesize on field changes (default true). */
  autoUpdate?: boolean;
  /** Yield to the page's frames between draws, with progress (default true). */
  interleave?: boolean;
  magnitudeExponent?: number;
  jitter?: number;
  passes?: number;
  kappa?: number;
  seed?: number;
  seams?: boolean;
  gutter?: number;
  timing?: 'levels' | 'total';
  /** Faces whose field goes to the GPU per task (default 32768): a big model's field is uploaded a slice per frame. */
  sliceFaces?: number;
}

export type ExemplarSource =
  | string
  | URL
  | Blob
  | ImageData
  | ImageBitmap
  | { procedural: string; size?: number; seed?: number };
`;

// Attributes, each reflected to a property. `type`: the property's type.
export const ATTRIBUTES = [
  { name: 'src', property: 'src', type: 'string | null', description: 'Model URL (.glb, .gltf, .obj, .off, .ply). Changing it loads that model; a failure keeps the current one. Without it nothing is loaded.' },
  { name: 'design', property: 'design', type: 'string | null', description: 'URL of a design JSON (docs/design-format.md), applied after the model loads.' },
  { name: 'boundary', property: 'boundary', type: 'string | null', default: 'free', description: 'Boundary condition: free, tangential, normal, or an angle in radians.' },
  { name: 'gamma', property: 'gamma', type: 'number', default: '0', description: 'Bi-Laplacian smoothness γ ≥ 0.' },
  { name: 'symmetry', property: 'symmetry', type: 'number', default: '1', description: "The field's symmetry N, a whole number 1–6: 1 a vector field, 2 a line field (a direction without sign), 4 a cross field (four directions at right angles). Follows the design: the Symmetry selector, setSymmetry(), undo and loaded designs write it back." },
  { name: 'curvature-alignment', property: 'curvatureAlignment', type: 'number', default: '0', description: 'How strongly a line or cross field (even N) is pulled toward the principal curvature directions, ≥ 0 (0: off). Follows the design, as symmetry does.' },
  { name: 'tool', property: 'tool', type: 'Tool | null', default: 'orbit', description: 'The active mouse tool.' },
  { name: 'views', property: 'views', type: 'string | null', default: 'arrows', description: 'Space-separated subset of: arrows streamlines lic magnitude singularities texture (lic: the flow texture). Reading the property gives the views() method; assigning a string sets the attribute.' },
  { name: 'controls', property: 'controls', type: 'Controls | null', default: 'minimal', description: 'full = the studio panels, minimal = toolbar only, none = canvas only.' },
  { name: 'readonly', property: 'readonly', type: 'boolean', default: 'false', description: 'No edits from the tools or panels (the script API still edits).' },
  { name: 'autosave', property: 'autosave', type: 'string | null', description: 'Autosave the design (IndexedDB, the last versions per model, with a localStorage copy) under this key and the model, and restore it on load. Off unless given.' },
  { name: 'exemplar', property: 'exemplar', type: 'string | null', default: 'stripes', description: "Texture exemplar for the texture view: 'stripes', 'scales', 'weave', 'brushed' (streaks for line fields) or an image URL." },
  { name: 'asset-base', property: 'assetBase', type: 'string | null', description: 'Folder (URL) with core-worker.js and wasm/; overrides TangentFieldDesigner.assetBase.' },
];

// Properties that are no attribute's.
export const PROPERTIES = [
  { name: 'ready', type: 'Promise<void>', readonly: true, description: 'Resolves when the core is up and, with src, the model is loaded and factored (and design applied); rejects with the reason.' },
  { name: 'DEFAULT_WEIGHT', type: 'number', readonly: true, description: '1e4, the weight strokes, vectors and edges get by default.' },
];

export const STATIC_PROPERTIES = [
  { name: 'assetBase', type: 'string | null', description: 'Folder (URL) with the package entry module, core-worker.js and wasm/ for elements that start afterwards; null = next to the module.' },
  { name: 'DEFAULT_WEIGHT', type: 'number', readonly: true, description: '1e4, the weight strokes, vectors and edges get by default.' },
];

// Methods, in the order of docs/js-api.md's sections (`group`).
export const METHODS = [
  // Models
  { name: 'loadModel', source: 'api', group: 'Models', signatures: [['source: ModelSource, options?: LoadModelOptions', 'Promise<MeshInfo>']], description: "Loads a model (URL, File/Blob, bytes) as one transaction; resolves with its info(), rejects and keeps the current model on failure." },
  { name: 'info', source: 'api', group: 'Models', signatures: [['', 'MeshInfo']], description: "The core's mesh report (as `tvf info`)." },
  { name: 'mesh', source: 'api', group: 'Models', signatures: [['', '{ positions: Float64Array; triangles: Int32Array }']], description: 'Copies of the welded mesh: 3 coordinates per vertex, 3 vertex indices per face.' },
  { name: 'edges', source: 'api', group: 'Models', signatures: [['', 'Int32Array']], description: "The core's edges, 2 vertex indices per edge, lower index first." },

  // Constraints
  { name: 'addStroke', source: 'api', group: 'Constraints', signatures: [['points: SurfacePoint[], options?: { strength?: number; weight?: number }', 'Promise<number>']], description: "A stroke through surface points; resolves with the new constraint's id." },
  { name: 'addVector', source: 'api', group: 'Constraints', signatures: [['face: number, vector: [number, number, number], options?: { weight?: number }', 'Promise<number>']], description: 'The field in a triangle should be this vector (projected into its plane).' },
  { name: 'addEdge', source: 'api', group: 'Constraints', signatures: [['edge: [number, number], value: number, options?: { weight?: number }', 'Promise<number>']], description: 'The line integral of the field along an edge should be this value.' },
  { name: 'addSource', source: 'api', group: 'Constraints', signatures: [['vertex: number, options?: { strength?: number }', 'Promise<number>']], description: 'A source at a vertex with total outflow strength.' },
  { name: 'addSink', source: 'api', group: 'Constraints', signatures: [['vertex: number, options?: { strength?: number }', 'Promise<number>']], description: 'A sink at a vertex with total inflow strength.' },
  { name: 'addVortex', source: 'api', group: 'Constraints', signatures: [['face: number, options?: { strength?: number }', 'Promise<number>']], description: 'A vortex in a triangle with circulation strength (positive: counter-clockwise).' },
  {
    name: 'remove',
    source: 'api',
    group: 'Constraints',
    signatures: [
      ['id: number', 'Promise<true>'],
      ['', 'void'],
    ],
    description: "With an id: removes that constraint. Without: the DOM's ChildNode.remove() (and so dispose()).",
  },
  { name: 'setWeight', source: 'api', group: 'Constraints', signatures: [['id: number, weight: number', 'Promise<true>']], description: 'Changes the weight of a stroke, vector or edge constraint.' },
  { name: 'setStrength', source: 'api', group: 'Constraints', signatures: [['id: number, strength: number', 'Promise<true>']], description: 'Changes the strength of a stroke, source, sink or vortex.' },
  { name: 'constraints', source: 'api', group: 'Constraints', signatures: [['', 'Constraint[]']], description: 'The constraints in id order, each in the design format plus its id.' },
  { name: 'setBoundary', source: 'api', group: 'Constraints', signatures: [['boundary: Boundary', 'Promise<void>']], description: 'Sets the boundary condition (refactors).' },
  { name: 'setGamma', source: 'api', group: 'Constraints', signatures: [['gamma: number', 'Promise<void>']], description: 'Sets the bi-Laplacian smoothness γ ≥ 0 (refactors).' },
  { name: 'setSymmetry', source: 'api', group: 'Constraints', signatures: [['n: number', 'Promise<Constraint[]>']], description: 'Sets the symmetry N (1 vector, 2 line, 4 cross; 1–6) as one undoable step; for N ≥ 2 it removes the sources, sinks, vortices and edge constraints and resolves with them (undo restores them).' },
  { name: 'setCurvatureAlignment', source: 'api', group: 'Constraints', signatures: [['strength: number', 'Promise<void>']], description: 'Pulls a line or cross field (even N) toward the principal curvature directions with this strength ≥ 0 (0: off).' },
  { name: 'settings', source: 'api', group: 'Constraints', signatures: [['', 'Settings']], description: 'The current boundary condition, γ, symmetry and curvature alignment.' },

  // Undo and redo
  { name: 'undo', source: 'api', group: 'Undo and redo', signatures: [['', 'Promise<boolean>']], description: 'Undoes the last edit; false when there is nothing to undo.' },
  { name: 'redo', source: 'api', group: 'Undo and redo', signatures: [['', 'Promise<boolean>']], description: 'Redoes the next edit; false when there is nothing to redo.' },
  { name: 'history', source: 'api', group: 'Undo and redo', signatures: [['', '{ undo: string[]; redo: string[] }']], description: 'What undo and redo would do (labels).' },

  // Designs and fields as documents
  { name: 'saveDesign', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'Design']], description: 'The design exactly as the CLI reads it (docs/design-format.md), with the mesh fingerprint.' },
  { name: 'loadDesign', source: 'api', group: 'Designs and fields as documents', signatures: [['design: Design, options?: { ignoreFingerprint?: boolean }', 'Promise<void>']], description: 'Replaces boundary condition, γ and all constraints with those of a design (one undo step).' },
  { name: 'hasUnsavedEdits', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'boolean']], description: 'Whether the design differs from the one last saved, loaded or opened with the model.' },
  { name: 'exportField', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'Promise<Record<string, unknown>>']], description: "The solved field as the CLI's -o FIELD.json writes it." },
  { name: 'exportFlowMap', source: 'api', group: 'Designs and fields as documents', signatures: [['options?: Partial<ExportOptions>', 'Promise<Uint8Array>']], description: 'The flow map PNG (docs/export.md): the same bytes as `tvf export` for this model file and field. A line or cross field is combed per atlas chart first (its sign flips only along the comb\'s cuts).' },
  { name: 'exportGlb', source: 'api', group: 'Designs and fields as documents', signatures: [['options?: Partial<ExportOptions>', 'Promise<Uint8Array>']], description: 'The one GLB export (docs/export.md): the model with the field attributes, the flow map and anisotropy material when asked, the design, and the synthesized texture when there is one, in one file. For a line or cross field the symmetry comes from the design: the directions are combed per atlas chart (KHR_materials_anisotropy does not see their sign) and _FIELD holds them per vertex.' },
  { name: 'exportRawField', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'Promise<string>']], description: 'A line or cross field (symmetry N ≥ 2) as Directional\'s raw field text: "N numF", then the N directions (x y z each, counter-clockwise about the normal) of every face of the welded mesh (docs/export.md), as `tvf export --rawfield` writes it. Rejects for a vector field.' },
  { name: 'exportOptions', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'ExportOptions']], description: 'The export options in force (the Export panel shows the same).' },
  { name: 'setExportOptions', source: 'api', group: 'Designs and fields as documents', signatures: [['options: Partial<ExportOptions>', 'void']], description: 'Changes some export options.' },
  { name: 'materialPreview', source: 'api', group: 'Designs and fields as documents', signatures: [['preset: MaterialPreset | null', 'Promise<void>']], description: "Shows (a preset) or hides (null) the exported GLB read back with three.js's GLTFLoader." },
  { name: 'materialPreviewInfo', source: 'api', group: 'Designs and fields as documents', signatures: [['', 'Promise<Record<string, unknown> | null>']], description: 'What the loader made of the previewed GLB, or null while the preview is off.' },

  // Autosave
  { name: 'autosaveVersions', source: 'api', group: 'Autosave', signatures: [['', 'Promise<AutosaveVersion[]>']], description: "The stored autosave versions of the current model's design, newest first." },
  { name: 'restoreAutosave', source: 'api', group: 'Autosave', signatures: [['id: number', 'Promise<void>']], description: 'Replaces the design with that autosave version (one undoable step).' },
  { name: 'autosaveIdle', source: 'api', group: 'Autosave', signatures: [['', 'Promise<true>']], description: 'Resolves when every autosave asked for so far has been written (or has failed and been reported).' },

  // Supervision of the core
  { name: 'cancel', source: 'api', group: 'Supervision of the core', signatures: [['', 'Promise<boolean>']], description: 'Stops the operation in flight by replacing the worker; false when nothing was in flight.' },
  { name: 'supervision', source: 'api', group: 'Supervision of the core', signatures: [['', 'Supervision']], description: 'How often the core was replaced, and the last failure.' },

  // Field and timings
  { name: 'faceVectors', source: 'api', group: 'Field and timings', signatures: [['', 'Float64Array']], description: "The field at each face's barycentre, 3 components per face (for N ≥ 2 a unit vector along one of its N directions)." },
  { name: 'vertexVectors', source: 'api', group: 'Field and timings', signatures: [['', 'Float64Array']], description: 'The field at each vertex, 3 components per vertex.' },
  { name: 'oneForm', source: 'api', group: 'Field and timings', signatures: [['', 'Float64Array']], description: 'The solution: one line integral per edge of edges().' },
  { name: 'hodge', source: 'api', group: 'Field and timings', signatures: [['', 'Promise<HodgeDecomposition>']], description: 'The Hodge decomposition of the current field: exact, coexact and harmonic parts (c = dα + δβ + h), made on first request.' },
  { name: 'singularities', source: 'api', group: 'Field and timings', signatures: [['', '{ vertex: number; index: number }[]']], description: "The field's singularities: an index per interior vertex that has one (an integer; a multiple of 1/N for a line or cross field)." },
  { name: 'stats', source: 'api', group: 'Field and timings', signatures: [['', 'Record<string, number | string | boolean>']], description: "The core's timings and sizes for the latest operations; \`preview\` is true while the field shown is a big model's preview (solved on a coarse copy), false for the exact field." },
  { name: 'settled', source: 'api', group: 'Field and timings', signatures: [['', 'Promise<void>']], description: "Resolves when the field shown is the exact one: at once on a small model; on a big one after the exact core has caught up with the preview's edits." },
  { name: 'perf', source: 'api', group: 'Field and timings', signatures: [['', 'Record<string, unknown>']], description: 'Page-side measurements (last worker request, last user action of each kind, restarts).' },

  // Views
  { name: 'views', source: 'api', group: 'Views', signatures: [['', 'Views']], description: 'The field views shown now.' },
  { name: 'setViews', source: 'api', group: 'Views', signatures: [['views: Partial<Views>', 'Views']], description: 'Turns field views on or off, several at once.' },
  { name: 'streamlines', source: 'api', group: 'Views', signatures: [['', 'number[][]']], description: 'The evenly spaced streamlines of the current field and spacing, as flat xyz arrays.' },
  { name: 'select', source: 'api', group: 'Views', signatures: [['id: number | null', 'void']], description: 'Selects a constraint for editing (null: none).' },
  { name: 'selected', source: 'api', group: 'Views', signatures: [['', 'number | null']], description: 'The id of the selected constraint, or null.' },

  // View helpers (for tests and embedding pages)
  { name: 'screenshot', source: 'api', group: 'View helpers', signatures: [['options?: { width?: number; height?: number; transparent?: boolean }', 'Promise<Blob>']], description: 'A PNG of the view, drawn again at width × height pixels (default: the canvas).' },
  { name: 'arrowInstances', source: 'api', group: 'View helpers', signatures: [['', '{ anchors: number[]; vectors: number[] }']], description: 'The arrows as drawn: anchor and vector of each, model units.' },
  { name: 'streamlineCues', source: 'api', group: 'View helpers', signatures: [['', '{ tip: number[]; back: number[] }[]']], description: 'The chevrons drawn on the streamlines: tip and middle of the back.' },
  { name: 'strokeCues', source: 'api', group: 'View helpers', signatures: [['', '{ uid: number; cues: { tip: number[]; back: number[] }[] }[]']], description: 'The chevrons drawn on the stroke handles, per stroke.' },
  { name: 'singularityMarkers', source: 'api', group: 'View helpers', signatures: [['', '{ vertex: number; corners: number[] }[]']], description: "Each singularity marker's vertex and the corners of its disc as drawn." },
  { name: 'projectToScreen', source: 'api', group: 'View helpers', signatures: [['xyz: [number, number, number]', '{ x: number; y: number }']], description: 'Client (CSS pixel) coordinates of a world-space point in the current view.' },
  { name: 'pick', source: 'api', group: 'View helpers', signatures: [['clientX: number, clientY: number', '{ face: number; bary: [number, number, number]; point: [number, number, number] } | null']], description: 'The surface point under a client pixel, or null off the model.' },
  { name: 'frame', source: 'api', group: 'View helpers', signatures: [["view?: 'home' | 'front' | 'back' | 'side' | 'top'", 'boolean']], description: 'Frames the whole model from a preset direction.' },
  { name: 'camera', source: 'api', group: 'View helpers', signatures: [['', '{ position: number[]; target: number[]; fov: number }']], description: 'The camera: position, orbit pivot (world coordinates) and field of view.' },
  { name: 'setCamera', source: 'api', group: 'View helpers', signatures: [['state: { position?: number[]; target?: number[] }', 'void']], description: 'Places the camera.' },

  // Texture synthesis
  { name: 'setExemplar', source: 'texture', group: 'Texture synthesis', signatures: [['source: ExemplarSource, options?: { size?: number }', 'Promise<Record<string, unknown>>']], description: 'Chooses and analyses the exemplar; a shown texture is resynthesized.' },
  { name: 'synthesize', source: 'texture', group: 'Texture synthesis', signatures: [['options?: SynthesisOptions', 'Promise<Record<string, unknown>>']], description: 'Synthesizes along the current field and shows the texture; field changes resynthesize until clearTexture(). Vector, line and cross fields (N = 1, 2, 4; a line or cross field combed per atlas chart); rejects other N with the reason.' },
  { name: 'synthesisStats', source: 'texture', group: 'Texture synthesis', signatures: [['', 'Record<string, unknown> | null']], description: 'The last synthesis: timings per level and in total, sizes, options, atlas.' },
  { name: 'synthesisProgress', source: 'texture', group: 'Texture synthesis', signatures: [['', '{ fraction: number; preview: boolean } | null']], description: 'Progress of the synthesis in flight, or null when none runs.' },
  { name: 'setTextureAutoUpdate', source: 'texture', group: 'Texture synthesis', signatures: [['on: boolean', 'void']], description: 'Resynthesize after every field change (on by default); off: field changes only mark the texture stale.' },
  { name: 'exportTexturePNG', source: 'texture', group: 'Texture synthesis', signatures: [['options?: { magnification?: number; resolution?: number }', 'Promise<Blob>']], description: 'The synthesized atlas texture as a PNG, rendered as the view renders it.' },
  { name: 'synthesisIdle', source: 'texture', group: 'Texture synthesis', signatures: [['', 'Promise<Record<string, unknown> | null>']], description: 'Resolves when no synthesis is queued, with the stats.' },
  { name: 'clearTexture', source: 'texture', group: 'Texture synthesis', signatures: [['', 'Promise<void>']], description: 'Back to the plain surface.' },
  { name: 'exemplarInfo', source: 'texture', group: 'Texture synthesis', signatures: [['', 'Record<string, unknown> | null']], description: 'The current exemplar: label, size, levels, analysis.' },
  { name: 'synthesisReadback', source: 'texture', group: 'Texture synthesis', signatures: [['', 'Promise<Record<string, unknown>>']], description: 'For tests: coordinates and Jacobian per atlas texel, the nearest-pixel colour image, the exemplar, the atlas UVs.' },
  { name: 'synthesisBench', source: 'texture', group: 'Texture synthesis', signatures: [['options?: { sizes?: number[] }', 'Promise<Record<string, unknown>>']], description: 'The synthesis benchmark.' },

  // The element itself
  { name: 'dispose', source: 'element', group: 'The element', signatures: [['', 'void']], description: 'Ends the worker, frees the WebGL contexts and clears the shadow root (removing the element does the same).' },

  // Test hooks
  { name: 'debugDelayExact', source: 'api', group: 'Test hooks', internal: true, signatures: [['ms: number', 'void']], description: 'Makes the exact factorization of the next loads wait ms first, so a preview surely leads.' },
  { name: 'debugTerminateCore', source: 'api', group: 'Test hooks', internal: true, signatures: [['', 'void']], description: 'Ends the core worker as a crash would.' },
  { name: 'debugHangCore', source: 'api', group: 'Test hooks', internal: true, signatures: [['ms: number', 'void']], description: 'Makes the core worker stop answering for ms milliseconds.' },
  { name: 'debugTrapCore', source: 'api', group: 'Test hooks', internal: true, signatures: [['', 'Promise<unknown>']], description: 'Makes the worker report what a wasm trap looks like.' },
  { name: 'debugSetFactorMemoryLimit', source: 'api', group: 'Test hooks', internal: true, signatures: [['bytes: number', 'Promise<true>']], description: "Sets the factor's memory limit (0: the wasm address space left)." },
  { name: 'debugCoreReadout', source: 'api', group: 'Test hooks', internal: true, signatures: [['', 'Promise<CoreReadout>']], description: 'What the core itself holds now, derived by the core on request.' },
  { name: 'debugTraceStreamlines', source: 'api', group: 'Test hooks', internal: true, signatures: [['', 'number[][]']], description: 'The streamlines traced on the page now, whatever the view holds.' },
  { name: 'debugGlPrograms', source: 'api', group: 'Test hooks', internal: true, signatures: [['', 'number']], description: "How many shader programs the viewer's renderer holds (views/shader-warm-up.js makes them all at the start)." },
  { name: 'debugSurfaceLayer', source: 'api', group: 'Test hooks', internal: true, signatures: [['minFaces?: number', '{ minFaces: number; drawn: number; copied: number; rect: { x: number; y: number; width: number; height: number } | null }']], description: 'Draws a surface of at least minFaces faces once per view and copies it under the field (views/surface-layer.js); how often it was drawn and copied, and the drawing-buffer pixels the copy covers (null: all).' },
  { name: 'debugComponent', source: 'api', group: 'Test hooks', internal: true, signatures: [["name: 'whole' | 'exact' | 'coexact' | 'harmonic'", 'Promise<FieldComponent>']], description: "The worker's component op: one part of the current field with its reconstructed vectors." },
];

// Events: CustomEvents that bubble and are composed, fired on the element. `detail`: [field, type, doc?].
export const EVENTS = [
  { name: 'load', detailType: 'LoadEventDetail', detail: [['info', 'MeshInfo']], description: 'A model is loaded and factored.' },
  { name: 'error', detailType: 'ErrorEventDetail', detail: [['code', 'ErrorCode', 'What failed: a model, a design, the texture, the core, a setting, an attribute, the autosave.'], ['message', 'string']], description: 'Something failed; code names what. The element also shows message in its banner.' },
  { name: 'fieldchange', detailType: 'FieldChangeEventDetail', detail: [['version', 'number'], ['stats', 'Record<string, number | string>']], description: 'After every completed change of the field (an edit, undo, redo, a model load).' },
  { name: 'constraintschange', detailType: 'ConstraintsChangeEventDetail', detail: [['constraints', 'Constraint[]']], description: 'The constraint list changed.' },
  { name: 'progress', detailType: 'ProgressEventDetail', detail: [['phase', 'string', "The core operation: 'loadMesh', 'add', 'remove', 'setBoundary', 'applyDesign', ..."], ['fraction', 'number', '0 when it starts, 1 when it ends.']], description: 'A core operation started (fraction 0) or ended (fraction 1).' },
  { name: 'corerestart', detailType: 'CoreRestartEventDetail', detail: [['kind', 'CoreFailureKind'], ['detail', 'string']], description: 'The core worker was replaced (it ended, failed, trapped, went silent, or was cancelled) and the model and design are back.' },
  { name: 'autosaveconflict', detailType: 'AutosaveConflictEventDetail', detail: [['model', 'string']], description: 'Another tab is editing the same model; both keep their autosave versions.' },
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
  { name: 'panels-toggle', description: 'The Panels button that opens the panels as drawers (below 900 px of element width)' },
  { name: 'status', description: 'Status bar' },
  { name: 'error', description: 'Error banner' },
  { name: 'progress', description: 'Progress bar' },
];
