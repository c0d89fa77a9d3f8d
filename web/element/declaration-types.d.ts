// SPDX-License-Identifier: GPL-2.0-or-later
// The types the signatures of declaration.js use, in TypeScript: scripts/gen-api.mjs copies what follows this
// comment into types/element.d.ts as it is, after the string unions of declaration.js's ENUMS (CoreFailureKind
// and the others), which these types refer to by name.

/** A point on the surface: barycentric coordinates in a face of the core's welded mesh. */
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
  /**
   * GLB: the synthesized texture as base colour — 'auto' (default): when one is shown; true: required; false:
   * never.
   */
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
  /** true: the field has exactly the prescribed singularities, none when none are prescribed. */
  exactSingularities: boolean;
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
  /** How the interior edges fold (by the angle between their faces' normals): gradually is 3–35°, sharply over
   * 35°; `longCurveEdges`, the sharp edges on feature curves at least a tenth of the bounding box's diagonal long.
   * A new design starts at `suggestedFeatureAngle`: 35 where at least a fifth of the folding edges fold sharply or
   * 60 % of the sharp ones lie on long curves (a creased model), 0 (no features) on a curved surface of facets. */
  folds?: {
    interiorEdges: number; gradualEdges: number; sharpEdges: number; longCurveEdges: number;
    sharpShare: number; longCurveShare: number; suggestedFeatureAngle: number;
  };
  [key: string]: unknown;
}

export type ConstraintSpec =
  | { type: 'stroke'; points: SurfacePoint[]; strength: number; weight: number }
  | { type: 'vector'; face: number; vector: [number, number, number]; weight: number }
  | { type: 'edge'; edge: [number, number]; value: number; weight: number }
  | { type: 'source' | 'sink'; vertex: number; strength: number }
  | { type: 'vortex'; face: number; strength: number }
  | { type: 'singularity'; vertex: number; index: number };

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
  /** Prescribed singularities: an index (a nonzero multiple of 1/N) at an interior vertex. */
  singularities?: { vertex: number; index: number }[];
  /** true: the field has exactly the prescribed singularities, none when none are prescribed (absent: false). */
  exactSingularities?: boolean;
  /** Edges whose dihedral angle exceeds this many degrees are features (0 or absent: none). */
  featureAngle?: number;
  /** Feature edges added to and removed from those the angle finds, as vertex pairs. */
  featureEdges?: { add: [number, number][]; remove: [number, number][] };
  [key: string]: unknown;
}

/** One of the field's singularities; a prescribed one carries its constraint id. */
export interface Singularity {
  vertex: number;
  /** An integer; a multiple of 1/N for a line or cross field. */
  index: number;
  /** Whether the design prescribes this index at this vertex (else the field placed it itself). */
  prescribed: boolean;
  id?: number;
}

/** What the prescribed singularities leave to the field (singularitySummary()). */
export interface SingularitySummary {
  /** 'none': nothing prescribed; 'exact': the field has exactly the prescribed singularities; 'free': it places
   * freeIndex = eulerCharacteristic - prescribedIndex itself. */
  mode: 'none' | 'exact' | 'free';
  eulerCharacteristic: number;
  prescribedIndex: number;
  freeIndex: number;
  /** The design asks for exactly the prescribed singularities (setExactSingularities). */
  exact: boolean;
}

/** The sharp features: the detection angle (degrees, 0: none) and the edits, as vertex pairs. */
export interface FeatureSettings {
  angle: number;
  add: [number, number][];
  remove: [number, number][];
}

/** The features as set, and the edges the field follows ([a, b] vertex pairs). */
export interface Features extends FeatureSettings {
  edges: [number, number][];
}

/** Stripe pattern options (setStripes; docs/stripes.md). */
export interface StripeOptions {
  /** Shown in place of the surface's colour. */
  visible: boolean;
  /** Stripes per unit length of the model; null: about 40 across the model's bounding-box diagonal. */
  frequency: number | null;
  /** 'stripes' | 'wood' | 'grid' | 'bricks' | 'weave' (a cross field: grid, bricks or weave); null: the field's default. */
  profile: 'stripes' | 'wood' | 'grid' | 'bricks' | 'weave' | null;
  /** 0..1: denser stripes where a vector field is stronger (0: even spacing). */
  magnitudeSpacing: number;
  /** The spacing gives way so that the stripes follow the field exactly (default true). */
  adaptSpacing: boolean;
  /** A vector or line field's stripes across it instead of along it (default false; a cross field has both). */
  across: boolean;
  /** The lines' share of a period, in (0, 1] (dark bands, grid lines, mortar, threads); null: the profile's own. */
  width: number | null;
  /** '#rrggbb' (or 0xrrggbb). */
  light: string | number;
  dark: string | number;
}

