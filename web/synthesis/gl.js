// SPDX-License-Identifier: GPL-2.0-or-later
// Small raw-WebGL2 helpers for the synthesizer: programs, float textures and render targets, full-screen passes.
// Every texture here is read with texelFetch (integer texel addresses), so all use NEAREST filtering and need only
// EXT_color_buffer_float to be rendered into.
import { scratchCanvas } from '../dom.js';

// Texture and atlas sizes are powers of two (the pyramid halves them down to 2x2).
export const isPow2 = (n) => Number.isInteger(n) && n > 0 && (n & (n - 1)) === 0;

export class GLError extends Error {
  constructor(message) {
    super(message);
    this.name = 'GLError';
  }
}

// A WebGL2 context of our own (synthesis never touches three.js's GL state) with float render targets.
export function createContext() {
  const canvas = scratchCanvas(1, 1);
  const gl = canvas.getContext('webgl2', {
    antialias: false,
    depth: false,
    stencil: false,
    alpha: true,
    premultipliedAlpha: false,
    preserveDrawingBuffer: false,
  });
  if (!gl) throw new GLError('texture synthesis needs WebGL2, which this browser does not provide');
  return requireFloatTargets(gl);
}

// gl with float render targets enabled (a context of its own or the view's), or a GLError.
export function requireFloatTargets(gl) {
  if (!gl.getExtension('EXT_color_buffer_float'))
    throw new GLError('texture synthesis needs float render targets (EXT_color_buffer_float)');
  return gl;
}

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  return shader;
}

// A linked program with its uniform locations looked up lazily. Compiled and linked without asking how it went:
// each such question waits for the driver (with software GL, the synthesis's nine in one task
// of 0.4 s at the first synthesis). ready() tells, without waiting, whether the driver is done
// (KHR_parallel_shader_compile; without it, the next question waits); check() asks, throwing on failure.
export class Program {
  constructor(gl, vertexSource, fragmentSource, label) {
    this.gl = gl;
    this.label = label;
    this.vs = compile(gl, gl.VERTEX_SHADER, vertexSource);
    this.fs = compile(gl, gl.FRAGMENT_SHADER, fragmentSource);
    const p = gl.createProgram();
    gl.attachShader(p, this.vs);
    gl.attachShader(p, this.fs);
    gl.linkProgram(p);
    this.program = p;
    this.locations = new Map();
    this.checked = false;
  }

  ready(parallel = this.gl.getExtension('KHR_parallel_shader_compile')) {
    return this.checked || !parallel || this.gl.getProgramParameter(this.program, parallel.COMPLETION_STATUS_KHR);
  }

  check() {
    if (this.checked) return this;
    const gl = this.gl;
    if (!gl.getProgramParameter(this.program, gl.LINK_STATUS)) {
      const compileLog = [this.vs, this.fs]
        .map((sh) => (gl.getShaderParameter(sh, gl.COMPILE_STATUS) ? '' : gl.getShaderInfoLog(sh)))
        .join('');
      throw new GLError(
        compileLog
          ? `${this.label}: shader compile failed: ${compileLog}`
          : `${this.label}: link failed: ${gl.getProgramInfoLog(this.program)}`,
      );
    }
    gl.deleteShader(this.vs);
    gl.deleteShader(this.fs);
    this.vs = this.fs = null;
    this.checked = true;
    return this;
  }

  loc(name) {
    if (!this.locations.has(name)) this.locations.set(name, this.gl.getUniformLocation(this.program, name));
    return this.locations.get(name);
  }

  use() {
    this.gl.useProgram(this.program);
    this.unit = 0;
    return this;
  }

  // Binds a texture to the next free unit and points the sampler uniform at it.
  texture(name, tex) {
    const gl = this.gl;
    const unit = this.unit++;
    gl.activeTexture(gl.TEXTURE0 + unit);
    gl.bindTexture(gl.TEXTURE_2D, tex.texture ?? tex);
    gl.uniform1i(this.loc(name), unit);
    return this;
  }

  int(name, v) {
    this.gl.uniform1i(this.loc(name), v);
    return this;
  }
  float(name, v) {
    this.gl.uniform1f(this.loc(name), v);
    return this;
  }
  vec2(name, x, y) {
    this.gl.uniform2f(this.loc(name), x, y);
    return this;
  }
  ivec2(name, x, y) {
    this.gl.uniform2i(this.loc(name), x, y);
    return this;
  }
  vec4v(name, arr) {
    this.gl.uniform4fv(this.loc(name), arr);
    return this;
  }
  mat4v(name, arr) {
    this.gl.uniformMatrix4fv(this.loc(name), false, arr);
    return this;
  }

