// Numbers in the element's boxes: how they are shown, and how a typed value is checked. A value outside its
// box's range is shown invalid and never silently replaced; range and parse only (a step is a spinner
// increment, not a rule: 0.15 is a fine strength).

export function fmtMs(ms) {
  if (typeof ms !== 'number' || !Number.isFinite(ms)) return '–';
  return ms < 10 ? ms.toFixed(2) : ms < 100 ? ms.toFixed(1) : ms.toFixed(0);
}

export function fmtNum(x) {
  if (typeof x !== 'number') return String(x);
  return Math.abs(x) >= 1e4 || (x !== 0 && Math.abs(x) < 1e-2) ? x.toExponential(0) : String(+x.toPrecision(4));
}

// Whether a key press is typing into a box (which keeps its keys) rather than a shortcut.
export function isTyping(target) {
  return (
    target instanceof HTMLInputElement || target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement
  );
}

function invalid(input) {
  const v = input.validity;
  return (
    v.badInput ||
    v.rangeUnderflow ||
    v.rangeOverflow ||
    input.value.trim() === '' ||
    !Number.isFinite(Number(input.value))
  );
}

// Marks each number box invalid (aria-invalid) as it is typed in.
export function watchNumbers(inputs) {
  for (const input of inputs)
    input.addEventListener('input', () => input.setAttribute('aria-invalid', String(invalid(input))));
}

// The number in `input`, or an Error naming the box and the value when it is not a valid one.
export function checkedNumber(input, what) {
  const bad = invalid(input);
  input.setAttribute('aria-invalid', String(bad));
  if (!bad) return Number(input.value);
  const range = input.min !== '' ? ` (at least ${input.min})` : '';
  throw new Error(`${what} must be a number${range}; the box shows "${input.value}"`);
}

// An event handler whose errors (a bad number) go to `showError` instead of the console.
export function guarded(showError, fn) {
  return (e) => {
    try {
      fn(e);
    } catch (err) {
      showError(err.message);
    }
  };
}
