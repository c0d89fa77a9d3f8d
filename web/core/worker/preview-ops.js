// A preview worker's steps (preview/, progressive-core.js on the page): a warm-up (warm-up.js; a failed one
// costs time, nothing else), the mesh's part from the exact worker's `read` (or `opened`) progress, and the
// rest from `opened`, which dispatch.js files as an open: its reply carries the preview field. From then on
// the state's preview answers every edit (dispatch.js, snapshot.js). Imports preview/ and preview-cache.js.
import { Preview } from '../preview/preview.js';
import { warmUpPreview } from '../preview/warm-up.js';
import { PreviewCache } from './preview-cache.js';

export function previewOps(state) {
  const kept = new PreviewCache();
  const anytime = {
    warmUpPreview() {
      state.warming = warmUpPreview(state.core).then(() => true, () => false);
      return state.warming;
    },

    async previewMesh(mesh) {
      await state.warming;
      // The parts of a mesh opened before (preview-cache.js); new ones are stored behind the reply.
      const found = await kept.find(mesh);
      state.prepared = await Preview.prepare(mesh, found.kept);
      if (!found.kept) kept.keep(found.key, Preview.keptParts(state.prepared));
      return { kept: !!found.kept };
    },
  };

  const opens = {
    openPreview(fineDoc, settings) {
      state.preview = Preview.open(state.core, state.prepared, fineDoc, settings);
      const { fine } = state.preview.map;
      state.spares.reset([fine.triangles.length, fine.positions.length]);
      return { timings: state.preview.timings };
    },
  };

  return { anytime, opens };
}
