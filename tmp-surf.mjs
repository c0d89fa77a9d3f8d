import { readFileSync } from 'node:fs';
import { Surface } from './web/geometry/surface.js';
import { pageSurface } from './web/geometry/mesh-bvh-transfer.js';
import { torus } from './web/core/preview/warm-up.js';
import { loadCore } from './web/core/core-client.js';
const core = await loadCore('file:///work/main/dist/');
core.readModel(new Uint8Array(readFileSync(process.argv[2])), 'off'); core.openParsed(null, null);
const m = core.pendingMesh();
const rounds = +process.argv[3], nu = +process.argv[4], nv = +process.argv[5];
let t = performance.now();
for (let r = 0; r < rounds; r++) { const w = torus(nu, nv); pageSurface(new Surface(w.positions, w.triangles, w.edges), true); }
console.log('warm-up', (performance.now() - t).toFixed(0));
t = performance.now();
const s = new Surface(m.positions, m.triangles, m.edges);
const t1 = performance.now();
pageSurface(s, true);
const t2 = performance.now();
console.log('surface', (t1 - t).toFixed(0), 'pageSurface (bvh+float32)', (t2 - t1).toFixed(0));
process.exit(0);
