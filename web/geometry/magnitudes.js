// A field's magnitude scale, shared by the arrows, the surface colours and the legend (views/), and computed
// where the field is made (core/worker/derived-field.js, core/preview/preview.js) so that the page's thread does not
// walk every vertex again after each edit (~40 ms per field at 400k vertices).
//
// Owns nothing. Imports nothing.

// The magnitude scale the arrows, the surface colours and the legend share, for vectors 3 per item: the
// largest magnitude and the 98th percentile, where the ramp tops out (sources and vortices make a few huge
// values that would otherwise leave everything else at the bottom). Non-finite magnitudes count as 0.
// Linear time (a selection, not a sort): it runs after every edit on every vertex.
export function magnitudeScale(vectors) {
  const m = vectors.length / 3;
  const mags = new Float64Array(m);
  let max = 0;
  for (let i = 0; i < m; i++) {
    const x = vectors[3 * i], y = vectors[3 * i + 1], z = vectors[3 * i + 2];
    let v = Math.sqrt(x * x + y * y + z * z);
    if (!Number.isFinite(v)) v = Math.hypot(x, y, z); // squares beyond double range
    mags[i] = Number.isFinite(v) ? v : 0;
    if (mags[i] > max) max = mags[i];
  }
  const top = (m ? select(mags, Math.min(m - 1, Math.floor(0.98 * m))) : 0) || max;
  return { max, top };
}

// The k-th smallest value of a (reordered in place): quickselect with a median-of-three pivot.
function select(a, k) {
  let lo = 0, hi = a.length - 1;
  while (hi > lo) {
    const mid = (lo + hi) >> 1;
    const p = median3(a[lo], a[mid], a[hi]);
    let i = lo, j = hi;
    while (i <= j) {
      while (a[i] < p) i++;
      while (a[j] > p) j--;
      if (i <= j) {
        const t = a[i];
        a[i] = a[j];
        a[j] = t;
        i++;
        j--;
      }
    }
    if (k <= j) hi = j;
    else if (k >= i) lo = i;
    else return a[k];
  }
  return a[k];
}

function median3(a, b, c) {
  return a < b ? (b < c ? b : a < c ? c : a) : a < c ? a : b < c ? c : b;
}
