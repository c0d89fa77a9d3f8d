// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesized texture on the model in the page's three.js view: the model drawn with per-corner atlas UVs and
// a MeshStandardMaterial whose base colour is the exemplar at the synthesized coordinates, magnified per pixel
// (shaders.js MAGNIFY_GLSL: the four nearest texels' coordinates, each continued with its Jacobian, blended),
// the same function the PNG/GLB export renders with.
import {
  BufferAttribute,
  BufferGeometry,
  DataTexture,
  DoubleSide,
  FloatType,
  LinearFilter,
  LinearMipmapLinearFilter,
  Mesh,
  MeshStandardMaterial,
  NearestFilter,
  RepeatWrapping,
  RGBAFormat,
  SRGBColorSpace,
  UnsignedByteType,
} from 'three';
import { MeshStaging } from '../views/mesh-staging.js';
import { MAGNIFY_GLSL } from './shaders.js';

// Faces per task while the textured geometry is built (~20 ms).
const BUILD_SLICE = 1 << 15;
// Bytes of a synthesized texture sent to the GPU per task (~20 ms with software GL).
const UPLOAD_BYTES = 2 << 20;

const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

// A float RGBA texture of the synthesis (row 0 = v 0), its data not yet sent.
function floatTexture(data, resolution) {
  const t = new DataTexture(data, resolution, resolution, RGBAFormat, FloatType);
  t.minFilter = t.magFilter = NearestFilter;
  t.generateMipmaps = false;
  return t;
}

function exemplarTexture(exemplar, exemplarSize) {
  const ex = new DataTexture(exemplar, exemplarSize, exemplarSize, RGBAFormat, UnsignedByteType);
  ex.colorSpace = SRGBColorSpace;
  ex.wrapS = ex.wrapT = RepeatWrapping;
  ex.magFilter = LinearFilter;
  ex.minFilter = LinearMipmapLinearFilter;
  ex.generateMipmaps = true;
  ex.anisotropy = 4;
  ex.needsUpdate = true;
  return ex;
}

// Sends textures to the GPU a slice of rows per task through three.js (its storage first, then its update
// ranges, which take one row each), or all in this task when not `sliced`. Returns false as soon as live() does.
async function upload(renderer, textures, resolution, live, sliced) {
  const rows = Math.max(1, Math.floor(UPLOAD_BYTES / (16 * resolution)));
  for (const t of textures) {
    if (!sliced) {
      t.needsUpdate = true;
      renderer.initTexture(t);
      continue;
    }
    t.source.dataReady = false;
    t.needsUpdate = true;
    renderer.initTexture(t);
    t.source.dataReady = true;
    for (let y0 = 0; y0 < resolution; y0 += rows) {
      await nextTask();
      if (!live()) return false;
      for (let y = y0; y < Math.min(resolution, y0 + rows); y++) t.addUpdateRange(4 * resolution * y, 4 * resolution);
      t.needsUpdate = true;
      renderer.initTexture(t);
    }
  }
  return true;
}

// The model's corners, each with its position, smooth normal and atlas UV. bounds: the surface's bounding
// sphere (the same points), when it has one.
async function cornerGeometry({ positions, triangles, vertexNormals }, cornerUVs, bounds) {
  const nF = triangles.length / 3;
  const pos = new Float32Array(9 * nF), nor = new Float32Array(9 * nF), uv = new Float32Array(6 * nF);
  for (let f0 = 0; f0 < nF; f0 += BUILD_SLICE) {
    // Each slice in a task of its own, the first too (the atlas was set up in the caller's).
    await nextTask();
    for (let f = f0; f < Math.min(nF, f0 + BUILD_SLICE); f++)
      for (let k = 0; k < 3; k++) {
        const v = 3 * triangles[3 * f + k];
        for (let c = 0; c < 3; c++) {
          pos[9 * f + 3 * k + c] = positions[v + c];
          nor[9 * f + 3 * k + c] = vertexNormals[v + c];
        }
        uv[6 * f + 2 * k] = cornerUVs[6 * f + 2 * k];
        uv[6 * f + 2 * k + 1] = cornerUVs[6 * f + 2 * k + 1];
      }
  }
  const geom = new BufferGeometry();
  geom.setAttribute('position', new BufferAttribute(pos, 3));
  geom.setAttribute('normal', new BufferAttribute(nor, 3));
  geom.setAttribute('uv', new BufferAttribute(uv, 2));
  if (bounds) geom.boundingSphere = bounds.clone();
  else geom.computeBoundingSphere();
  return geom;
}

const FRAGMENT_PARS = `
uniform highp sampler2D uSynthCoord;
uniform highp sampler2D uSynthJac;
uniform highp sampler2D uExemplarMap;
uniform float uAtlasSize;
uniform float uExemplarSize;
${MAGNIFY_GLSL}
`;

// Per fragment the magnification of shaders.js (four texels' patches blended), read with textureGrad whose
// derivatives are each texel's J times the screen derivatives of the atlas position: the filter footprint (mip
// level and anisotropy) follows the Jacobian, not the coordinate, which jumps at patch seams.
const FRAGMENT_MAP = `
{
  vec2 atlasPos = vUv * uAtlasSize;
  float found;
  vec3 texel = magnifiedColour(uSynthCoord, uSynthJac, uExemplarMap, atlasPos, uExemplarSize, dFdx(atlasPos),
                               dFdy(atlasPos), found);
  diffuseColor.rgb *= texel;
}
`;

