// The rectangle the surface layer's copy covers (web/views/surface-layer.js): every pixel the surface can
// reach lies inside it, it is a real cut of the canvas when the model is framed, and it is the whole canvas
// (null) when the camera is inside the bounds or the model lies behind it. And from which size a surface is
// drawn into the layer: any with software GL, 200,000 faces on a GPU.
import assert from 'node:assert/strict';
import test from 'node:test';
import { Box3, Mesh, MeshBasicMaterial, PerspectiveCamera, SphereGeometry, TorusKnotGeometry, Vector3 } from 'three';
import { layerMinFaces, screenRectOf } from '../../web/views/surface-layer.js';

const W = 1024, H = 656;

// Each vertex's pixel (x right, y up from the bottom left, as GL's scissor counts).
function projectedPixels(mesh, camera) {
  const p = mesh.geometry.getAttribute('position');
  const v = new Vector3();
  const out = [];
  for (let i = 0; i < p.count; i++) {
    v.fromBufferAttribute(p, i).applyMatrix4(mesh.matrixWorld).project(camera);
    out.push([((v.x + 1) / 2) * W, ((v.y + 1) / 2) * H]);
  }
  return out;
}

function cameraAt(position, target) {
  const camera = new PerspectiveCamera(45, W / H, 0.01, 100);
  camera.position.copy(position);
  camera.lookAt(target);
  camera.updateMatrixWorld();
  return camera;
}

test('the copy rectangle holds every pixel of the surface, and is a fraction of the canvas', () => {
  const mesh = new Mesh(new TorusKnotGeometry(1, 0.3, 128, 16), new MeshBasicMaterial());
  mesh.position.set(0.4, -0.2, 0.1);
  mesh.scale.set(1.3, 0.8, 1);
  mesh.updateMatrixWorld();
  for (const eye of [new Vector3(0, 0, 14), new Vector3(9, 5, 7), new Vector3(-5, -11, 4)]) {
    const camera = cameraAt(eye, new Vector3(0.4, -0.2, 0.1));
    const r = screenRectOf(mesh, camera, W, H);
    assert.ok(r, `eye ${eye.toArray()}`);
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (const [x, y] of projectedPixels(mesh, camera)) {
      assert.ok(x >= r.x && x <= r.x + r.width && y >= r.y && y <= r.y + r.height, `eye ${eye.toArray()}: (${x}, ${y}) outside ${JSON.stringify(r)}`);
      (x0 = Math.min(x0, x)), (x1 = Math.max(x1, x)), (y0 = Math.min(y0, y)), (y1 = Math.max(y1, y));
    }
    // Not the whole canvas, and not far beyond the surface's own extent on screen.
    assert.ok(r.width * r.height < 0.6 * W * H, `eye ${eye.toArray()}: ${JSON.stringify(r)}`);
    assert.ok(r.width * r.height < 3 * (x1 - x0) * (y1 - y0), `eye ${eye.toArray()}: ${JSON.stringify(r)}`);
  }
});

test('a camera inside the bounds, or one looking away, gets the whole canvas or an empty cut', () => {
  const mesh = new Mesh(new SphereGeometry(1, 32, 16), new MeshBasicMaterial());
  mesh.updateMatrixWorld();
  assert.equal(screenRectOf(mesh, cameraAt(new Vector3(0.2, 0, 0.3), new Vector3(1, 0, 0)), W, H), null);
  // Behind the camera: the box reaches behind the near plane, so no cut is made.
  assert.equal(screenRectOf(mesh, cameraAt(new Vector3(0, 0, 5), new Vector3(0, 0, 10)), W, H), null);
  // Off to the side, in front: the rectangle is clamped to the canvas (empty when it misses it).
  const r = screenRectOf(mesh, cameraAt(new Vector3(0, 0, 5), new Vector3(20, 0, 0)), W, H);
  assert.ok(r === null || (r.x >= 0 && r.x + r.width <= W && r.y >= 0 && r.y + r.height <= H), JSON.stringify(r));
});

test('positions changed in place move the rectangle with them', () => {
  const mesh = new Mesh(new SphereGeometry(1, 16, 8), new MeshBasicMaterial());
  mesh.updateMatrixWorld();
  const camera = cameraAt(new Vector3(0, 0, 10), new Vector3(0, 0, 0));
  const before = screenRectOf(mesh, camera, W, H);
  const p = mesh.geometry.getAttribute('position');
  for (let i = 0; i < p.count; i++) p.setX(i, p.getX(i) + 2);
  p.needsUpdate = true;
  const after = screenRectOf(mesh, camera, W, H);
  assert.ok(after.x > before.x + 50, `${JSON.stringify(before)} -> ${JSON.stringify(after)}`);
});

test('a box the geometry came with is used as it is, until its positions change', () => {
  const mesh = new Mesh(new SphereGeometry(1, 16, 8), new MeshBasicMaterial());
  mesh.updateMatrixWorld();
  const camera = cameraAt(new Vector3(0, 0, 10), new Vector3(0, 0, 0));
  // A box wider than the positions (as a BVH's root bounds may be): the rectangle follows it, not the vertices.
  const given = new Box3(new Vector3(-2, -1, -1), new Vector3(2, 1, 1));
  mesh.geometry.boundingBox = given;
  const wide = screenRectOf(mesh, camera, W, H);
  assert.equal(mesh.geometry.boundingBox, given);
  assert.deepEqual(given.max.toArray(), [2, 1, 1]);
  mesh.geometry.getAttribute('position').needsUpdate = true;
  const own = screenRectOf(mesh, camera, W, H);
  assert.ok(own.width < wide.width - 50, `${JSON.stringify(wide)} -> ${JSON.stringify(own)}`);
});

// A renderer whose context names `name` as its (unmasked) renderer, as WEBGL_debug_renderer_info gives it.
function rendererNamed(name) {
  const info = { UNMASKED_RENDERER_WEBGL: 0x9246 };
  const getParameter = (p) => (p === info.UNMASKED_RENDERER_WEBGL ? name : 'WebKit WebGL');
  const gl = { RENDERER: 0x1f01, getExtension: () => info, getParameter };
  return { getContext: () => gl };
}

test('with software GL every surface goes into the layer, on a GPU only a big one', () => {
  const swiftShader = 'ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), SwiftShader driver)';
  assert.equal(layerMinFaces(rendererNamed(swiftShader)), 1);
  assert.equal(layerMinFaces(rendererNamed('llvmpipe (LLVM 15.0.6, 256 bits)')), 1);
  const gpu = 'ANGLE (NVIDIA, Vulkan 1.4.312 (NVIDIA NVIDIA H200 (0x00002335)), NVIDIA)';
  assert.equal(layerMinFaces(rendererNamed(gpu)), 200_000);
});
