// Files in and out: the Open…, Save, Load… and Export buttons, their file pickers, and dropping files on the
// view. A .gltf may come with its .bin files: the first mesh-like file is the model, the rest are its
// resources; a lone .json is a design, a lone .sing (Directional's singularities) is added to the design.
const MODEL = /\.(glb|gltf|obj|off|ply)$/i;

// $: querySelector in the shadow root.
export function bindFiles($, actions) {
  const fileInput = $('#file-input');
  const designInput = $('#design-input');
  const viewport = $('#viewport');
  const dropOverlay = $('#drop-overlay');
  fileInput.accept = actions.accept;
  designInput.accept = '.json,application/json,.sing';

  function openFiles(files) {
    const main = files.find((f) => MODEL.test(f.name));
    if (!main && files.length === 1 && /\.json$/i.test(files[0].name)) return actions.onLoadDesign(files[0]);
    if (!main && files.length === 1 && /\.sing$/i.test(files[0].name)) return actions.onLoadSing(files[0]);
    const model = main ?? files[0];
    actions.onOpen(model, files.filter((f) => f !== model));
  }

  $('#open-button').addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    const files = [...fileInput.files];
    fileInput.value = ''; // picking the same file again must fire change again
    if (files.length) openFiles(files);
  });
  $('#save-design').addEventListener('click', () => actions.onSaveDesign());
  $('#load-design').addEventListener('click', () => designInput.click());
  designInput.addEventListener('change', () => {
    const [file] = designInput.files;
    designInput.value = '';
    if (file) (/\.sing$/i.test(file.name) ? actions.onLoadSing : actions.onLoadDesign)(file);
  });
  $('#export-field').addEventListener('click', () => actions.onExportField());

  // Drag and drop anywhere over the viewport.
  let dragDepth = 0;
  const carriesFiles = (e) => e.dataTransfer?.types.includes('Files');
  viewport.addEventListener('dragenter', (e) => {
    if (!carriesFiles(e)) return;
    e.preventDefault();
    dragDepth++;
    dropOverlay.hidden = false;
  });
  viewport.addEventListener('dragover', (e) => {
    if (!carriesFiles(e)) return;
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
  });
  viewport.addEventListener('dragleave', () => {
    if (--dragDepth <= 0) {
      dragDepth = 0;
      dropOverlay.hidden = true;
    }
  });
  viewport.addEventListener('drop', (e) => {
    e.preventDefault();
    dragDepth = 0;
    dropOverlay.hidden = true;
    const files = [...(e.dataTransfer?.files ?? [])];
    if (files.length) openFiles(files);
  });
}
