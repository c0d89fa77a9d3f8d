// A consumer app bundled with esbuild that uses three.js itself: the package's code (its default, peer build)
// and three.js end up in app.js once; the element is told where its worker and wasm were copied
// (docs/embedding.md, "In a bundled app").
import { Scene } from 'three';
import { TangentFieldDesigner } from 'tangent-field-designer';

TangentFieldDesigner.assetBase = new URL('./tangent-field-designer/', import.meta.url).href;
window.__appScene = new Scene();
