// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesized texture on the model in the page's three.js view: the model drawn with per-corner atlas UVs and
// a MeshStandardMaterial whose base colour is the exemplar at the synthesized coordinates, magnified per pixel
// (shaders.js MAGNIFY_GLSL: the four nearest texels' coordinates, each continued with its Jacobian, blended),
// the same function the PNG/GLB export renders with.
import {
  DataTexture,
  DoubleSide,
  ExternalTexture,
  LinearFilter,
  LinearMipmapLinearFilter,
  Mesh,
  MeshStandardMaterial,
  RepeatWrapping,
  RGBAFormat,
  SRGBColorSpace,
  UnsignedByteType,
} from 'three';
import { stagedCornerGeometry } from '../views/corner-geometry.js';
import { MeshStaging } from '../views/mesh-staging.js';
import { MAGNIFY_GLSL } from './shaders.js';

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
    this.targets = null; // the synthesizer's display targets behind coord and jac
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
    this.staging ??= new MeshStaging(this.viewer.renderer, this.viewer.camera);
    const bounds = this.viewer.surfaceMesh?.geometry.boundingSphere;
    const geom = await stagedCornerGeometry(this.staging, surface, cornerUVs, bounds, () => this.building === call);
    if (!geom) return;
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
    this.mesh.userData.costlyPixels = true; // drawn once per view and texture (views/surface-layer.js)
    this.viewer.scene.add(this.mesh);
    this.viewer.surfaceStandIn = this.mesh;
    await this.viewer.surfaceLayer.compile(this.viewer.renderer, this.viewer.scene, this.viewer.camera, this.mesh);
  }

  // coord, jac: the synthesizer's display targets (synthesis-readout.js displayCopy: RGBA32F, resolution^2, row 0
  // = v 0), made in this view's own WebGL context and drawn as they are (three.js ExternalTexture): nothing is
  // read back or uploaded on the way to the screen. The model owns them from here and frees them when a newer
  // texture replaces them. exemplar: RGBA8 of exemplarSize^2. Returns false (freeing them) without a mesh.
  setTexture({ resolution, coord, jac, exemplar, exemplarSize }) {
    if (!this.mesh) {
      coord.dispose();
      jac.dispose();
      return false;
    }
    const previous = this.textures;
    const keepExemplar = previous?.ex.image.data === exemplar && previous.ex.image.width === exemplarSize;
    const ex = keepExemplar ? previous.ex : exemplarTexture(exemplar, exemplarSize);
    this.#disposeTextures({ keep: ex });
    this.textures = { coord: new ExternalTexture(coord.texture), jac: new ExternalTexture(jac.texture), ex };
    this.targets = [coord, jac];
    this.uniforms.uSynthCoord.value = this.textures.coord;
    this.uniforms.uSynthJac.value = this.textures.jac;
    this.uniforms.uExemplarMap.value = ex;
    this.uniforms.uAtlasSize.value = resolution;
    this.uniforms.uExemplarSize.value = exemplarSize;
    this.mesh.userData.pictureVersion++;
    this.setVisible(this.visible);
    return true;
  }

  // The view's context was lost: the textures went with it (three.js makes its own again, not these).
  dropTextures() {
    this.targets = null;
    this.textures = null;
    this.setVisible(this.visible);
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

  #disposeTextures({ keep = null } = {}) {
    for (const t of Object.values(this.textures ?? {})) if (t !== keep) t.dispose();
    for (const target of this.targets ?? []) target.dispose();
    this.textures = null;
    this.targets = null;
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
