// Synchronous change signals: the session says what changed and knows nothing of who listens (the element
// subscribes its views and panels, as an editor's viewport and sidebar subscribe to the editor's signals).
export class Emitter {
  #listeners = new Map();

  // Returns the function that unsubscribes.
  on(type, listener) {
    const list = this.#listeners.get(type) ?? [];
    list.push(listener);
    this.#listeners.set(type, list);
    return () => {
      const now = this.#listeners.get(type) ?? [];
      this.#listeners.set(type, now.filter((l) => l !== listener));
    };
  }

  emit(type, detail) {
    for (const listener of this.#listeners.get(type) ?? []) listener(detail);
  }

  clearListeners() {
    this.#listeners.clear();
  }
}
