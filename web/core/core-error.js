// The core's one error type: what the core refused or failed at, in its words, prefixed with the operation
// (client/checks.js makes them on the worker; core-proxy.js makes them again on the page from the reply, so
// that the page has one error path). Owns the class; imports nothing.

export class CoreError extends Error {
  constructor(message) {
    super(message);
    this.name = 'CoreError';
  }
}
