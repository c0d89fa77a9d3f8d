// SPDX-License-Identifier: GPL-2.0-or-later
// The declared methods on the model, its design and its field (Models to Field and timings in docs/js-api.md):
// data for declaration.js, which says what the fields mean. Imports nothing.

// Each group's source and section of docs/js-api.md, spread into its methods.
const MODELS = { source: 'api', group: 'Models' };
const CONSTRAINTS = { source: 'api', group: 'Constraints' };
const UNDO = { source: 'api', group: 'Undo and redo' };
const DOCUMENTS = { source: 'api', group: 'Designs and fields as documents' };
const AUTOSAVE = { source: 'api', group: 'Autosave' };
const SUPERVISION = { source: 'api', group: 'Supervision of the core' };
const FIELD = { source: 'api', group: 'Field and timings' };

export const DESIGN_METHODS = [
  {
    name: 'loadModel', ...MODELS,
    signatures: [['source: ModelSource, options?: LoadModelOptions', 'Promise<MeshInfo>']],
    description: 'Loads a model (URL, File/Blob, bytes) as one transaction; resolves with its info(), rejects and ' +
      'keeps the current model on failure.',
  },
  { name: 'info', ...MODELS, signatures: [['', 'MeshInfo']], description: "The core's mesh report (as `tvf info`)." },
  {
    name: 'mesh', ...MODELS,
    signatures: [['', '{ positions: Float64Array; triangles: Int32Array }']],
    description: 'Copies of the welded mesh: 3 coordinates per vertex, 3 vertex indices per face.',
  },
  {
    name: 'edges', ...MODELS,
    signatures: [['', 'Int32Array']],
    description: "The core's edges, 2 vertex indices per edge, lower index first.",
  },

  {
    name: 'addStroke', ...CONSTRAINTS,
    signatures: [['points: SurfacePoint[], options?: { strength?: number; weight?: number }', 'Promise<number>']],
    description: "A stroke through surface points; resolves with the new constraint's id.",
  },
  {
    name: 'addVector', ...CONSTRAINTS,
    signatures: [['face: number, vector: [number, number, number], options?: { weight?: number }', 'Promise<number>']],
    description: 'The field in a triangle should be this vector (projected into its plane).',
  },
  {
    name: 'addEdge', ...CONSTRAINTS,
    signatures: [['edge: [number, number], value: number, options?: { weight?: number }', 'Promise<number>']],
    description: 'The line integral of the field along an edge should be this value.',
  },
  {
    name: 'addSource', ...CONSTRAINTS,
    signatures: [['vertex: number, options?: { strength?: number }', 'Promise<number>']],
    description: 'A source at a vertex with total outflow strength.',
  },
  {
    name: 'addSink', ...CONSTRAINTS,
    signatures: [['vertex: number, options?: { strength?: number }', 'Promise<number>']],
    description: 'A sink at a vertex with total inflow strength.',
  },
  {
    name: 'addVortex', ...CONSTRAINTS,
    signatures: [['face: number, options?: { strength?: number }', 'Promise<number>']],
    description: 'A vortex in a triangle with circulation strength (positive: counter-clockwise).',
  },
  {
    name: 'remove', ...CONSTRAINTS,
    signatures: [['id: number', 'Promise<true>'], ['', 'void']],
    description: "With an id: removes that constraint. Without: the DOM's ChildNode.remove() (and so dispose()).",
  },
  {
    name: 'setWeight', ...CONSTRAINTS,
    signatures: [['id: number, weight: number', 'Promise<true>']],
    description: 'Changes the weight of a stroke, vector or edge constraint.',
  },
  {
    name: 'setStrength', ...CONSTRAINTS,
    signatures: [['id: number, strength: number', 'Promise<true>']],
    description: 'Changes the strength of a stroke, source, sink or vortex.',
  },
  {
    name: 'addSingularity', ...CONSTRAINTS,
    signatures: [['vertex: number, index: number', 'Promise<number>']],
    description: 'Prescribes a singularity: the field has this index (a nonzero multiple of 1/N) at this interior ' +
      "vertex. Resolves with its constraint id; rejects with the core's reason (a boundary vertex, a bad index, a " +
      'vertex that has one), the design unchanged.',
  },
  {
    name: 'moveSingularity', ...CONSTRAINTS,
    signatures: [['id: number, vertex: number', 'Promise<true>']],
    description: 'Moves a prescribed singularity to another vertex, keeping its id and index.',
  },
  {
    name: 'removeSingularity', ...CONSTRAINTS,
    signatures: [['id: number', 'Promise<true>']],
    description: 'Removes a prescribed singularity (as remove(id); undo brings back its vertex and index).',
  },
  {
    name: 'setFeatures', ...CONSTRAINTS,
    signatures: [['features: Partial<FeatureSettings>', 'Promise<void>']],
    description: 'Sets the sharp features the field follows: edges sharper than `angle` degrees (0: none; a new ' +
      'design starts at 35 on a creased model, at 0 on a curved one made of facets: `info().folds`), plus `add`, ' +
      'minus `remove` (vertex pairs); keys left out keep their values.',
  },
  {
    name: 'features', ...CONSTRAINTS,
    signatures: [['', 'Features']],
    description: 'The sharp features as set, and `edges`: the vertex pairs the field follows.',
  },
  {
    name: 'setExactSingularities', ...CONSTRAINTS,
    signatures: [['exact: boolean', 'Promise<void>']],
    description: 'true: the field has exactly the prescribed singularities, none when none are prescribed (a ' +
      "torus's cross field without any); false (the default): with none prescribed the smoothest field places its " +
      'own. One undoable step; the Field panel\'s "Only prescribed singularities".',
  },
  {
    name: 'loadSing', ...CONSTRAINTS,
    signatures: [['text: string', 'Promise<number[]>']],
    description: "Adds the singularities of a Directional .sing file (its text) to the design as one undoable " +
      'step, all or none; resolves with their constraint ids. Rejects with the line or the singularity refused.',
  },
  {
    name: 'constraints', ...CONSTRAINTS,
    signatures: [['', 'Constraint[]']],
    description: 'The constraints in id order, each in the design format plus its id.',
  },
  {
    name: 'setBoundary', ...CONSTRAINTS,
    signatures: [['boundary: Boundary', 'Promise<void>']],
    description: 'Sets the boundary condition (refactors).',
  },
  {
    name: 'setGamma', ...CONSTRAINTS,
    signatures: [['gamma: number', 'Promise<void>']],
    description: 'Sets the bi-Laplacian smoothness γ ≥ 0 (refactors).',
  },
  {
    name: 'setSymmetry', ...CONSTRAINTS,
    signatures: [['n: number', 'Promise<Constraint[]>']],
    description: 'Sets the symmetry N (1 vector, 2 line, 4 cross; 1–6) as one undoable step; ' +
      'for N ≥ 2 it removes ' +
      'the sources, sinks, vortices and edge constraints and resolves with them (undo restores them).',
  },
  {
    name: 'setCurvatureAlignment', ...CONSTRAINTS,
    signatures: [['strength: number', 'Promise<void>']],
    description: 'Pulls a line or cross field (even N) toward the principal curvature directions with this strength ' +
      '≥ 0 (0: off).',
  },
  {
    name: 'settings', ...CONSTRAINTS,
    signatures: [['', 'Settings']],
    description: 'The current boundary condition, γ, symmetry, curvature alignment and exactSingularities.',
  },

  {
    name: 'undo', ...UNDO,
    signatures: [['', 'Promise<boolean>']],
    description: 'Undoes the last edit; false when there is nothing to undo.',
  },
  {
    name: 'redo', ...UNDO,
    signatures: [['', 'Promise<boolean>']],
    description: 'Redoes the next edit; false when there is nothing to redo.',
  },
  {
    name: 'history', ...UNDO,
    signatures: [['', '{ undo: string[]; redo: string[] }']],
    description: 'What undo and redo would do (labels).',
  },

  {
    name: 'saveDesign', ...DOCUMENTS,
    signatures: [['', 'Design']],
    description: 'The design exactly as the CLI reads it (docs/design-format.md), with the mesh fingerprint.',
  },
  {
    name: 'loadDesign', ...DOCUMENTS,
    signatures: [['design: Design, options?: { ignoreFingerprint?: boolean }', 'Promise<void>']],
    description: 'Replaces boundary condition, γ and all constraints with those of a design (one undo step).',
  },
  {
    name: 'hasUnsavedEdits', ...DOCUMENTS,
    signatures: [['', 'boolean']],
    description: 'Whether the design differs from the one last saved, loaded or opened with the model.',
  },
  {
    name: 'exportField', ...DOCUMENTS,
    signatures: [['', 'Promise<Record<string, unknown>>']],
    description: "The solved field as the CLI's -o FIELD.json writes it.",
  },
  {
    name: 'exportFlowMap', ...DOCUMENTS,
    signatures: [['options?: Partial<ExportOptions>', 'Promise<Uint8Array>']],
    description: 'The flow map PNG (docs/export.md): the same bytes as `tvf export` for this model file and field. ' +
      "A line or cross field is combed per atlas chart first (its sign flips only along the comb's cuts).",
  },
  {
    name: 'exportGlb', ...DOCUMENTS,
    signatures: [['options?: Partial<ExportOptions>', 'Promise<Uint8Array>']],
    description: 'The one GLB export (docs/export.md): the model with the field attributes, the flow map and ' +
      'anisotropy material when asked, the design, and the synthesized texture when there is one, in one file. For ' +
      'a line or cross field the symmetry comes from the design: the directions are combed per atlas chart ' +
      '(KHR_materials_anisotropy does not see their sign) and _FIELD holds them per vertex.',
  },
  {
    name: 'exportRawField', ...DOCUMENTS,
    signatures: [['', 'Promise<string>']],
    description: 'A line or cross field (symmetry N ≥ 2) as Directional\'s raw field text: "N numF", then the ' +
      'N directions (x y z each, counter-clockwise about the normal) of every face of the welded mesh ' +
      '(docs/export.md), as `tvf export --rawfield` writes it. Rejects for a vector field.',
  },
  {
    name: 'exportSing', ...DOCUMENTS,
    signatures: [['', 'Promise<string>']],
    description: "Every singularity of the field, prescribed or placed by it, as Directional's .sing text " +
      '(docs/export.md), as `tvf export --sing` writes it.',
  },
  {
    name: 'exportRosy', ...DOCUMENTS,
    signatures: [['', 'Promise<string>']],
    description: "A cross field (N = 4) as QuadWild's .rosy text, as `tvf export --rosy` writes it. Rejects for " +
      'any other N.',
  },
  {
    name: 'exportSharp', ...DOCUMENTS,
    signatures: [['', 'Promise<string>']],
    description: "The feature edges in use (and the border) as QuadWild's .sharp text, as `tvf export --sharp` " +
      'writes it.',
  },
  {
    name: 'exportOptions', ...DOCUMENTS,
    signatures: [['', 'ExportOptions']],
    description: 'The export options in force (the Export panel shows the same).',
  },
  {
    name: 'setExportOptions', ...DOCUMENTS,
    signatures: [['options: Partial<ExportOptions>', 'void']],
    description: 'Changes some export options.',
  },
  {
    name: 'materialPreview', ...DOCUMENTS,
    signatures: [['preset: MaterialPreset | null', 'Promise<void>']],
    description: "Shows (a preset) or hides (null) the exported GLB read back with three.js's GLTFLoader.",
  },
  {
    name: 'materialPreviewInfo', ...DOCUMENTS,
    signatures: [['', 'Promise<Record<string, unknown> | null>']],
    description: 'What the loader made of the previewed GLB, or null while the preview is off.',
  },

  {
    name: 'autosaveVersions', ...AUTOSAVE,
    signatures: [['', 'Promise<AutosaveVersion[]>']],
    description: "The stored autosave versions of the current model's design, newest first.",
  },
  {
    name: 'restoreAutosave', ...AUTOSAVE,
    signatures: [['id: number', 'Promise<void>']],
    description: 'Replaces the design with that autosave version (one undoable step).',
  },
  {
    name: 'autosaveIdle', ...AUTOSAVE,
    signatures: [['', 'Promise<true>']],
    description: 'Resolves when every autosave asked for so far has been written (or has failed and been reported).',
  },

  {
    name: 'cancel', ...SUPERVISION,
    signatures: [['', 'Promise<boolean>']],
    description: 'Stops the operation in flight by replacing the worker; false when nothing was in flight.',
  },
  {
    name: 'supervision', ...SUPERVISION,
    signatures: [['', 'Supervision']],
    description: 'How often the core was replaced, and the last failure.',
  },

  {
    name: 'faceVectors', ...FIELD,
    signatures: [['', 'Float64Array']],
    description: "The field at each face's barycentre, 3 components per face (for N ≥ 2 a unit vector along one of " +
      'its N directions).',
  },
  {
    name: 'vertexVectors', ...FIELD,
    signatures: [['', 'Float64Array']],
    description: 'The field at each vertex, 3 components per vertex.',
  },
  {
    name: 'oneForm', ...FIELD,
    signatures: [['', 'Float64Array']],
    description: 'The solution: one line integral per edge of edges().',
  },
  {
    name: 'hodge', ...FIELD,
    signatures: [['', 'Promise<HodgeDecomposition>']],
    description: 'The Hodge decomposition of the current field: exact, coexact and harmonic parts ' +
      '(c = dα + δβ + h), ' +
      'made on first request.',
  },
  {
    name: 'singularities', ...FIELD,
    signatures: [['', 'Singularity[]']],
    description: "The field's singularities: an index per interior vertex that has one (an integer; a multiple of " +
      '1/N for a line or cross field), `prescribed` when the design prescribes it (then with its constraint id).',
  },
  {
    name: 'singularitySummary', ...FIELD,
    signatures: [['', 'SingularitySummary']],
    description: 'What the prescribed singularities leave to the field: the Euler characteristic, the prescribed ' +
      'index and the index the field places itself, and `exact`: whether the design asks for only the prescribed.',
  },
  {
    name: 'stats', ...FIELD,
    signatures: [['', 'Record<string, number | string | boolean>']],
    description: "The core's timings and sizes for the latest operations; `preview` is true while the field shown is " +
      "a big model's preview (solved on a coarse copy), false for the exact field.",
  },
  {
    name: 'settled', ...FIELD,
    signatures: [['', 'Promise<void>']],
    description: 'Resolves when the field shown is the exact one: at once on a small model; on a big one after the ' +
      "exact core has caught up with the preview's edits.",
  },
  {
    name: 'perf', ...FIELD,
    signatures: [['', 'Record<string, unknown>']],
    description: 'Page-side measurements (last worker request, last user action of each kind, restarts).',
  },
];
