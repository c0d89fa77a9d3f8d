// Designs as documents: downloads (design, field), reading a design file, and the autosave's quick copy in
// localStorage (the durable, versioned autosave is autosave-store.js, in IndexedDB).
// Autosaves are keyed by the model's name, size and a content hash, so a different file that happens to
// share a name never receives a design whose indices mean nothing on it.

import { fnv1a } from '../core/model-bytes.js';
import { CREASED_FEATURE_ANGLE } from './constraint-table.js';

const AUTOSAVE_PREFIX = 'tvf.autosave.v1:';

// FNV-1a over the bytes (core/model-bytes.js): fast (a few ms per MB) and plenty to tell models apart.
// digest: given when the bytes were read on another thread, which made it there.
export function modelKey(name, bytes, digest = fnv1a(bytes)) {
  return `${name}|${bytes.length}|${digest}`;
}

// Nothing to keep: no constraint, no prescribed singularity, no feature edge edit and every setting at its
// default (a feature angle of 0 or a creased surface's: a design left at either is not worth a version).
export function isEmptyDesign(design) {
  const vectorField = (design.symmetry ?? 1) === 1 && !design.curvatureAlignment;
  const defaults = (design.boundary ?? 'free') === 'free' && !design.gamma && vectorField;
  const angle = design.featureAngle ?? 0;
  const features = (angle === 0 || angle === CREASED_FEATURE_ANGLE) && !design.featureEdges;
  return !design.constraints?.length && !design.singularities?.length && defaults && features;
}

// store: the autosave attribute's value ('' on the app page), so that several designers on one origin can keep
// separate autosaves; key: modelKey().
function storageKey(store, key) {
  return `${AUTOSAVE_PREFIX}${store ? `${store}|` : ''}${key}`;
}

export function loadAutosave(store, key) {
  try {
    const text = localStorage.getItem(storageKey(store, key));
    return text ? JSON.parse(text) : null;
  } catch {
    return null; // storage disabled or a corrupt entry: start without it
  }
}

export function saveAutosave(store, key, design, savedAt = new Date().toISOString()) {
  try {
    if (isEmptyDesign(design)) localStorage.removeItem(storageKey(store, key));
    else localStorage.setItem(storageKey(store, key), JSON.stringify({ savedAt, design }));
    return true;
  } catch {
    return false; // quota or privacy mode: autosave is a convenience, never an error
  }
}

export function baseName(name) {
  return (name || 'model').replace(/\.[a-z0-9]+$/i, '');
}

// text: a JSON string or an object.
export function downloadJson(filename, text) {
  const json = typeof text === 'string' ? text : JSON.stringify(text, null, 1);
  downloadBlob(filename, new Blob([json], { type: 'application/json' }));
}

export function downloadBlob(filename, blob) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = filename;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

export async function readJsonFile(file) {
  const text = await file.text();
  try {
    return JSON.parse(text);
  } catch (err) {
    throw new Error(`${file.name} is not valid JSON (${err.message})`);
  }
}
