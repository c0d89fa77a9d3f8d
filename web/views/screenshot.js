// Screenshot of the viewport as a PNG at a chosen size, optionally with a transparent background. The view
// is drawn once more at that size (the same camera, the aspect of the requested image) and the canvas is put
// back as it was: the picture is the model, not an upscaled copy of the screen.
const MAX_SIDE = 8192; // beyond this browsers refuse the drawing buffer

export async function captureScreenshot(viewer, { width, height, transparent = false } = {}) {
  const canvas = viewer.canvas;
  const w = width ?? canvas.width, h = height ?? canvas.height;
  for (const [name, v] of [['width', w], ['height', h]]) {
    if (!Number.isInteger(v) || v < 1 || v > MAX_SIDE)
      throw new Error(`screenshot: ${name} must be a whole number of pixels from 1 to ${MAX_SIDE} (got ${v})`);
  }
  const { renderer, camera } = viewer;
  const ratio = renderer.getPixelRatio(), aspect = camera.aspect;
  const alpha = renderer.getClearAlpha();
  const cssW = canvas.clientWidth, cssH = canvas.clientHeight;
  try {
    renderer.setPixelRatio(1);
    renderer.setSize(w, h, false);
    renderer.setClearAlpha(transparent ? 0 : 1);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    viewer.renderNow();
    // toBlob reads the drawing buffer (kept: preserveDrawingBuffer) before anything else draws into it.
    return await new Promise((resolve, reject) =>
      canvas.toBlob(
        (blob) => (blob ? resolve(blob) : reject(new Error('screenshot: the browser could not encode the PNG'))),
        'image/png',
      ),
    );
  } finally {
    renderer.setPixelRatio(ratio);
    renderer.setClearAlpha(alpha);
    renderer.setSize(Math.max(1, cssW), Math.max(1, cssH), false);
    camera.aspect = aspect;
    camera.updateProjectionMatrix();
    viewer.renderNow();
  }
}
