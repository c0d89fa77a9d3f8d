// The material preview (docs/export.md): the GLB the export writes, read back with three.js's GLTFLoader
// and shown in the designer's scene, so the physical material's anisotropy along the field looks here as it
// will in any viewer that supports KHR_materials_anisotropy. Lit by a locally generated room environment
// (three's RoomEnvironment through PMREM: no downloaded HDR). One per viewer; nothing module-level mutable.
import { PMREMGenerator } from 'three';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// Base-material looks; the anisotropy strength and rotation come from the export options.
export const MATERIAL_PRESETS = {
  // Anisotropic highlights read best at medium roughness: too smooth and there is nothing to stretch.
  'brushed metal': { color: 0x8d9299, metalness: 1.0, roughness: 0.45, envMapIntensity: 0.5 },
  satin: {
    color: 0x6e1530,
    metalness: 0.0,
    roughness: 0.55,
    sheen: 0.8,
    sheenRoughness: 0.3,
    sheenColor: 0xff9fbf,
    envMapIntensity: 0.7,
  },
};

export class MaterialPreview {
  constructor(viewer) {
    this.viewer = viewer;
    this.root = null; // the loaded glTF scene
    this.environment = null; // PMREM render target, made on first use
    this.preset = 'brushed metal';
    this.serial = 0; // drops the results of superseded loads
  }

  get visible() {
    return this.root != null;
  }

  #environmentMap() {
    if (!this.environment) {
      const pmrem = new PMREMGenerator(this.viewer.renderer);
      this.environment = pmrem.fromScene(new RoomEnvironment(), 0.04);
      pmrem.dispose();
    }
    return this.environment.texture;
  }

  // glb: the bytes exportGlb() wrote. Resolves when the preview is on screen.
  async show(glb, preset = this.preset) {
    const serial = ++this.serial;
    const buffer = glb.buffer.slice(glb.byteOffset, glb.byteOffset + glb.byteLength);
    const gltf = await new GLTFLoader().parseAsync(buffer, '');
    if (serial !== this.serial) {
      disposeTree(gltf.scene);
      return;
    }
    this.#remove();
    this.preset = preset;
    this.root = gltf.scene;
    this.#applyPreset();
    this.viewer.scene.add(this.root);
    if (this.viewer.surfaceMesh) this.viewer.surfaceMesh.visible = false;
    const shown = this.viewer.nextRenderShown();
    this.viewer.requestRender();
    await shown;
  }

  setPreset(preset) {
    if (!MATERIAL_PRESETS[preset])
      throw new Error(`unknown material preset "${preset}" (${Object.keys(MATERIAL_PRESETS).join(', ')})`);
    this.preset = preset;
    if (this.root) {
      this.#applyPreset();
      this.viewer.requestRender();
    }
  }

  #applyPreset() {
    const look = MATERIAL_PRESETS[this.preset];
    const envMap = this.#environmentMap();
    this.root.traverse((o) => {
      if (!o.isMesh) return;
      const m = o.material;
      m.color.setHex(look.color);
      m.map = null; // a base-colour texture would hide the highlights the preview is for
      m.metalness = look.metalness;
      m.roughness = look.roughness;
      if ('sheen' in m) {
        m.sheen = look.sheen ?? 0;
        m.sheenRoughness = look.sheenRoughness ?? 1;
        m.sheenColor?.setHex(look.sheenColor ?? 0);
      }
      m.envMap = envMap;
      m.envMapIntensity = look.envMapIntensity;
      m.needsUpdate = true;
    });
  }

  // What GLTFLoader made of the export: the material and the per-vertex frames (copies), for tests and tools.
  info() {
    if (!this.root) return null;
    const meshes = [];
    this.root.updateMatrixWorld(true);
    this.root.traverse((o) => {
      if (!o.isMesh) return;
      const m = o.material, g = o.geometry;
      meshes.push({
        material: {
          type: m.type,
          isMeshPhysicalMaterial: m.isMeshPhysicalMaterial === true,
          anisotropy: m.anisotropy,
          anisotropyRotation: m.anisotropyRotation,
          hasAnisotropyMap: m.anisotropyMap != null,
          hasEnvMap: m.envMap != null,
        },
        matrixWorld: o.matrixWorld.toArray(),
        positions: Array.from(g.attributes.position.array),
        normals: g.attributes.normal ? Array.from(g.attributes.normal.array) : null,
        tangents: g.attributes.tangent ? Array.from(g.attributes.tangent.array) : null,
        field: g.attributes._field ? Array.from(g.attributes._field.array) : null,
        uvs: g.attributes.uv ? Array.from(g.attributes.uv.array) : null,
      });
    });
    return { preset: this.preset, meshes };
  }

  hide() {
    this.serial++;
    this.#remove();
    this.viewer.requestRender();
  }

  #remove() {
    if (!this.root) return;
    this.viewer.scene.remove(this.root);
    disposeTree(this.root);
    this.root = null;
    if (this.viewer.surfaceMesh) this.viewer.surfaceMesh.visible = true;
  }

  dispose() {
    this.hide();
    this.environment?.dispose();
    this.environment = null;
  }
}

function disposeTree(root) {
  root.traverse((o) => {
    o.geometry?.dispose();
    for (const m of [o.material].flat()) {
      if (!m) continue;
      for (const value of Object.values(m)) if (value?.isTexture) value.dispose();
      m.dispose();
    }
  });
}
