// SPDX-License-Identifier: GPL-2.0-or-later
// The stripe pattern on the model in the page's three.js view: the model's corners (views/corner-geometry.js),
// each with its face's phases and branch indices, drawn with a MeshStandardMaterial whose base colour is the
// profile (profiles.js) of the phase at each fragment: the corners' phases interpolated across the face (the
// barycentric point from the corner's place in its face, gl_VertexID % 3) plus n·L(b) in a branch face, so a
// stripe ends or forks inside that face as the paper draws it, with no smearing. It stands in for the surface
// (viewer.surfaceStandIn), which stays in the scene for picking. Owns its mesh; imports three.js, views/.
import { BufferAttribute, Color, DoubleSide, Mesh, MeshStandardMaterial } from 'three';
import { stagedCornerGeometry } from '../views/corner-geometry.js';
import { MeshStaging } from '../views/mesh-staging.js';
import { STRIPE_GLSL, profileIndex } from './profiles.js';

const VERTEX_PARS = /* glsl */ `
attribute vec2 stripePhase;
attribute vec2 stripeBranch;
varying vec2 vStripePhase;
varying vec2 vStripeBranch;
varying vec3 vStripeBary;
`;
const VERTEX_MAIN = /* glsl */ `
vStripePhase = stripePhase;
vStripeBranch = stripeBranch;
int stripeCorner = gl_VertexID % 3;
vStripeBary = vec3(stripeCorner == 0, stripeCorner == 1, stripeCorner == 2);
`;
const FRAGMENT_PARS = /* glsl */ `
uniform int uStripeProfile;
uniform float uStripeWidth; // the lines' share of a period
uniform vec3 uStripeLight; // sRGB, 0..1: mixed there, as the core's bake mixes bytes
uniform vec3 uStripeDark;
varying vec2 vStripePhase;
varying vec2 vStripeBranch;
varying vec3 vStripeBary;
${STRIPE_GLSL}
vec3 stripeToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
`;
// The footprint: the linear part's change over a pixel (fwidth), halved (the filter's half-width), as the
// bake's per texel (stripe_texture.cpp texelFootprint).
const FRAGMENT_MAP = /* glsl */ `
{
  vec3 b = vStripeBary / max(vStripeBary.x + vStripeBary.y + vStripeBary.z, 1e-6);
  float turn = stripeAngle(b);
  vec2 phase = (vStripePhase + vStripeBranch * turn) / (2.0 * STRIPE_PI);
  float w = 0.5 * max(fwidth(vStripePhase.x), fwidth(vStripePhase.y)) / (2.0 * STRIPE_PI);
  float t = clamp(stripeProfile(uStripeProfile, phase.x, phase.y, w, uStripeWidth), 0.0, 1.0);
  diffuseColor.rgb *= stripeToLinear(mix(uStripeDark, uStripeLight, t));
}
`;

const srgb = (hex) => {
  const c = new Color();
  c.setHex(hex, 'srgb-linear'); // the bytes as they are: the shader mixes in sRGB, then converts
  return c;
};

export class StripeModel {
  constructor(viewer) {
    this.viewer = viewer;
    this.staging = null;
    this.building = null;
    this.mesh = null;
    this.visible = false;
    this.hasPattern = false;
    this.replaced = null; // the stand-in this one replaced while shown (the synthesized texture's)
    this.uniforms = {
      uStripeProfile: { value: 0 },
      uStripeWidth: { value: 0.5 },
      uStripeLight: { value: srgb(0xece4d4) },
      uStripeDark: { value: srgb(0x342c28) },
    };
  }

