// SPDX-License-Identifier: GPL-2.0-or-later
// Types of <tangent-field-designer> (hand-written; docs/embedding.md and docs/js-api.md describe the same).

/** A point on the surface: barycentric coordinates in a face of the core's welded mesh. */
export interface SurfacePoint {
  face: number;
  bary: [number, number, number];
}

/** Flow map and GLB export options (docs/export.md). */
export interface ExportOptions {
  size: number;
  convention: 'gltf' | 'opengl';
  bits: 8 | 16;
  strength: number;
  rotation: number;
  embedFlowMap?: boolean;
  embedDesign?: boolean;
}

export type Boundary = 'free' | 'tangential' | 'normal' | { angle: number };
export type Tool = 'orbit' | 'select' | 'stroke' | 'vector' | 'source' | 'sink' | 'vortex';
export type Controls = 'full' | 'minimal' | 'none';

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
  constraints: ConstraintSpec[];
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
}

export interface LoadModelOptions {
  name?: string;
  format?: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '';
  companions?: File[];
  /** false: do not restore the autosaved design (autosave is only ever on with the `autosave` attribute). */
  restore?: boolean;
}

export type ModelSource = string | URL | Blob | ArrayBuffer | ArrayBufferView;

export interface LoadEventDetail {
  info: MeshInfo;
}
export interface ErrorEventDetail {
  /** 'model' | 'design' | 'texture' | 'core' | 'setting' | 'attribute' */
  code: 'model' | 'design' | 'texture' | 'core' | 'setting' | 'attribute';
  message: string;
}
export interface FieldChangeEventDetail {
  version: number;
  stats: Record<string, number>;
}
export interface ConstraintsChangeEventDetail {
  constraints: Constraint[];
}
export interface ProgressEventDetail {
  /** The core operation: 'loadMesh', 'add', 'remove', 'setBoundary', 'applyDesign', ... */
  phase: string;
  fraction: number;
}

export interface TangentFieldDesignerEventMap {
  load: CustomEvent<LoadEventDetail>;
  error: CustomEvent<ErrorEventDetail>;
  fieldchange: CustomEvent<FieldChangeEventDetail>;
  constraintschange: CustomEvent<ConstraintsChangeEventDetail>;
  progress: CustomEvent<ProgressEventDetail>;
}

export interface SynthesisOptions {
  resolution?: number;
  featureScale?: number;
  magnitudeExponent?: number;
  jitter?: number;
  passes?: number;
  kappa?: number;
  seed?: number;
  seams?: boolean;
  gutter?: number;
  timing?: 'levels' | 'total';
}

export declare class TangentFieldDesigner extends HTMLElement {
  /** Folder (URL) with the package's entry module, core-worker.js and wasm/; default: next to this module. */
  static assetBase: string | null;
  static readonly DEFAULT_WEIGHT: number;
  readonly DEFAULT_WEIGHT: number;

  // Reflected attributes.
  src: string | null;
  design: string | null;
  boundary: string | null;
  gamma: number;
  tool: Tool | null;
  /** Reading gives the views() method (js-api.md); assigning a string sets the `views` attribute. */
  get views(): () => Views;
  set views(value: string | null);
  controls: Controls | null;
  readonly: boolean;
  autosave: string | null;
  exemplar: string | null;
  assetBase: string | null;

  /** Resolves when the core is up and, with `src`, the model is loaded and factored. */
  readonly ready: Promise<void>;
  /** Ends the worker and frees the WebGL contexts (removing the element does the same). */
  dispose(): void;

  loadModel(source: ModelSource, options?: LoadModelOptions): Promise<MeshInfo>;
  info(): MeshInfo;
  mesh(): { positions: Float64Array; triangles: Int32Array };
  edges(): Int32Array;

  addStroke(points: SurfacePoint[], options?: { strength?: number; weight?: number }): Promise<number>;
  addVector(face: number, vector: [number, number, number], options?: { weight?: number }): Promise<number>;
  addEdge(edge: [number, number], value: number, options?: { weight?: number }): Promise<number>;
  addSource(vertex: number, options?: { strength?: number }): Promise<number>;
  addSink(vertex: number, options?: { strength?: number }): Promise<number>;
  addVortex(face: number, options?: { strength?: number }): Promise<number>;
  /** With an id: removes that constraint. Without: the DOM's ChildNode.remove() (and so dispose()). */
  remove(id: number): Promise<true>;
  remove(): void;
  setWeight(id: number, weight: number): Promise<true>;
  setStrength(id: number, strength: number): Promise<true>;
  constraints(): Constraint[];
  setBoundary(boundary: Boundary): Promise<void>;
  setGamma(gamma: number): Promise<void>;
  settings(): { boundary: Boundary; gamma: number };

