// SPDX-License-Identifier: GPL-2.0-or-later
// The declared methods on what is seen: the views, the view helpers, texture synthesis, the element's own, and
// the test hooks that read the views and the core (Views to Test hooks in docs/js-api.md): data for
// declaration.js, which says what the fields mean. Imports nothing.

// Each group's source and section of docs/js-api.md, spread into its methods.
const VIEWS = { source: 'api', group: 'Views' };
const VIEW_HELPERS = { source: 'api', group: 'View helpers' };
const STRIPES = { source: 'api', group: 'Stripe patterns' };
const QUAD = { source: 'api', group: 'Quad meshes' };
const TEXTURE = { source: 'texture', group: 'Texture synthesis' };
const ELEMENT = { source: 'element', group: 'The element' };
const TEST_HOOKS = { source: 'api', group: 'Test hooks', internal: true };

export const VIEW_METHODS = [
  { name: 'views', ...VIEWS, signatures: [['', 'Views']], description: 'The field views shown now.' },
  {
    name: 'setViews', ...VIEWS,
    signatures: [['views: Partial<Views>', 'Views']],
    description: 'Turns field views on or off, several at once.',
  },
  {
    name: 'streamlines', ...VIEWS,
    signatures: [['', 'number[][]']],
    description: 'The evenly spaced streamlines of the current field and spacing, as flat xyz arrays.',
  },
  {
    name: 'select', ...VIEWS,
    signatures: [['id: number | null', 'void']],
    description: 'Selects a constraint for editing (null: none).',
  },
  {
    name: 'selected', ...VIEWS,
    signatures: [['', 'number | null']],
    description: 'The id of the selected constraint, or null.',
  },

  {
    name: 'setStripes', ...STRIPES,
    signatures: [['options: Partial<StripeOptions>', 'Promise<StripeState>']],
    description: "Shows or hides the field's stripe pattern and sets its frequency, profile, spacing, direction, " +
      'line width and colours.',
  },
  {
    name: 'stripes', ...STRIPES,
    signatures: [['', 'StripeState']],
    description: "The stripe pattern's options in force, whether it is shown, and the last pattern's stats.",
  },
  {
    name: 'stripesIdle', ...STRIPES,
    signatures: [['options?: { settled?: boolean }', 'Promise<StripeState>']],
    description: 'Resolves once the stripes shown are of the field the views draw and of the options; with ' +
      'settled, once they are the whole pattern (an edit is first solved where its field changed).',
  },

  {
    name: 'remesh', ...QUAD,
    signatures: [['options?: QuadRemeshOptions', 'Promise<QuadMesh>']],
    description: 'A quad mesh whose edges follow the cross field, made on a worker of its own (the design stays ' +
      "editable); no edit. Rejects with 'Quad meshes need a cross field' for another symmetry, or the core's reason.",
  },
  {
    name: 'cancelRemesh', ...QUAD,
    signatures: [['', 'boolean']],
    description: 'Stops the remeshing in flight (its worker ended at once); false when none was.',
  },
  {
    name: 'quadMesh', ...QUAD,
    signatures: [['', 'QuadMeshState']],
    description: "The Quad mesh panel's state: the run's stage, the target, the last quad mesh's stats, stale or not.",
  },
  {
    name: 'exportQuadObj', ...QUAD,
    signatures: [['', 'string']],
    description: 'The last quad mesh as OBJ text: its polygons as they are (f a b c d, 1-based).',
  },
  {
    name: 'exportQuadGlb', ...QUAD,
    signatures: [['', 'ArrayBuffer']],
    description: 'The last quad mesh as a GLB: a triangulated copy (each quad split along its shorter diagonal).',
  },

  {
    name: 'screenshot', ...VIEW_HELPERS,
    signatures: [['options?: { width?: number; height?: number; transparent?: boolean }', 'Promise<Blob>']],
    description: 'A PNG of the view, drawn again at width × height pixels (default: the canvas).',
  },
  {
    name: 'arrowInstances', ...VIEW_HELPERS,
    signatures: [['', '{ anchors: number[]; vectors: number[] }']],
    description: 'The arrows as drawn: anchor and vector of each, model units.',
  },
  {
    name: 'streamlineCues', ...VIEW_HELPERS,
    signatures: [['', '{ tip: number[]; back: number[] }[]']],
    description: 'The chevrons drawn on the streamlines: tip and middle of the back.',
  },
  {
    name: 'strokeCues', ...VIEW_HELPERS,
    signatures: [['', '{ uid: number; cues: { tip: number[]; back: number[] }[] }[]']],
    description: 'The chevrons drawn on the stroke handles, per stroke.',
  },
  {
    name: 'singularityMarkers', ...VIEW_HELPERS,
    signatures: [['', '{ vertex: number; corners: number[] }[]']],
    description: "Each singularity marker's vertex and the corners of its disc as drawn.",
  },
  {
    name: 'projectToScreen', ...VIEW_HELPERS,
    signatures: [['xyz: [number, number, number]', '{ x: number; y: number }']],
    description: 'Client (CSS pixel) coordinates of a world-space point in the current view.',
  },
  {
    name: 'pick', ...VIEW_HELPERS,
    signatures: [
      [
        'clientX: number, clientY: number',
        '{ face: number; bary: [number, number, number]; point: [number, number, number] } | null',
      ],
    ],
    description: 'The surface point under a client pixel, or null off the model.',
  },
  {
    name: 'frame', ...VIEW_HELPERS,
    signatures: [["view?: 'home' | 'front' | 'back' | 'side' | 'top'", 'boolean']],
    description: 'Frames the whole model from a preset direction.',
  },
  {
    name: 'camera', ...VIEW_HELPERS,
    signatures: [['', '{ position: number[]; target: number[]; fov: number }']],
    description: 'The camera: position, orbit pivot (world coordinates) and field of view.',
  },
  {
    name: 'setCamera', ...VIEW_HELPERS,
    signatures: [['state: { position?: number[]; target?: number[] }', 'void']],
    description: 'Places the camera.',
  },

  {
    name: 'setExemplar', ...TEXTURE,
    signatures: [['source: ExemplarSource, options?: { size?: number }', 'Promise<Record<string, unknown>>']],
    description: 'Chooses and analyses the exemplar; a shown texture is resynthesized.',
  },
  {
    name: 'synthesize', ...TEXTURE,
    signatures: [['options?: SynthesisOptions', 'Promise<Record<string, unknown>>']],
    description: 'Synthesizes along the current field and shows the texture; field changes resynthesize until ' +
      'clearTexture(). Vector, line and cross fields (N = 1, 2, 4; a line or cross field combed per atlas chart); ' +
      'rejects other N with the reason.',
  },
  {
    name: 'synthesisStats', ...TEXTURE,
    signatures: [['', 'Record<string, unknown> | null']],
    description: 'The last synthesis: timings per level and in total, sizes, options, atlas.',
  },
  {
    name: 'synthesisProgress', ...TEXTURE,
    signatures: [['', '{ fraction: number; preview: boolean } | null']],
    description: 'Progress of the synthesis in flight, or null when none runs.',
  },
  {
    name: 'setTextureAutoUpdate', ...TEXTURE,
    signatures: [['on: boolean', 'void']],
    description: 'Resynthesize after every field change (on by default); off: field changes only mark the texture ' +
      'stale.',
  },
  {
    name: 'exportTexturePNG', ...TEXTURE,
    signatures: [['options?: { magnification?: number; resolution?: number }', 'Promise<Blob>']],
    description: 'The synthesized atlas texture as a PNG, rendered as the view renders it.',
  },
  {
    name: 'synthesisIdle', ...TEXTURE,
    signatures: [['', 'Promise<Record<string, unknown> | null>']],
    description: 'Resolves when no synthesis is queued, with the stats.',
  },
  { name: 'clearTexture', ...TEXTURE, signatures: [['', 'Promise<void>']], description: 'Back to the plain surface.' },
  {
    name: 'exemplarInfo', ...TEXTURE,
    signatures: [['', 'Record<string, unknown> | null']],
    description: 'The current exemplar: label, size, levels, analysis.',
  },
  {
    name: 'synthesisReadback', ...TEXTURE,
    signatures: [['', 'Promise<Record<string, unknown>>']],
    description: 'For tests: coordinates and Jacobian per atlas texel, the nearest-pixel colour image, the exemplar, ' +
      'the atlas UVs.',
  },
  {
    name: 'synthesisBench', ...TEXTURE,
    signatures: [['options?: { sizes?: number[] }', 'Promise<Record<string, unknown>>']],
    description: 'The synthesis benchmark.',
  },

  {
    name: 'dispose', ...ELEMENT,
    signatures: [['', 'void']],
    description: 'Ends the worker, frees the WebGL contexts and clears the shadow root (removing the element does ' +
      'the same).',
  },

  {
    name: 'debugDelayExact', ...TEST_HOOKS,
    signatures: [['ms: number', 'void']],
    description: 'Makes the exact factorization of the next loads wait ms first, so a preview surely leads.',
  },
  {
    name: 'debugTextureFollowMs', ...TEST_HOOKS,
    signatures: [['ms: number | null', 'void']],
    description: "The texture's update time under which a field's frame waits for its texture (null: 250 ms), so " +
      'that a page test sees that wait whatever the machine.',
  },
  {
    name: 'debugStripesFollowMs', ...TEST_HOOKS,
    signatures: [['ms: number | null', 'void']],
    description: "An edit's stripes' time under which the next field's frame waits for its stripes (null: 250 ms), " +
      'so that a page test sees that wait whatever the machine.',
  },
  {
    name: 'debugTerminateCore', ...TEST_HOOKS,
    signatures: [['', 'void']],
    description: 'Ends the core worker as a crash would.',
  },
  {
    name: 'debugHangCore', ...TEST_HOOKS,
    signatures: [['ms: number', 'void']],
    description: 'Makes the core worker stop answering for ms milliseconds.',
  },
  {
    name: 'debugTrapCore', ...TEST_HOOKS,
    signatures: [['', 'Promise<unknown>']],
    description: 'Makes the worker report what a wasm trap looks like.',
  },
  {
    name: 'debugSetFactorMemoryLimit', ...TEST_HOOKS,
    signatures: [['bytes: number', 'Promise<true>']],
    description: "Sets the factor's memory limit (0: the wasm address space left).",
  },
  {
    name: 'debugCoreReadout', ...TEST_HOOKS,
    signatures: [['', 'Promise<CoreReadout>']],
    description: 'What the core itself holds now, derived by the core on request.',
  },
  {
    name: 'debugTraceStreamlines', ...TEST_HOOKS,
    signatures: [['', 'number[][]']],
    description: 'The streamlines traced on the page now, whatever the view holds.',
  },
  {
    name: 'debugGlPrograms', ...TEST_HOOKS,
    signatures: [['', 'number']],
    description: "How many shader programs the viewer's renderer holds (views/shader-warm-up.js makes them all at " +
      'the start).',
  },
  {
    name: 'debugRecordFrames', ...TEST_HOOKS,
    signatures: [['', 'number[]']],
    description: 'From now on, the time (performance.now()) of every frame the view draws, pushed onto the array ' +
      'returned.',
  },
  {
    name: 'debugSurfaceLayer', ...TEST_HOOKS,
    signatures: [
      [
        'minFaces?: number',
        '{ minFaces: number; drawn: number; copied: number; rect: { x: number; y: number; width: number; height: ' +
          'number } | null }',
      ],
    ],
    description: 'Draws a surface of at least minFaces faces once per view and copies it under the field ' +
      '(views/surface-layer.js); how often it was drawn and copied, and the drawing-buffer pixels the copy covers ' +
      '(null: all).',
  },
  {
    name: 'debugComponent', ...TEST_HOOKS,
    signatures: [["name: 'whole' | 'exact' | 'coexact' | 'harmonic'", 'Promise<FieldComponent>']],
    description: "The worker's component op: one part of the current field with its reconstructed vectors.",
  },
];
