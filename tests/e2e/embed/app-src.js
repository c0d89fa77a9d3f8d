// A consumer app bundled with esbuild: the package's code ends up in app.js, so the element is told where
// its worker and wasm were copied (docs/embedding.md, "Bundlers").
import { TangentFieldDesigner } from 'tangent-field-designer';

TangentFieldDesigner.assetBase = new URL('./tangent-field-designer/', import.meta.url).href;
