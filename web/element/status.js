// What the element tells the user without being asked: the error banner (with an optional action), the
// in-element confirmation, the status line (model, sizes, timings; a passing message over it) and the
// progress indicator of a long operation.
import { setText } from '../dom.js';
import { fmtMs } from './numbers.js';

const PROGRESS_DELAY_MS = 200; // shorter operations show no indicator at all

// $: querySelector in the shadow root; host: the element (its `busy` class shows the progress cursor).
export function bindStatus($, host, { onCancel }) {
  const banner = $('#error-banner');
  const bannerMsg = banner.querySelector('.message');
  const bannerAction = banner.querySelector('.action');
  const status = $('#status');
  const progress = $('#progress');
  const confirmBox = $('#confirm');
  let bannerRun = null;
  let confirmDone = null;
  let flashTimer = 0, flashText = null;
  let statusText = 'Loading…';

  // ---- banner
  // action: {label, run} — a button next to the message (e.g. apply a design made for another mesh anyway).
  function showError(message, action = null) {
    bannerMsg.textContent = message;
    bannerAction.hidden = !action;
    bannerAction.textContent = action?.label ?? '';
    bannerRun = action?.run ?? null;
    banner.hidden = false;
  }

  // After the next success: an error that no longer describes the state must not stay up.
  function clearError() {
    banner.hidden = true;
    bannerRun = null;
  }
  banner.querySelector('.dismiss').addEventListener('click', () => clearError());
  bannerAction.addEventListener('click', () => {
    const run = bannerRun;
    clearError();
    run?.();
  });

  // ---- confirmation
  // An in-element question (no window.confirm: it would block every designer on the page). Resolves true
  // when the user chose `ok`, false on Cancel or Escape.
  function confirm(message, ok) {
    confirmDone?.(false);
    $('#confirm-message').textContent = message;
    $('#confirm-ok').textContent = ok;
    confirmBox.hidden = false;
    $('#confirm-ok').focus();
    return new Promise((resolve) => {
      confirmDone = (yes) => {
        confirmDone = null;
        confirmBox.hidden = true;
        resolve(yes);
      };
    });
  }
  $('#confirm-ok').addEventListener('click', () => confirmDone?.(true));
  $('#confirm-cancel').addEventListener('click', () => confirmDone?.(false));
  confirmBox.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') {
      e.stopPropagation();
      confirmDone?.(false);
    }
  });

  // ---- status line
  function renderStatus() {
    setText(status, flashText ?? statusText);
  }

  // model: {name, info, stats}
  function setStatus({ name, info, stats = {} }) {
    if (!info) return;
    statusText = [
      name,
      `V ${info.vertices}`,
      `E ${info.edges}`,
      `F ${info.faces}`,
      `genus ${info.genus}`,
      `boundary loops ${info.boundaryLoops}`,
      `factor ${fmtMs(stats.factorMs)} ms`,
      `update ${fmtMs(stats.updateMs)} ms`,
      `solve ${fmtMs(stats.solveMs)} ms`,
    ].join('  ·  ');
    const problems = (info.problems || []).map((p) => (typeof p === 'string' ? p : JSON.stringify(p)));
    status.title = problems.length ? `Mesh notes:\n${problems.join('\n')}` : '';
    status.classList.toggle('has-problems', problems.length > 0);
    renderStatus();
  }

  function flash(text, ms = 2500) {
    clearTimeout(flashTimer);
    flashText = text;
    renderStatus();
    flashTimer = setTimeout(() => {
      flashText = null;
      renderStatus();
    }, ms);
  }

  // ---- progress
  // Cancel stops the operation in flight by replacing the core (core-proxy.js); Escape does the same while busy.
  progress.querySelector('.cancel')?.addEventListener('click', () => onCancel?.());

  // Returns a function that ends the indication, whose relabel(text) names the operation's current phase. Shows
  // nothing for operations shorter than 200 ms. The bar does not move and the seconds tick once a second: with
  // software GL every repaint is composited on the CPU, and a sliding bar's frames took a core from the very
  // factorization it waited for (a 1.25M-edge model's first field came 4 s later).
  function startProgress(label) {
    const t0 = performance.now();
    let ticker = 0;
    let shown = false;
    const update = () => {
      if (!shown) return;
      const seconds = Math.round((performance.now() - t0) / 1000);
      progress.querySelector('.label').textContent = `${label} ${seconds} s`;
    };
    const show = setTimeout(() => {
      shown = true;
      progress.hidden = false;
      host.classList.add('busy');
      update();
      ticker = setInterval(update, 1000);
    }, PROGRESS_DELAY_MS);
    const end = () => {
      clearTimeout(show);
      clearInterval(ticker);
      if (!shown) return; // never shown: the panel is left untouched (a write is a repaint)
      shown = false;
      progress.hidden = true;
      host.classList.remove('busy');
    };
    end.relabel = (text) => {
      label = text;
      update();
    };
    return end;
  }

  return {
    showError,
    clearError,
    confirm,
    setStatus,
    flash,
    startProgress,
    get busy() {
      return !progress.hidden;
    },
    dispose: () => clearTimeout(flashTimer),
  };
}
