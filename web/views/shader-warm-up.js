// Every kind of material the views draw, compiled when the viewer starts rather than when a view first shows
// one. A new program's first draw reads its uniforms back, a synchronous round trip to the GPU process that
// waits for the link and for every frame still in flight: with software GL and a million-triangle model that
// froze the page for seconds at the first stroke, the first singularity markers, the first colour map.
// Compiled at the start, they are linked by the GPU process while the page goes on (renderer.compileAsync
// waits for that where the browser offers KHR_parallel_shader_compile).
//
// The samples copy the views' material settings (handles.js, markers.js, singularities-view.js, arrows-view.js,
// streamlines-view.js, viewer.js): a setting that drifts only costs that program its head start.
//
// Owns nothing past the call. Imports three and the views' band and marker makers.
import {
  BufferAttribute,
  BufferGeometry,
  CircleGeometry,
  Color,
  DoubleSide,
  Group,
  InstancedMesh,
  LineBasicMaterial,
  LineSegments,
  Mesh,
  MeshBasicMaterial,
  MeshStandardMaterial,
} from 'three';
import { arrowGeometry, glyphGeometry, markerSprite } from './markers.js';
import { BandMaterial, bandGeometry, bandMesh } from './screen-ribbon.js';
import { layerTarget } from './surface-layer.js';

// A triangle with the given attributes: a program depends on which attributes the geometry has.
function triangle(...names) {
  const g = new BufferGeometry();
  const data = {
    position: [0, 0, 0, 1, 0, 0, 0, 1, 0],
    normal: [0, 0, 1, 0, 0, 1, 0, 0, 1],
    color: new Array(9).fill(1),
  };
  for (const name of names) g.setAttribute(name, new BufferAttribute(new Float32Array(data[name]), 3));
  return g;
}

function samples(labels) {
  const group = new Group();
  const points = [[0, 0, 0], [1, 0, 0], [1, 1, 0]], normals = points.map(() => [0, 0, 1]);
  group.add(bandMesh(bandGeometry(points, normals), new BandMaterial({ color: 0xffffff, widthPx: 6 })));
  group.add(new Mesh(arrowGeometry(), new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide })));
  const map = labels.get('warm-up', '#ffffff', '');
  group.add(
    new Mesh(
      new CircleGeometry(0.5, 8),
      new MeshBasicMaterial({ map, transparent: true, side: DoubleSide, polygonOffset: true }),
    ),
  );
  group.add(markerSprite(map));
  const arrows = new InstancedMesh(glyphGeometry(1), new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide }), 1);
  arrows.setColorAt(0, new Color(1, 1, 1));
  group.add(arrows);
  group.add(new LineSegments(triangle('position'), new LineBasicMaterial({ color: 0x111827 })));
  group.add(...surfaces());
  for (const object of group.children) object.frustumCulled = false;
  return group;
}

function surfaces() {
  return [false, true].map((vertexColors) => {
    const surface = new MeshStandardMaterial({
      roughness: 0.65,
      metalness: 0,
      side: DoubleSide,
      polygonOffset: true,
      vertexColors,
    });
    const mesh = new Mesh(triangle('position', 'normal', 'color'), surface);
    mesh.frustumCulled = false;
    return mesh;
  });
}

// The surface's programs as a big surface draws them into its layer (surface-layer.js): linear output, another
// program than the canvas's. compile() makes them at once; the GPU process links them in the background.
function warmUpLayer(renderer, scene, camera) {
  const group = new Group();
  group.add(...surfaces());
  scene.add(group);
  const target = layerTarget(1, 1);
  const previous = renderer.getRenderTarget();
  try {
    renderer.setRenderTarget(target);
    renderer.compile(scene, camera);
  } finally {
    renderer.setRenderTarget(previous);
    scene.remove(group);
    target.dispose();
  }
}

// How often a read-back looks again at its fence or its program's link.
const POLL_MS = 8;

// Resolves when the programs are linked (or at once where compiling in the background is not offered). The
// samples' materials are left undisposed: disposing the last material of a program deletes the program.
export async function warmUpShaders(renderer, scene, camera, labels) {
  warmUpLayer(renderer, scene, camera);
  const group = samples(labels);
  scene.add(group);
  try {
    // Without the extension compile() is the same minus the waiting (compileAsync would warn that it is missing):
    // the GPU process links while the page goes on, and the first draw finds the program linked.
    if (renderer.extensions.has('KHR_parallel_shader_compile')) await renderer.compileAsync(scene, camera);
    else renderer.compile(scene, camera);
  } finally {
    scene.remove(group);
  }
  readBackLater(renderer);
}

// A program's first draw still reads it back (three.js's first use: its link status, its uniforms and
// attributes), and that round trip waits for whatever the GPU process has queued by then: in a big model's
// first field, behind its mesh's uploads, 30-50 ms of the task that drew it. Read back now, a program per
// task, each once a fence shows the GPU process idle and its link done (polled, never waited on): a read-back
// issued behind a model's first uploads held the page for 386 ms at the start of one load. Without
// KHR_parallel_shader_compile a read-back waits for its link.
function readBackLater(renderer) {
  const gl = renderer.getContext();
  const name = 'KHR_parallel_shader_compile';
  const parallel = renderer.extensions.has(name) ? renderer.extensions.get(name) : null;
  const programs = [...(renderer.info.programs ?? [])];
  let fence = null;
  const later = (ms) => setTimeout(next, ms);
  const next = () => {
    if (gl.isContextLost()) return;
    if (!fence) {
      fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
      gl.flush();
      return later(POLL_MS);
    }
    if (gl.getSyncParameter(fence, gl.SYNC_STATUS) !== gl.SIGNALED) return later(POLL_MS);
    gl.deleteSync(fence);
    fence = null;
    const program = programs.shift();
    if (!program) return;
    const live = renderer.info.programs?.includes(program); // not released since
    if (live && parallel && !gl.getProgramParameter(program.program, parallel.COMPLETION_STATUS_KHR)) {
      programs.push(program); // still linking: the others first
      return later(POLL_MS);
    }
    try {
      if (live) program.getUniforms();
    } catch {
      // a program that failed to link is reported at its first draw, as three.js does
    }
    later(0);
  };
  later(0);
}
