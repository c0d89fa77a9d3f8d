// Undo/redo stacks of design edits. An entry is plain data describing the change in terms of the page's
// constraint ids (which survive a delete and re-add); main.js turns it into the inverse factor update.
//
// Entry kinds: {kind: 'add' | 'remove', uid, spec}, {kind: 'weight' | 'strength', uid, from, to},
// {kind: 'boundary' | 'gamma', from, to}, {kind: 'design', label, before, after} with before/after =
// {design, uids} (a whole document, e.g. Load or Clear).

const LIMIT = 500;

export class History {
  constructor(onChange = () => {}) {
    this.undoStack = [];
    this.redoStack = [];
    this.onChange = onChange;
  }

  push(entry) {
    this.undoStack.push(entry);
    if (this.undoStack.length > LIMIT) this.undoStack.shift();
    this.redoStack.length = 0;
    this.onChange();
  }

  clear() {
    this.undoStack.length = 0;
    this.redoStack.length = 0;
    this.onChange();
  }

  peekUndo() {
    return this.undoStack[this.undoStack.length - 1] ?? null;
  }

  peekRedo() {
    return this.redoStack[this.redoStack.length - 1] ?? null;
  }

  // Called once the inverse (or the redo) has been applied to the core.
  didUndo() {
    this.redoStack.push(this.undoStack.pop());
    this.onChange();
  }

  didRedo() {
    this.undoStack.push(this.redoStack.pop());
    this.onChange();
  }

  labels() {
    return { undo: this.undoStack.map(describe), redo: this.redoStack.map(describe).reverse() };
  }
}

export function describe(entry) {
  if (!entry) return '';
  switch (entry.kind) {
    case 'add': return `add ${entry.spec.type} #${entry.uid}`;
    case 'remove': return `delete ${entry.spec.type} #${entry.uid}`;
    case 'weight': return `weight of #${entry.uid}`;
    case 'strength': return `strength of #${entry.uid}`;
    case 'boundary': return 'boundary condition';
    case 'gamma': return 'γ';
    case 'design': return entry.label;
    default: return entry.kind;
  }
}
