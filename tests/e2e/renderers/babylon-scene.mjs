// The exported GLB drawn by Babylon.js (npm @babylonjs/core and @babylonjs/loaders) as its viewer would: the glTF
// loader's PBR material (anisotropy from KHR_materials_anisotropy and the TANGENT attribute), a point light at
// the camera, nothing else. Bundled by tests/e2e/anisotropy-renderers.spec.mjs into an IIFE (TvfBabylonScene).
// Imported module by module, as Babylon's docs advise for bundles: the package's index (and the glTF loader's
// index, every extension) brought every part of the engine, a 16.9 MB bundle for the page to parse, where this
// is 3.6 MB (the spec's whitespace-free build).
import { UniversalCamera } from '@babylonjs/core/Cameras/universalCamera.js';
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { PointLight } from '@babylonjs/core/Lights/pointLight.js';
import { ImportMeshAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import { Color4 } from '@babylonjs/core/Maths/math.color.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { Scene } from '@babylonjs/core/scene.js';
import '@babylonjs/loaders/glTF/glTFFileLoader.js';
import '@babylonjs/loaders/glTF/2.0/glTFLoader.js';
// The one extension the exported GLB uses (a GLB whose material asked for another would fail to load, or draw
// no highlight along the field: the tests would see either).
import '@babylonjs/loaders/glTF/2.0/Extensions/KHR_materials_anisotropy.js';
import { topDownPixels } from './read-pixels.mjs';

// glb: the file's bytes; camera: {position, target} in the glTF's frame (right-handed: the loader flips it into
// Babylon's). Returns the drawing buffer's RGBA8, row 0 at the top.
export async function render(canvas, glb, camera) {
  const engine = new Engine(canvas, false, { preserveDrawingBuffer: true, stencil: false });
  const scene = new Scene(engine);
  scene.useRightHandedSystem = true;
  scene.clearColor = new Color4(0, 0, 0, 1);
  await ImportMeshAsync(glb, scene, { pluginExtension: '.glb' });
  const view = new UniversalCamera('camera', new Vector3(...camera.position), scene);
  view.fov = (30 * Math.PI) / 180;
  view.fovMode = 0; // vertical, as three's
  view.minZ = 0.01;
  view.upVector = new Vector3(0, 1, 0);
  view.setTarget(new Vector3(...camera.target));
  const light = new PointLight('light', new Vector3(...camera.position), scene);
  light.intensity = 2.5;
  light.falloffType = 2; // none: as three's decay 0
  await scene.whenReadyAsync();
  scene.render();
  const pixels = topDownPixels(engine._gl, canvas.width, canvas.height);
  engine.dispose();
  return pixels;
}
