// Undo/redo stacks of command objects (commands/): execute() runs a command and records it, undo() takes the
// newest back (the inverse factor update), redo() runs it again. A command that fails stays where it was.
// The history only stacks; each command knows its own change.

const LIMIT = 500;

export class History {
  constructor(onChange = () => {}) {
    this.undoStack = [];
    this.redoStack = [];
    this.onChange = onChange;
  }

  // Applies the command; records it unless it changed nothing (command.changes === false).
  async execute(command, session) {
    await command.execute(session);
    if (command.changes === false) return;
    this.undoStack.push(command);
    if (this.undoStack.length > LIMIT) this.undoStack.shift();
    this.redoStack.length = 0;
    this.onChange();
  }

  async undo(session) {
    const command = this.peekUndo();
    if (!command) return false;
    await command.undo(session);
    this.redoStack.push(this.undoStack.pop());
    this.onChange();
    return true;
  }

  async redo(session) {
    const command = this.peekRedo();
    if (!command) return false;
    await command.execute(session);
    this.undoStack.push(this.redoStack.pop());
    this.onChange();
    return true;
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
