// The exported GLB drawn by three.js (the package's peer) as a viewer would: GLTFLoader's material
// (MeshPhysicalMaterial with anisotropy from KHR_materials_anisotropy and the TANGENT attribute), a point light
// at the camera, nothing else. Bundled by tests/e2e/anisotropy-renderers.spec.mjs into an IIFE (TvfThreeScene).
import { Color, PerspectiveCamera, PointLight, Scene, WebGLRenderer } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { topDownPixels } from './read-pixels.mjs';

// glb: the file's bytes; camera: {position, target} in the model's frame. Returns the drawing buffer's RGBA8,
// row 0 at the top.
export async function render(canvas, glb, camera) {
  const renderer = new WebGLRenderer({ canvas, preserveDrawingBuffer: true, antialias: false });
  renderer.setSize(canvas.width, canvas.height, false);
  const gltf = await new GLTFLoader().parseAsync(glb.buffer.slice(glb.byteOffset, glb.byteOffset + glb.byteLength), '');
  const scene = new Scene();
  scene.background = new Color(0, 0, 0);
  scene.add(gltf.scene);
  const view = new PerspectiveCamera(30, canvas.width / canvas.height, 0.01, 100);
  view.position.set(...camera.position);
  view.up.set(0, 1, 0);
  view.lookAt(...camera.target);
  const light = new PointLight(0xffffff, 1, 0, 0);
  light.position.set(...camera.position);
  scene.add(view, light);
  renderer.render(scene, view);
  const pixels = topDownPixels(renderer.getContext(), canvas.width, canvas.height);
  renderer.dispose();
  return pixels;
}
