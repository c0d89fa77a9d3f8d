// Camera moves of one viewer: frame the model (on load, Frame/Home/F), view presets (front, side, top) and the
// orbit pivot set by a double-click on the surface. Stateless functions of the viewer: each element's viewer
// owns its camera and controls.
import { Vector3 } from 'three';

// Directions from the model's centre to the camera, with y up (glTF's convention: +Z is the front).
// "home" is the load view: the front, slightly from the right and above, so the model reads as a solid.
export const VIEW_PRESETS = {
  home: [0.35, 0.25, 1],
  front: [0, 0, 1],
  back: [0, 0, -1],
  side: [1, 0, 0],
  top: [0, 1, 0],
};

// Puts the whole model (its bounding sphere) in view from `preset` (a VIEW_PRESETS name) and makes its centre
// the orbit pivot. The distance fits the sphere in the narrower of the two fields of view, so a tall
// phone viewport frames as well as a wide one.
// How far from the centre of a bounding sphere of this radius frameModel puts the camera: the sphere fills the
// narrower field of view, with a margin.
export function framingDistance(camera, radius) {
  const r = Math.max(radius, 1e-9);
  const vHalf = (camera.fov * Math.PI) / 360;
  const hHalf = Math.atan(Math.tan(vHalf) * camera.aspect);
  return (r / Math.sin(Math.min(vHalf, hHalf))) * 1.05;
}

export function frameModel(viewer, preset = 'home') {
  const mesh = viewer.surfaceMesh;
  if (!mesh) return false;
  const { camera, controls } = viewer;
  const s = mesh.geometry.boundingSphere;
  const dist = framingDistance(camera, s.radius);
  const dir = new Vector3(...(VIEW_PRESETS[preset] ?? VIEW_PRESETS.home)).normalize();
  camera.position.copy(s.center).addScaledVector(dir, dist);
  camera.near = dist / 100;
  camera.far = dist * 10;
  // Looking straight down, y cannot be up: the top view has -z up (the front at the bottom of the screen).
  camera.up.set(0, 1, 0);
  if (preset === 'top') camera.up.set(0, 0, -1);
  camera.lookAt(s.center);
  camera.updateProjectionMatrix();
  controls.target.copy(s.center);
  controls.update();
  camera.up.set(0, 1, 0);
  viewer.requestRender();
  return true;
}

// After the view's aspect changed from `oldAspect`, moves the camera along its view direction so that whatever
// filled the narrower field of view before fills it again: a framed model stays framed (e.g. on a phone turned
// from portrait to landscape), and a zoomed-in view keeps its zoom.
export function refitToAspect(viewer, oldAspect) {
  const { camera, controls } = viewer;
  if (!viewer.surfaceMesh || !(oldAspect > 0)) return;
  const vHalf = (camera.fov * Math.PI) / 360;
  const narrow = (aspect) => Math.min(vHalf, Math.atan(Math.tan(vHalf) * aspect));
  const scale = Math.sin(narrow(oldAspect)) / Math.sin(narrow(camera.aspect));
  if (Math.abs(scale - 1) < 1e-6) return;
  const offset = camera.position.clone().sub(controls.target).multiplyScalar(scale);
  camera.position.copy(controls.target).add(offset);
  camera.updateProjectionMatrix();
  controls.update();
}

// Makes the surface point under (clientX, clientY) the orbit pivot, keeping the view direction; returns the
// point or null (off the model: nothing changes).
export function setPivotAt(viewer, clientX, clientY) {
  const hit = viewer.pick(clientX, clientY);
  if (!hit) return null;
  const { camera, controls } = viewer;
  const p = new Vector3(...hit.point);
  // Move camera and pivot together so the picked point comes to the centre of the screen at the same distance.
  const offset = new Vector3().subVectors(camera.position, controls.target);
  controls.target.copy(p);
  camera.position.copy(p).add(offset);
  controls.update();
  viewer.requestRender();
  return hit.point;
}

// {position, target, up} of the camera, plain arrays (js-api camera()).
export function cameraState(viewer) {
  const { camera, controls } = viewer;
  return { position: camera.position.toArray(), target: controls.target.toArray(), fov: camera.fov };
}

// Places the camera (js-api setCamera()); the near/far planes follow the distance.
export function setCameraState(viewer, { position, target }) {
  const { camera, controls } = viewer;
  if (target) controls.target.set(...target);
  if (position) camera.position.set(...position);
  const dist = camera.position.distanceTo(controls.target) || 1;
  const r = viewer.surfaceMesh?.geometry.boundingSphere.radius ?? dist;
  camera.near = Math.max(dist - 2 * r, dist / 1000, 1e-6) / 10;
  camera.far = (dist + 2 * r) * 10;
  camera.updateProjectionMatrix();
  controls.update();
  viewer.requestRender();
}
