// How the session follows its core beyond a reply to each request: the exact field of a big model landing
// behind its preview (core/progressive-core.js), an exact op failing after the preview answered for it, and a
// replaced worker getting the model and design back (core/core-proxy.js supervision). Functions of the
// session (session.js), which owns all the state they touch.

// While the exact factorization of a big model runs behind its preview: a progress indicator of its own.
export function awaitExact(s) {
  s.emit('busy', { op: 'exactFactor', done: false });
  s.core.settled().then(() => s.emit('busy', { op: 'exactFactor', done: true }));
}

// The exact core has caught up with every edit: its field replaces the preview.
// reply: the exact core's reply, whose worker-side timings perf keeps (lastExact) beside the preview's (lastOp).
export function exactLanded(s, snapshot, reply = {}) {
  if (s.disposed) return;
  // A model's reply waiting for its mesh's uploads (model-loader.js) is adopted first.
  if (s.models.adopting) return void s.models.adopting.then(() => exactLanded(s, snapshot, reply));
  const receivedAt = performance.now();
  s.applySnapshot(snapshot);
  s.perf.exactLandedAt = performance.now();
  const applyMs = s.perf.exactLandedAt - receivedAt;
  s.perf.lastExact = { workerMs: reply.workerMs, workerParts: reply.timing, receivedAt, applyMs };
  s.models.previous = null;
  s.changed();
  s.emitChanges();
}

// An exact op failed after the preview had answered for it: the preview ends, and the page takes what the exact
// core holds (a load that failed keeps the previous model: model-loader.js).
export function exactFailed(s, err, op, caughtUp) {
  if (s.disposed) return;
  if (s.models.adopting) return void s.models.adopting.then(() => exactFailed(s, err, op, caughtUp));
  s.core.dropPreview();
  if (op === 'loadMesh') return void s.models.exactLoadFailed(err);
  if (caughtUp && err.reply?.snapshot) {
    s.applySnapshot(err.reply.snapshot);
    s.changed();
    s.emitChanges();
  }
  const what = `The exact solve did not take an edit made during the preview (${err.message})`;
  s.fail('core', new Error(`${what}; the design shown is the exact core's.`));
}

// The proxy replaced a dead, trapped or cancelled worker: the current model and design go to the new one, the
// page ids are mapped onto the new core ids (the history stays valid), and the user is told.
export async function revive(s, { kind, detail, call }) {
  const t0 = performance.now();
  if (!s.modelSource || s.disposed) return;
  s.core?.dropPreview(); // its ids would no longer be the new exact core's
  const uids = s.table.uidsInCoreOrder();
  const bytes = s.modelSource.bytes.slice();
  const reply = await call('loadMesh', [bytes, s.modelSource.format, s.settings(), s.design], [bytes.buffer]);
  s.applySnapshot(reply.snapshot);
  s.table.mapDocument(uids);
  s.changed();
  s.perf.lastRestart = { kind, detail, restoreMs: performance.now() - t0, constraints: s.table.size };
  s.emit('corerestart', { kind, detail });
  s.flash(
    kind === 'cancelled'
      ? 'Cancelled. The design is as it was before.'
      : `The core stopped (${detail}) and was restarted; your model and design are back.`,
    6000,
  );
}
