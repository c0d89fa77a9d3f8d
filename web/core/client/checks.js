// The checked call to the wasm core, shared by the client's call groups (core-client.js composes them). The core
// reports failures as strings (or -1 plus lastError()), throws C++ exceptions as numbers and traps as
// RuntimeErrors; every call goes through guard() and check() here, so that each comes out as a CoreError that
// names the operation. Owns the checks; imports core-error.js.
import { CoreError } from '../core-error.js';

// A C++ exception or a wasm trap escaping embind arrives as a number or a RuntimeError, neither readable.
export function describe(err) {
  if (err instanceof Error) return err.message || String(err);
  if (typeof err === 'number') return 'internal error in the core (uncaught C++ exception)';
  return String(err);
}

// "what: message", unless the core already named the operation itself.
export function prefixed(what, message) {
  return message.startsWith(`${what}:`) ? message : `${what}: ${message}`;
}

export function guard(what, fn) {
  try {
    return fn();
  } catch (err) {
    throw new CoreError(prefixed(what, describe(err)));
  }
}

// Embind turns null into 0 and a missing number into NaN before the core can see it: arguments are checked
// here, in the core's words, before they cross.
export function requireNumber(what, x) {
  if (typeof x !== 'number') {
    const got = x === null ? 'null' : x === undefined ? 'nothing' : typeof x;
    throw new CoreError(`${what} must be a number (got ${got})`);
  }
  return x;
}

// The calls that return an object report a failure as the error message instead.
export function checkObject(what, result) {
  if (typeof result === 'string') throw new CoreError(prefixed(what, result || 'rejected by the core'));
  return result;
}

export function check(what, result) {
  if (typeof result === 'string' && result !== '') throw new CoreError(prefixed(what, result));
  return result;
}
