// The host page's own three.js: a scene drawn into its own canvas with its own renderer. Then the designer,
// imported by its bare name; the import map decides which build that is (three-page.html: the peer build,
// which uses this page's three; three-page-standalone.html: the standalone bundle, which brings its own).
import * as THREE from 'three';
import { TangentFieldDesigner } from 'tangent-field-designer';

const scene = new THREE.Scene();
scene.background = new THREE.Color(0x204060);
const camera = new THREE.PerspectiveCamera(50, 4 / 3, 0.1, 10);
camera.position.z = 3;
scene.add(new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), new THREE.MeshNormalMaterial()));
const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById('own'), preserveDrawingBuffer: true });
renderer.render(scene, camera);

window.__host = {
  revision: THREE.REVISION,
  designerDefined: customElements.get('tangent-field-designer') === TangentFieldDesigner,
  // The host's scene was drawn: the centre pixel has the cube's colour (its front face's normal, bluish
  // white), not the background's (red 0x20).
  ownDrawn: (() => {
    const gl = renderer.getContext();
    const px = new Uint8Array(4);
    gl.readPixels(80, 60, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return px[0] > 90 && px[2] > 200;
  })(),
};