/** The options in force, and the last pattern's stats. */
export interface StripeState {
  visible: boolean;
  frequency: number;
  profile: 'stripes' | 'wood' | 'grid' | 'bricks' | 'weave';
  magnitudeSpacing: number;
  adaptSpacing: boolean;
  /** Stripes across the field (false for a cross field, which has both directions). */
  across: boolean;
  /** The lines' width drawn: the one asked, or the profile's (stripes 0.5, wood 0.7, grid, bricks 0.12, weave 1). */
  width: number;
  light: string;
  dark: string;
  stats: {
    /** The field is zero everywhere (no direction to follow): no pattern is shown, families 0, nothing else. */
    zeroField?: boolean;
    families: number;
    iterations: number;
    residual: number;
    /** An edit's local update (solved where its field changed), not yet followed by the whole pattern. */
    localUpdate: boolean;
    localVertices: number;
    workerMs: number;
    /** Made by the worker right after the edit's field, before the page asked. */
    madeAhead?: boolean;
    /** From the page's request to the stripes drawn, and the drawing alone. */
    roundTripMs: number;
    drawMs: number;
    /** When they were drawn (performance.now()). */
    drawnAt: number;
  } | null;
  /** The stripes shown are a whole pattern (false: an edit's local update, the whole pattern to follow). */
  settled: boolean;
  error: string | null;
}

/** The target size of a remesh (remesh()): exactly one of the two. */
export type QuadRemeshOptions =
  /** The quads' edge length, in the model's units. */
  | { edgeLength: number }
  /** About this many quads (the surface's area over it gives the edge length). */
  | { quads: number };

/** The statistics of a quad mesh (the core's, core/quad/quad_mesh_stats.h). */
export interface QuadMeshStats {
  faces: number;
  quads: number;
  vertices: number;
  /** quads / faces, 0..1. */
  quadShare: number;
  /** Interior vertices whose valence is not 4. */
  irregularVertices: number;
  fieldSingularities: number;
  /** Share of the irregular vertices within two edge lengths of a field singularity, 0..1. */
  irregularNearSingularity: number;
  /** Angle between the quad edges and the nearest field direction, degrees. */
  edgeAngleMedianDeg: number;
  edgeAngleP90Deg: number;
  /** Hausdorff distance to the model over its bounding-box diagonal. */
  hausdorffRelative: number;
  aspectMedian: number;
  flippedFaces: number;
  degenerateFaces: number;
  manifold: boolean;
  eulerCharacteristic: number;
  /** The edge length used. */
  edgeLength: number;
  /** The design's feature curves at least an edge length long, and those let go where the grid folded beside
   * them (features closer together than a quad). */
  featureCurves: number;
  releasedFeatureCurves: number;
  /** The core's time, ms. */
  ms: number;
  /** And the core's other measures (stageMs: each stage's time, ...). */
  [key: string]: unknown;
}

/** A quad mesh (remesh()): polygons in CSR form, counter-clockwise; nearly all are quads. */
export interface QuadMesh {
  /** 3 per vertex. */
  positions: Float64Array;
  /** faces + 1: face k is faceVertices[faceStart[k] .. faceStart[k + 1]). */
  faceStart: Int32Array;
  faceVertices: Int32Array;
  /** The interior vertices whose valence is not 4. */
  irregular: Int32Array;
  stats: QuadMeshStats;
}

/** The Quad mesh panel's state (quadMesh()). */
export interface QuadMeshState {
  running: boolean;
  /** The core's stage while running, else null. */
  stage: string | null;
  /** 0..1 while running. */
  fraction: number;
  target: QuadRemeshOptions;
  /** The wireframe is shown (the panel's Show). */
  visible: boolean;
  hasResult: boolean;
  /** The design changed since the quad mesh was made. */
  stale: boolean;
  stats: QuadMeshStats | null;
  error: string | null;
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
  /**
   * The part of the Hodge decomposition every view draws (singularity markers stay the whole field's): 'exact'
   * curl-free, 'coexact' divergence-free.
   */
  component: 'whole' | 'exact' | 'coexact' | 'harmonic';
}

export interface LoadModelOptions {
  name?: string;
  format?: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '';
  companions?: File[];
  /** false: do not restore the autosaved design (autosave is only ever on with the `autosave` attribute). */
  restore?: boolean;
  /**
   * A mesh with at least this many edges opens with a preview field solved on a coarse copy, the exact field
   * following (default 300000; 0: never).
   */
  previewEdges?: number;
}

export type ModelSource = string | URL | Blob | ArrayBuffer | ArrayBufferView;

/** One stored autosave version of the current model's design. */
export interface AutosaveVersion {
  id: number;
  /** ISO 8601 time of the save. */
  savedAt: string;
  /** The tab that saved it; `mine`: this tab. */
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

/** One part of the field as the worker's `component` op returns it. */
export interface FieldComponent {
  oneForm: Float64Array;
  faceVectors: Float64Array;
  vertexVectors: Float64Array;
}

export interface SynthesisOptions {
  /** Atlas side, a power of two, or 'auto' (256–1024 by face count and curvature). */
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
  /** Faces whose field goes to the GPU per task (default 98304): a big model's field is uploaded a slice per frame. */
  sliceFaces?: number;
  /**
   * Degrees (default 1): a run with the atlas, exemplar and options of the one before makes again only the texels
   * whose field turned or scaled by more than this since they were made, and two texels round them; 0: every run whole.
   */
  localDegrees?: number;
}

export type ExemplarSource =
  | string
  | URL
  | Blob
  | ImageData
  | ImageBitmap
  | { procedural: string; size?: number; seed?: number };
