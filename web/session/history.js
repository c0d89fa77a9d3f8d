// Undo/redo stacks of command objects (commands/), as plain records: the session runs a command and pushes it
// here once it took, and moves it between the stacks once its undo or redo took. A command that fails is not
// moved. The history runs nothing itself.

const LIMIT = 500;

export class History {
  constructor(onChange = () => {}) {
    this.undoStack = [];
    this.redoStack = [];
    this.onChange = onChange;
  }

  // A command that took; a new edit drops what could be redone.
  push(command) {
    this.undoStack.push(command);
    if (this.undoStack.length > LIMIT) this.undoStack.shift();
    this.redoStack.length = 0;
    this.onChange();
  }

  // The newest command was taken back (peekUndo()).
  undone() {
    this.redoStack.push(this.undoStack.pop());
    this.onChange();
  }

  // The next command to redo was run again (peekRedo()).
  redone() {
    this.undoStack.push(this.redoStack.pop());
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

  // The stacks as plain data (commands' serialize()), oldest first.
  serialize() {
    return { undo: this.undoStack.map((c) => c.serialize()), redo: this.redoStack.map((c) => c.serialize()) };
  }

  labels() {
    return { undo: this.undoStack.map((c) => c.label), redo: this.redoStack.map((c) => c.label).reverse() };
  }
}
