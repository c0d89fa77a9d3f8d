// How the exact worker opens a model that may take a preview (worker/load-ops.js loadMesh; the page's side is
// progressive-core.js): the file is read, and a mesh big enough for a preview (every face brings at least 1.5
// edges) is sent to the page at once ({phase: 'read', mesh: {positions, triangles}}), so that the preview
// worker simplifies it while this one checks it; then it is checked and configured, and a model of at least
// `previewEdges` edges sends its design and the rest ahead of its factorization ({phase: 'opened'}, with the
// positions and triangles when they did not go with 'read'; the preview needs no edges, the page has them
// from the surface).
//
// Owns nothing. Imports nothing: it drives the worker's CoreClient.

// args: {bytes, format, settings, design, embedded (the design came from the file), previewEdges}.
// progress(value, transferList): the worker's progress message. Returns {opened, info, ahead}: openParsed's
// reply, the pending model's info, whether the page was sent the model for a preview.
export function openModelInSteps(core, args, progress) {
  const { bytes, format, settings, design, embedded, previewEdges } = args;
  const read = core.readModel(bytes, format);
  const early = previewEdges > 0 && 1.5 * read.faces >= previewEdges;
  if (early) {
    const { positions, triangles } = core.parsedMesh();
    progress({ phase: 'read', mesh: { positions, triangles } }, [positions.buffer, triangles.buffer]);
  }
  const opened = core.openParsed(settings, design);
  const info = core.pendingInfo();
  const ahead = previewEdges > 0 && info.edges >= previewEdges;
  if (ahead) {
    // With `read` sent, the mesh is not sent again.
    const mesh = early ? {} : (({ positions, triangles }) => ({ positions, triangles }))(core.pendingMesh());
    const cornerUVs = core.designer.pendingCornerUVs().slice();
    const design = core.pendingDesign();
    const value = { phase: 'opened', info, mesh, ...opened, embeddedDesign: embedded, cornerUVs, design };
    progress(value, [...Object.values(mesh).map((a) => a.buffer), cornerUVs.buffer]);
  }
  return { opened, info, ahead };
}