  undo(): Promise<boolean>;
  redo(): Promise<boolean>;
  history(): { undo: string[]; redo: string[] };

  saveDesign(): Design;
  loadDesign(design: Design, options?: { ignoreFingerprint?: boolean }): Promise<void>;
  hasUnsavedEdits(): boolean;
  frame(view?: 'home' | 'front' | 'back' | 'side' | 'top'): boolean;
  camera(): { position: number[]; target: number[]; fov: number };
  setCamera(state: { position?: number[]; target?: number[] }): void;
  exportField(): Promise<Record<string, unknown>>;
  /** docs/export.md: the same bytes as `tvf export` for this model file and field. */
  exportFlowMap(options?: Partial<ExportOptions>): Promise<Uint8Array>;
  exportGlb(options?: Partial<ExportOptions>): Promise<Uint8Array>;
  exportOptions(): ExportOptions;
  setExportOptions(options: Partial<ExportOptions>): void;
  materialPreview(preset: 'brushed metal' | 'satin' | null): Promise<void>;
  materialPreviewInfo(): Promise<Record<string, unknown> | null>;

  faceVectors(): Float64Array;
  vertexVectors(): Float64Array;
  oneForm(): Float64Array;
  singularities(): { vertex: number; index: number }[];
  stats(): Record<string, number>;

  select(id: number | null): void;
  selected(): number | null;
  setViews(views: Partial<Views>): Views;
  streamlines(): number[][];
  perf(): Record<string, unknown>;
  projectToScreen(xyz: [number, number, number]): { x: number; y: number };
  screenshot(options?: { width?: number; height?: number; transparent?: boolean }): Promise<Blob>;
  arrowInstances(): { anchors: number[]; vectors: number[] };
  streamlineCues(): { tip: number[]; back: number[] }[];
  strokeCues(): { uid: number; cues: { tip: number[]; back: number[] }[] }[];
  singularityMarkers(): { vertex: number; corners: number[] }[];
  pick(clientX: number, clientY: number): { face: number; bary: [number, number, number]; point: [number, number, number] } | null;

  setExemplar(source: string | URL | Blob | ImageData | ImageBitmap | { procedural: string; size?: number; seed?: number }, options?: { size?: number }): Promise<Record<string, unknown>>;
  synthesize(options?: SynthesisOptions): Promise<Record<string, unknown>>;
  synthesisStats(): Record<string, unknown> | null;
  synthesisIdle(): Promise<Record<string, unknown> | null>;
  /** Progress of the synthesis in flight, or null when none runs. */
  synthesisProgress(): { fraction: number; preview: boolean } | null;
  /** Resynthesize after every field change (on by default). */
  setTextureAutoUpdate(on: boolean): void;
  clearTexture(): Promise<void>;
  exemplarInfo(): Record<string, unknown> | null;
  exportTexturePNG(options?: { magnification?: 1 | 2 | 4 }): Promise<Blob>;
  exportGLB(): Promise<Blob>;
  synthesisReadback(): Promise<Record<string, unknown>>;
  synthesisBench(options?: { sizes?: number[] }): Promise<Record<string, unknown>>;

  addEventListener<K extends keyof TangentFieldDesignerEventMap>(
    type: K,
    listener: (this: TangentFieldDesigner, event: TangentFieldDesignerEventMap[K]) => unknown,
    options?: boolean | AddEventListenerOptions,
  ): void;
  addEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | AddEventListenerOptions): void;
  removeEventListener<K extends keyof TangentFieldDesignerEventMap>(
    type: K,
    listener: (this: TangentFieldDesigner, event: TangentFieldDesignerEventMap[K]) => unknown,
    options?: boolean | EventListenerOptions,
  ): void;
  removeEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | EventListenerOptions): void;
}

export declare const TAG_NAME: 'tangent-field-designer';

/** Registers the element under tagName (default tangent-field-designer) unless taken; returns its constructor. */
export declare function define(tagName?: string): typeof TangentFieldDesigner;

declare global {
  interface HTMLElementTagNameMap {
    'tangent-field-designer': TangentFieldDesigner;
  }
}
