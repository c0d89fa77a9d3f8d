// A big model's mesh buffers, sent to the GPU ahead of the frame that first draws them, in tasks of a few
// megabytes each. three.js uploads a geometry's buffers inside the first render that draws it: at 832,000 faces
// that was ~150 ms of bufferData in the one task that also adopts the model, and the 10 MB index alone still
// took 80–106 ms in a task of its own (a profile of the page, issue 28). The mesh arrives ahead of its field
// (session 'surface'), so each buffer is first allocated empty, then filled a slice per task.
//
// Both go through three.js's own upload, driven by an empty draw (draw range 0) of a stand-in geometry that
// shares the buffer, into a 1×1 render target (nothing is rasterized, the canvas is untouched): three.js keys a
// buffer by its attribute, so the surface's own draw finds it uploaded and current. The allocation is three.js's
// bufferData with the size in place of the array (WebGL allocates zeros, nothing is copied: three.js has no
// call for that, so the context's bufferData is wrapped for that one draw); the slices are three.js's update
// ranges (bufferSubData).
//
// An upload issued while the GPU process is still busy (a frame of the model opened before: seconds of a big
// textured model with software GL) waits for it on the page's thread: a 923 ms bufferSubData when armadillo-sub2
// was opened again over its textured self. So each step waits, in short polls, for a fence issued after the
// step before (the first for everything issued before the staging began).
//
// Owned by viewer.js. Imports three.js only.
import { BufferAttribute, BufferGeometry, Mesh, MeshBasicMaterial, Scene, WebGLRenderTarget } from 'three';

// Bytes uploaded per task: ~20 ms each with software GL.
const SLICE_BYTES = 2 << 20;

export class MeshStaging {
  constructor(renderer, camera) {
    this.renderer = renderer;
    this.camera = camera;
    this.staged = null; // {surface, geometry}
    this.material = null;
    this.target = null;
  }

  // build(): the surface's BufferGeometry as the viewer will draw it, made in a task of its own too. Replaces
  // (and disposes) a staged geometry never taken. Resolves with the number of uploads made when every buffer
  // is uploaded, or the staging was replaced or taken.
  stage(surface, build) {
    this.#drop();
    const staged = (this.staged = { surface, geometry: null });
    return new Promise((resolve) => {
      let steps = null, done = 0, fence = this.#fence();
      const next = () => {
        if (this.staged !== staged) {
          this.#deleteFence(fence);
          return resolve(done);
        }
        if (fence && !this.#signalled(fence)) return setTimeout(next, 1);
        fence = this.#deleteFence(fence);
        try {
          if (!steps) {
            staged.geometry = build();
            steps = this.#steps(staged.geometry);
          } else steps.shift()(), done++;
        } catch {
          // The viewer's setMesh builds and uploads as it would without staging, and reports what fails there.
          this.#drop();
          return resolve(done);
        }
        if (!steps.length) return resolve(done);
        fence = this.#fence();
        setTimeout(next, 0);
      };
      setTimeout(next, 0);
    });
  }

  // The empty draw's program, compiled when the viewer starts (shader-warm-up.js reads it back later): made at
  // a big model's first staging step, that step waited for its link.
  warmUp() {
    const standIn = new BufferGeometry();
    standIn.setAttribute('position', new BufferAttribute(new Float32Array(9), 3));
    standIn.setDrawRange(0, 0);
    const mesh = new Mesh(standIn, this.#material());
    const scene = new Scene();
    scene.add(mesh);
    const { renderer } = this;
    const before = renderer.getRenderTarget();
    try {
      renderer.setRenderTarget(this.#target());
      renderer.compile(scene, this.camera);
    } finally {
      renderer.setRenderTarget(before);
      standIn.dispose();
    }
  }

  // The staged geometry of this surface (null if none, or not built yet): the viewer draws it, its uploads
  // done or not.
  take(surface) {
    const staged = this.staged;
    if (staged?.surface !== surface) return null;
    this.staged = null;
    return staged.geometry;
  }

  dispose() {
    this.#drop();
    this.material?.dispose();
    this.target?.dispose();
  }

  // A fence after everything issued so far in the view's context, or null (a lost context).
  #fence() {
    const gl = this.renderer.getContext();
    const fence = gl.fenceSync?.(gl.SYNC_GPU_COMMANDS_COMPLETE, 0) ?? null;
    if (fence) gl.flush();
    return fence;
  }

  #signalled(fence) {
    const gl = this.renderer.getContext();
    return gl.isContextLost() || gl.getSyncParameter(fence, gl.SYNC_STATUS) === gl.SIGNALED;
  }

  #deleteFence(fence) {
    if (fence) this.renderer.getContext().deleteSync(fence);
    return null;
  }

  #material() {
    return (this.material ??= new MeshBasicMaterial({ colorWrite: false, depthWrite: false, depthTest: false }));
  }

  #target() {
    return (this.target ??= new WebGLRenderTarget(1, 1, { depthBuffer: false }));
  }

  #drop() {
    this.staged?.geometry?.dispose();
    this.staged = null;
  }

  // One function per task: each buffer allocated, then filled slice by slice.
  #steps(geometry) {
    const steps = [];
    for (const attribute of [geometry.index, ...Object.values(geometry.attributes)].filter(Boolean)) {
      const { array } = attribute;
      steps.push(() => this.#draw(geometry, attribute, array.byteLength));
      const slice = Math.max(1, Math.floor(SLICE_BYTES / array.BYTES_PER_ELEMENT));
      for (let start = 0; start < array.length; start += slice) {
        steps.push(() => {
          attribute.addUpdateRange(start, Math.min(slice, array.length - start));
          attribute.needsUpdate = true;
          this.#draw(geometry, attribute);
        });
      }
    }
    return steps;
  }

  // An empty draw of a geometry holding only `attribute` (the index or a vertex attribute): three.js uploads it
  // (allocates it with `allocate` bytes, when given, instead of copying its array).
  #draw(geometry, attribute, allocate = 0) {
    const standIn = new BufferGeometry();
    const isIndex = attribute === geometry.index;
    if (isIndex) standIn.setIndex(attribute);
    else standIn.setAttribute('position', attribute);
    standIn.setDrawRange(0, 0);
    // The renderer sorts by the bounding sphere, which it would otherwise compute (24 ms over 416k positions).
    standIn.boundingSphere = geometry.boundingSphere;
    const mesh = new Mesh(standIn, this.#material());
    mesh.frustumCulled = false;
    const scene = new Scene();
    scene.add(mesh);
    const { renderer } = this;
    const gl = renderer.getContext();
    const bufferData = Object.getPrototypeOf(gl).bufferData;
    if (allocate)
      gl.bufferData = (target, data, usage) =>
        bufferData.call(gl, target, data === attribute.array ? allocate : data, usage);
    const before = renderer.getRenderTarget();
    try {
      renderer.setRenderTarget(this.#target());
      renderer.render(scene, this.camera);
    } finally {
      delete gl.bufferData;
      renderer.setRenderTarget(before);
      // Disposing the stand-in frees what three.js keeps for it, and would free the buffer too: it lets go first.
      if (isIndex) standIn.setIndex(null);
      else standIn.deleteAttribute('position');
      standIn.dispose();
    }
  }
}