export class TexturedModel {
  constructor(viewer) {
    this.viewer = viewer;
    this.staging = null; // the geometry's uploads (views/mesh-staging.js)
    this.building = null; // the setGeometry call in progress
    this.mesh = null;
    this.textures = null; // {coord, jac, ex}: what the mesh shows
    this.uploading = null; // the setTexture call whose textures go to the GPU
    this.visible = true;
  }

  // surface: the model's Surface (geometry/surface.js); cornerUVs: 6 per face. A non-indexed geometry (every
  // corner its own UV) shaded with the welded mesh's smooth vertex normals, which the Surface already holds.
  // Built a slice of faces per task and sent to the GPU ahead of its first frame (views/mesh-staging.js): at
  // 832k faces, 80 MB that took the page's thread 0.6 s in one task. Resolves once the mesh is in the scene (or
  // a newer call replaced it).
  async setGeometry(surface, cornerUVs) {
    this.#disposeMesh();
    const call = (this.building = {});
    const geom = await cornerGeometry(surface, cornerUVs, this.viewer.surfaceMesh?.geometry.boundingSphere);
    if (this.building === call) {
      this.staging ??= new MeshStaging(this.viewer.renderer, this.viewer.camera);
      await this.staging.stage(geom, () => geom);
      this.staging.take(geom);
    }
    if (this.building !== call) return geom.dispose();
    const material = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.7, metalness: 0.0, side: DoubleSide });
    material.defines = { USE_UV: '' };
    this.uniforms = {
      uSynthCoord: { value: null },
      uSynthJac: { value: null },
      uExemplarMap: { value: null },
      uAtlasSize: { value: 1 },
      uExemplarSize: { value: 1 },
    };
    material.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, this.uniforms);
      shader.fragmentShader = shader.fragmentShader
        .replace('#include <common>', `#include <common>\n${FRAGMENT_PARS}`)
        .replace('#include <map_fragment>', `#include <map_fragment>\n${FRAGMENT_MAP}`);
    };
    material.customProgramCacheKey = () => 'tvf-synthesized-texture';
    this.mesh = new Mesh(geom, material);
    this.mesh.name = 'synthesized texture';
    this.mesh.visible = false; // until the first texture arrives
    this.mesh.userData.pictureVersion = 0;
    this.viewer.scene.add(this.mesh);
    this.viewer.surfaceStandIn = this.mesh;
    await this.viewer.surfaceLayer.compile(this.viewer.renderer, this.viewer.scene, this.viewer.camera, this.mesh);
  }

  // coords, jacobian: Float32Array RGBA of resolution^2 (row 0 = v 0); exemplar: RGBA8 of exemplarSize^2. The
  // two float textures (32 MB for a 1024 atlas) go to the GPU a slice per task, into textures of their own: the
  // model shows the previous ones until both are complete (three.js's upload at the next frame held the page for
  // 0.1–0.2 s at 832k faces, issue 28); all at once when not `sliced` (a blocking synthesis). Resolves true once
  // shown, false if a newer call or a new mesh came first.
  async setTexture({ resolution, coords, jacobian, exemplar, exemplarSize }, { sliced = true } = {}) {
    if (!this.mesh) return false;
    const call = (this.uploading = {}), mesh = this.mesh;
    const coord = floatTexture(coords, resolution), jac = floatTexture(jacobian, resolution);
    const live = () => this.uploading === call && this.mesh === mesh;
    if (!(await upload(this.viewer.renderer, [coord, jac], resolution, live, sliced))) {
      coord.dispose();
      jac.dispose();
      return false;
    }
    this.uploading = null;
    const previous = this.textures;
    const keepExemplar = previous?.ex.image.data === exemplar && previous.ex.image.width === exemplarSize;
    const ex = keepExemplar ? previous.ex : exemplarTexture(exemplar, exemplarSize);
    if (previous) for (const t of Object.values(previous)) if (t !== ex) t.dispose();
    this.textures = { coord, jac, ex };
    this.uniforms.uSynthCoord.value = coord;
    this.uniforms.uSynthJac.value = jac;
    this.uniforms.uExemplarMap.value = ex;
    this.uniforms.uAtlasSize.value = resolution;
    this.uniforms.uExemplarSize.value = exemplarSize;
    mesh.userData.pictureVersion++;
    this.setVisible(this.visible);
    return true;
  }

  // Shows the textured model in place of the viewer's own surface (which stays in the scene for picking).
  setVisible(visible) {
    this.visible = visible;
    const on = visible && !!this.mesh && !!this.textures;
    if (this.mesh) this.mesh.visible = on;
    const surface = this.viewer.surfaceMesh;
    if (surface) surface.material.visible = !on;
    this.viewer.requestRender?.();
  }

  #disposeTextures() {
    if (!this.textures) return;
    for (const t of Object.values(this.textures)) t.dispose();
    this.textures = null;
  }

  #disposeMesh() {
    this.#disposeTextures();
    if (!this.mesh) return;
    if (this.viewer.surfaceStandIn === this.mesh) this.viewer.surfaceStandIn = null;
    this.viewer.scene.remove(this.mesh);
    this.mesh.geometry.dispose();
    this.mesh.material.dispose();
    this.mesh = null;
  }

  dispose() {
    this.building = null;
    this.staging?.dispose();
    this.staging = null;
    const surface = this.viewer.surfaceMesh;
    if (surface) surface.material.visible = true;
    this.#disposeMesh();
  }
}
