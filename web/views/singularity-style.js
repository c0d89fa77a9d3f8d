// How a singularity is shown: its colour and its label, from its index (a multiple of 1/N for an N-field).
// Pure (no three.js, no DOM), so the ramp and the fractions are checked in node.

const POSITIVE = '#facc15'; // +1 and above, as a vector field's singularities have always been drawn
const NEGATIVE = '#c084fc'; // −1 and below
// Where the ramps start as |index| → 0: the same hue, paler, so that +1/4 reads as "a little of +1".
const POSITIVE_PALE = [0xfe, 0xf9, 0xc3];
const NEGATIVE_PALE = [0xf3, 0xe8, 0xff];

const MINUS = '\u2212';

// A prescribed singularity (one the user pinned, not one the field placed itself): the disc of its index,
// ringed in cyan, a hue the index ramps, the handles and the feature lines never use.
export const PRESCRIBED_RING = '#22d3ee';
// The marker of the prescribed singularity the Singularity tool has selected, and its ghost while it is dragged.
export const SELECTED_RING = '#ffffff';

function gcd(a, b) {
  while (b) [a, b] = [b, a % b];
  return a;
}

// "+1", "−2" for a vector field (N = 1, as before); "+1/2", "−1/4", "+3/4", "+1" for an N-field, the index
// reduced to lowest terms over N.
export function indexLabel(index, N = 1) {
  if (N <= 1) {
    const r = Math.round(index);
    return r > 0 ? `+${r}` : r < 0 ? `${MINUS}${-r}` : '0';
  }
  const k = Math.round(index * N);
  if (k === 0) return '0';
  const g = gcd(Math.abs(k), N), num = Math.abs(k) / g, den = N / g;
  return `${k > 0 ? '+' : MINUS}${num}${den === 1 ? '' : `/${den}`}`;
}

// The disc's fill: yellow for positive, violet for negative, as before for whole indices; a fractional index
// lies on the ramp from a pale tint of its sign's colour (|index| → 0) to the full colour (|index| = 1).
export function singularityFill(index) {
  const full = index > 0 ? POSITIVE : NEGATIVE;
  const m = Math.abs(index);
  if (Number.isInteger(index) || m >= 1) return full;
  const pale = index > 0 ? POSITIVE_PALE : NEGATIVE_PALE;
  const to = [1, 3, 5].map((i) => parseInt(full.slice(i, i + 2), 16));
  // √ spreads the common small fractions (1/6 … 1/2) further apart than a linear ramp would.
  const t = Math.sqrt(m);
  return `#${pale.map((p, i) => Math.round(p + t * (to[i] - p)).toString(16).padStart(2, '0')).join('')}`;
}