  // surface: the model's Surface (geometry/surface.js). Built a slice of faces per task and sent to the GPU
  // ahead of its first frame (views/mesh-staging.js). Resolves once the mesh is in the scene (or a newer call
  // replaced it).
  async setGeometry(surface) {
    this.#disposeMesh();
    const call = (this.building = {});
    this.staging ??= new MeshStaging(this.viewer.renderer, this.viewer.camera);
    const bounds = this.viewer.surfaceMesh?.geometry.boundingSphere;
    const geom = await stagedCornerGeometry(this.staging, surface, null, bounds, () => this.building === call, (g) => {
      const corners = g.getAttribute('position').count;
      g.setAttribute('stripePhase', new BufferAttribute(new Float32Array(2 * corners), 2));
      g.setAttribute('stripeBranch', new BufferAttribute(new Int8Array(2 * corners), 2));
    });
    if (!geom) return;
    const material = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.7, metalness: 0.0, side: DoubleSide });
    material.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, this.uniforms);
      shader.vertexShader = shader.vertexShader
        .replace('#include <common>', `#include <common>\n${VERTEX_PARS}`)
        .replace('#include <begin_vertex>', `#include <begin_vertex>\n${VERTEX_MAIN}`);
      shader.fragmentShader = shader.fragmentShader
        .replace('#include <common>', `#include <common>\n${FRAGMENT_PARS}`)
        .replace('#include <map_fragment>', `#include <map_fragment>\n${FRAGMENT_MAP}`);
    };
    material.customProgramCacheKey = () => 'tvf-stripes';
    this.mesh = new Mesh(geom, material);
    this.mesh.name = 'stripes';
    this.mesh.visible = false;
    this.mesh.userData.pictureVersion = 0;
    this.viewer.scene.add(this.mesh);
    this.hasPattern = false;
    await this.viewer.surfaceLayer.compile(this.viewer.renderer, this.viewer.scene, this.viewer.camera, this.mesh);
    this.setVisible(this.visible);
  }

  // phase, branch: 2 per corner (stripes/worker-ops.js cornerAttributes), taken as they are. Returns false
  // without a mesh of that many corners. They become the attributes' arrays, uploaded into the attributes' own
  // buffers: a new attribute each time would leave the last one's buffer behind (three.js frees a geometry's
  // buffers with the geometry only), two a pattern.
  setPattern({ phase, branch }) {
    const g = this.mesh?.geometry;
    if (!g || g.getAttribute('position').count * 2 !== phase.length || branch.length !== phase.length) return false;
    for (const [name, array] of [['stripePhase', phase], ['stripeBranch', branch]]) {
      const attribute = g.getAttribute(name);
      attribute.array = array;
      attribute.needsUpdate = true;
    }
    this.hasPattern = true;
    this.#changed();
    return true;
  }

  // No pattern: the surface shows as it is until the next one.
  clearPattern() {
    this.hasPattern = false;
    this.#changed();
  }

  // profile: a name of profiles.js PROFILES; width: its lines' share of a period; light, dark: sRGB colours as
  // numbers (0xrrggbb).
  setStyle({ profile, width, light, dark }) {
    this.uniforms.uStripeProfile.value = profileIndex(profile);
    this.uniforms.uStripeWidth.value = width;
    this.uniforms.uStripeLight.value = srgb(light);
    this.uniforms.uStripeDark.value = srgb(dark);
    this.#changed();
  }

  // Shows the stripes in place of the viewer's surface and of any other stand-in (the synthesized texture),
  // which comes back when they hide.
  setVisible(visible) {
    this.visible = visible;
    const on = visible && !!this.mesh && this.hasPattern;
    const viewer = this.viewer;
    if (this.mesh) this.mesh.visible = on;
    if (on && viewer.surfaceStandIn !== this.mesh) {
      this.replaced = viewer.surfaceStandIn;
      viewer.surfaceStandIn = this.mesh;
    } else if (!on && this.mesh && viewer.surfaceStandIn === this.mesh) {
      viewer.surfaceStandIn = this.replaced?.parent ? this.replaced : null;
      this.replaced = null;
    }
    if (viewer.surfaceMesh) viewer.surfaceMesh.material.visible = !on && !viewer.surfaceStandIn?.visible;
    viewer.requestRender?.();
  }

  #changed() {
    if (this.mesh) this.mesh.userData.pictureVersion++;
    this.setVisible(this.visible);
  }

  #disposeMesh() {
    if (!this.mesh) return;
    const viewer = this.viewer;
    if (viewer.surfaceStandIn === this.mesh) viewer.surfaceStandIn = this.replaced?.parent ? this.replaced : null;
    this.replaced = null;
    this.viewer.scene.remove(this.mesh);
    this.mesh.geometry.dispose();
    this.mesh.material.dispose();
    this.mesh = null;
    this.hasPattern = false;
  }

  dispose() {
    this.building = null;
    this.staging?.dispose();
    this.staging = null;
    this.#disposeMesh();
    if (this.viewer.surfaceMesh) this.viewer.surfaceMesh.material.visible = !this.viewer.surfaceStandIn?.visible;
  }
}