  dispose() {
    this.gl.deleteProgram(this.program);
    if (this.vs) this.gl.deleteShader(this.vs);
    if (this.fs) this.gl.deleteShader(this.fs);
  }
}

// The next animation frame (a task where there is none: node, workers).
export const animationFrame = () =>
  new Promise((resolve) =>
    typeof requestAnimationFrame === 'function' ? requestAnimationFrame(() => resolve()) : setTimeout(resolve, 0),
  );

// Each program checked (Program.check), in turn: once the questions of a task have taken `budgetMs`, the rest
// wait for nextFrame(). Every question waits for the GPU process, which software GL keeps busy drawing: 8-17 ms
// each beside a big model's first frames, where the synthesis's thirteen in one task held the page 66-108 ms.
// run(f): the caller's GL guard. Resolves false, the rest unchecked, where lost() says the context went.
export async function checkInTurn(programs, nextFrame, { budgetMs = 8, run = (f) => f(), lost = () => false } = {}) {
  let start = performance.now();
  for (const p of programs) {
    if (p.checked) continue;
    if (performance.now() - start > budgetMs) {
      await nextFrame();
      start = performance.now();
    }
    if (lost()) return false;
    run(() => p.check());
  }
  return true;
}

// An RGBA32F texture (optionally a render target) of width x height.
export class FloatTarget {
  // check: ask the driver whether the target is complete. That call waits for the GPU process, which with
  // software GL may be seconds behind the page: a caller making many targets of one kind checks the first.
  constructor(gl, width, height, data = null, { target = true, check = true } = {}) {
    this.gl = gl;
    this.width = width;
    this.height = height;
    this.texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, width, height, 0, gl.RGBA, gl.FLOAT, data);
    for (const [k, v] of [
      [gl.TEXTURE_MIN_FILTER, gl.NEAREST],
      [gl.TEXTURE_MAG_FILTER, gl.NEAREST],
      [gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE],
      [gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE],
    ])
      gl.texParameteri(gl.TEXTURE_2D, k, v);
    this.framebuffer = null;
    if (target) {
      this.framebuffer = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.texture, 0);
      const status = check ? gl.checkFramebufferStatus(gl.FRAMEBUFFER) : gl.FRAMEBUFFER_COMPLETE;
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      if (status !== gl.FRAMEBUFFER_COMPLETE)
        throw new GLError(`RGBA32F render target ${width}x${height} is incomplete (0x${status.toString(16)})`);
    }
  }

  bindAsTarget() {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.viewport(0, 0, this.width, this.height);
  }

  read(out = new Float32Array(4 * this.width * this.height)) {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.readPixels(0, 0, this.width, this.height, gl.RGBA, gl.FLOAT, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }

  dispose() {
    this.gl.deleteTexture(this.texture);
    if (this.framebuffer) this.gl.deleteFramebuffer(this.framebuffer);
  }
}

// An RGBA8 render target (the resolved colour image, read back as bytes).
export class ByteTarget {
  constructor(gl, width, height) {
    this.gl = gl;
    this.width = width;
    this.height = height;
    this.texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, width, height, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    this.framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.texture, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }
  bindAsTarget() {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.viewport(0, 0, this.width, this.height);
  }
  read(out = new Uint8Array(4 * this.width * this.height)) {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.readPixels(0, 0, this.width, this.height, gl.RGBA, gl.UNSIGNED_BYTE, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }
  dispose() {
    this.gl.deleteTexture(this.texture);
    this.gl.deleteFramebuffer(this.framebuffer);
  }
}

// One triangle covering the viewport; the vertex shader derives positions from gl_VertexID.
export const FULLSCREEN_VS = `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

export function drawFullscreen(gl, vao) {
  gl.bindVertexArray(vao);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  gl.bindVertexArray(null);
}

// The full-screen pass drawn only within `rects` ([{x, y, w, h}] in the target's pixels), or everywhere (null).
export function drawWithin(gl, vao, rects) {
  if (!rects) return drawFullscreen(gl, vao);
  gl.enable(gl.SCISSOR_TEST);
  for (const { x, y, w, h } of rects) {
    gl.scissor(x, y, w, h);
    drawFullscreen(gl, vao);
  }
  gl.disable(gl.SCISSOR_TEST);
}

// Waits for the GPU: a 1x1 readPixels from the current framebuffer (gl.finish() does not wait in Chromium).
export function sync(gl, target) {
  const px = new Float32Array(4);
  gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, px);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  return px;
}
