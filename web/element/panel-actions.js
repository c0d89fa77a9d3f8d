// Panel input → session: what each button, field and file drop of the panels (ui.js) does. UI-started
// actions report failures in the banner (designer.report); the API's variants reject instead.
import { baseName, downloadBlob, downloadJson, readJsonFile } from '../session/documents.js';
import { ACCEPT } from '../session/model-files.js';
import { captureScreenshot } from '../views/screenshot.js';

// Asks before a UI action would discard unsaved edits; true to go ahead.
async function mayDiscard(d, what, confirmLabel) {
  const s = d.session;
  if (!s.hasUnsavedEdits()) return true;
  const n = s.table.size;
  return d.ui.confirm(
    `${what} replaces the current design (${n} constraint${n === 1 ? '' : 's'}), which has unsaved edits. ` +
      'Save it first with Save (Ctrl+S), or go ahead.',
    confirmLabel,
  );
}

// A design file picked or dropped by the user: refused with the reason (the design untouched); a design for
// another mesh can be applied after an explicit choice, undoably.
async function loadDesignFile(d, file) {
  const s = d.session;
  let design;
  try {
    design = await readJsonFile(file);
  } catch (err) {
    throw s.fail('design', new Error(`Could not load ${file.name}: ${err.message}`));
  }
  const apply = (ignoreFingerprint) =>
    s.replaceDesign(design, 'load design', { ignoreFingerprint }).then(() => {
      s.markSaved();
      d.ui.flash(
        `Loaded ${file.name} (${s.table.size} constraints). Undo (Ctrl+Z) brings the previous design back.`,
        5000,
      );
    });
  try {
    await apply(false);
  } catch (err) {
    const message = `Could not load ${file.name}: ${err.message}`;
    s.emit('error', { code: 'design', message });
    if (/another mesh/.test(err.message))
      d.ui.showError(message, { label: 'Apply anyway', run: () => d.report(apply(true)) });
  }
}

// A Directional .sing picked or dropped: its singularities join the design as one step (undo removes them all);
// a refusal is shown as any other, the design untouched.
async function loadSingFile(d, file) {
  const ids = await d.session.topology.addSingFile(await file.text(), file.name);
  const n = ids.length;
  d.ui.flash(`Added ${n} singularit${n === 1 ? 'y' : 'ies'} from ${file.name}. Undo (Ctrl+Z) removes them.`, 5000);
}

function saveDesign(d) {
  const s = d.session;
  try {
    s.requireReady();
    const name = `${baseName(s.modelName)}.design.json`;
    downloadJson(name, JSON.stringify(s.design, null, 1));
    s.markSaved();
    d.ui.flash(`Saved ${name} (${s.table.size} constraint${s.table.size === 1 ? '' : 's'}).`, 4000);
  } catch (err) {
    d.ui.showError(err.message);
  }
}

export function panelActions(d) {
  const editable = (fn) => (...args) => (d.session.readonly ? undefined : fn(...args));
  const s = () => d.session;
  return {
    accept: ACCEPT,
    onOpen: async (file, companions) => {
      if (await mayDiscard(d, 'Opening a model', 'Open anyway')) d.report(s().loadModel(file, { companions }));
    },
    onLoadDesign: editable(async (file) => {
      if (await mayDiscard(d, 'Loading a design', 'Load anyway')) d.report(loadDesignFile(d, file));
    }),
    onLoadSing: editable((file) => d.report(loadSingFile(d, file))),
    onSaveDesign: () => saveDesign(d),
    onExportField: () => {
      const download = (text) => downloadJson(`${baseName(s().modelName)}.field.json`, text);
      return d.report(s().exportField().then(download));
    },
    onTool: (tool) => {
      d.tools?.setTool(tool); // bindUi selects orbit before the tools exist
      // Placing singularities means seeing where the field puts the rest: the Singularities view comes on (its box
      // ticked, so it stays a choice the user sees and can undo).
      const sync = d.viewSync;
      if (tool === 'singularity' && sync && !sync.views.singularities) sync.set({ singularities: true });
      d.onTool(tool);
    },
    onUndo: editable(() => d.edit('undo', s().step(false))),
    onRedo: editable(() => d.edit('redo', s().step(true))),
    onBoundary: editable((bc) => d.report(s().setSetting('boundary', bc))),
    onGamma: editable((g) => d.report(s().setSetting('gamma', g))),
    // What a new N removes is announced by the session (a flash) and comes back with undo.
    onSymmetry: editable((n) => d.report(s().setSetting('symmetry', n))),
    onCurvatureAlignment: editable((strength) => d.report(s().setSetting('curvatureAlignment', strength))),
    // The angle over which edges are sharp features (0: none); the Feature tool's additions and removals kept.
    onFeatureAngle: editable((angle) => d.report(s().topology.setFeatures({ angle }))),
    // The field with exactly the prescribed singularities (none when none are prescribed), or free to add its own.
    onExactSingularities: editable((exact) => d.report(s().topology.setExactSingularities(exact))),
    onViews: (views) => d.viewSync?.apply(views),
    onSelect: (uid) => s().select(uid),
    onFrame: (view) => d.viewer.frame(view),
    onScreenshot: () => {
      const c = d.viewer.canvas;
      const size = { width: Math.min(8192, 2 * c.clientWidth), height: Math.min(8192, 2 * c.clientHeight) };
      d.report(captureScreenshot(d.viewer, size).then((blob) => downloadBlob(`${baseName(s().modelName)}.png`, blob)));
    },
    // The first-run hint is remembered with the autosave (the app page), shown every time elsewhere.
    hintKey: d.session.autosave.name != null ? 'tvf-hint-seen' : null,
    onRemove: editable((uid) => d.edit('delete', s().remove(uid))),
    onEditWeight: editable((uid, w) => d.report(s().setParameter('weight', uid, w))),
    onEditStrength: editable((uid, v) => d.report(s().setParameter('strength', uid, v))),
    onCancel: () => s().cancel(),
    // The constraints and prescribed singularities go; the settings and the features stay.
    onClear: editable(() => {
      const cleared = { ...s().settings(), ...s().table.featureKeys(), constraints: [] };
      return s().table.size && d.report(s().replaceDesign(cleared, 'clear'));
    }),
  };
}
