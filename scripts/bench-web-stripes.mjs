// bench:web's stripes stage (scripts/bench-web.mjs --stripes N): the stripe pattern turned on over the field the
// strokes left, then N strokes, each timed from addStroke to its field drawn, to its stripes drawn (the core's
// local update where it took one) and to its whole pattern drawn (asked for at once: stripesIdle settled), with the
// page's long tasks (PerformanceObserver 'longtask', collected by bench-web.mjs into window.__longTasks); then
// the same strokes in quick succession, each next one's field timed while the last one's stripes are made.
const median = (v) => {
  const s = v.filter(Number.isFinite).sort((a, b) => a - b);
  return s.length === 0 ? null : s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
const longest = (tasks) => tasks.reduce((m, t) => Math.max(m, t.ms), 0);

export async function stripesBench(page, strokes) {
  await page.evaluate(() => window.__longTasks.splice(0));
  const first = await page.evaluate(async () => {
    const t0 = performance.now();
    const state = await window.tvf.setStripes({ visible: true });
    await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
    return { ms: performance.now() - t0, stats: state.stats };
  });
  const firstTasks = await page.evaluate(() => window.__longTasks.splice(0));
  const runs = [];
  for (const points of strokes) {
    runs.push(await page.evaluate(async (pts) => {
      const frames = () => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      await frames();
      const before = window.tvf.stripes().stats?.fieldKey;
      const t0 = performance.now();
      await window.tvf.addStroke(pts);
      const fieldMs = performance.now() - t0;
      await window.tvf.settled();
      let state = await window.tvf.stripesIdle();
      while (state.stats?.fieldKey === before && performance.now() - t0 < 60_000) {
        await frames();
        state = await window.tvf.stripesIdle();
      }
      // Timed as the field is: when their draw was issued (the controller draws them at once).
      const stripesMs = state.stats.drawnAt - t0;
      await frames();
      const onScreenMs = performance.now() - t0;
      const settled = await window.tvf.stripesIdle({ settled: true });
      await frames();
      return {
        fieldMs, stripesMs, onScreenMs, stats: state.stats, settledMs: performance.now() - t0, settledStats: settled.stats,
      };
    }, points));
  }
  const tasks = await page.evaluate(() => window.__longTasks.splice(0));
  // Strokes in quick succession: each next one as soon as the last one's field is drawn, while the worker makes
  // that field's stripes. The next field's time shows whether it waited for them (a pattern gives way to a
  // newer edit where the page is cross-origin isolated: core-proxy.js).
  const quick = await page.evaluate(async (list) => {
    const out = [];
    for (const pts of list) {
      const t0 = performance.now();
      await window.tvf.addStroke(pts);
      out.push(performance.now() - t0);
    }
    await window.tvf.settled();
    await window.tvf.stripesIdle();
    return out;
  }, strokes);
  await page.evaluate(() => window.tvf.setStripes({ visible: false }));
  return {
    stripesFirstMs: first.ms,
    stripesFirstStats: first.stats,
    stripesLongestFirstTaskMs: longest(firstTasks),
    // Medians over the strokes: the field drawn, the stripes drawn (both from addStroke), their ratio per edit,
    // and the worker's pattern (the eigensolver's steps, the whole op).
    stripesStrokeFieldMs: median(runs.map((r) => r.fieldMs)),
    stripesStrokeMs: median(runs.map((r) => r.stripesMs)),
    // The stripes with two frames presented after them (polled a frame or two at a time: up to ~50 ms late).
    stripesStrokeOnScreenMs: median(runs.map((r) => r.onScreenMs)),
    stripesOverFieldPerEdit: median(runs.map((r) => r.stripesMs / r.fieldMs)),
    stripesWorkerMs: median(runs.map((r) => r.stats?.workerMs)),
    // Of it the core's computation (DesignStripes::compute, timed in wasm); the rest lays its arrays out per corner.
    stripesCoreMs: median(runs.map((r) => r.stats?.ms)),
    // From the page's request (once the field is drawn) to the stripes drawn, and the drawing alone (the page's
    // part after the reply: the pattern's attributes and the frame).
    stripesRoundTripMs: median(runs.map((r) => r.stats?.roundTripMs)),
    stripesDrawMs: median(runs.map((r) => r.stats?.drawMs)),
    stripesIterations: median(runs.map((r) => r.stats?.iterations)),
    // The worker's pattern in parts (medians): the energy's factorization, the eigensolver's steps, the adapted
    // spacing; and how many strokes' energies a shift below the last eigenvalue was refused for.
    stripesWorkerParts: Object.fromEntries(
      ['factorMs', 'iterateMs', 'spacingMs', 'smoothMs', 'alignMs', 'closeMs']
        .map((k) => [k, median(runs.map((r) => r.stats?.[k]))]),
    ),
    stripesShiftsRefused: runs.filter((r) => r.stats?.shiftRefused).length,
    // How many strokes' stripes came as a local update, on how many vertices (median), and the whole pattern
    // after it, asked for as soon as the local update was drawn: from addStroke, and the worker's part.
    stripesLocalUpdates: runs.filter((r) => r.stats?.localUpdate).length,
    // How many were made ahead: by the worker after the edit's field, before the page asked (stripes/worker-ops.js).
    stripesMadeAhead: runs.filter((r) => r.stats?.madeAhead).length,
    // How many strokes' field frames waited for their stripes (one frame for both: StripesController.followsWithin),
    // and for how long they could have (median).
    stripesFieldFramesWaited: runs.filter((r) => r.stats?.fieldFrameWaited > 0).length,
    stripesFieldFrameWaitMs: median(runs.map((r) => r.stats?.fieldFrameWaited)),
    stripesLocalVertices: median(runs.filter((r) => r.stats?.localUpdate).map((r) => r.stats.localVertices)),
    stripesStrokeSettledMs: median(runs.map((r) => r.settledMs)),
    stripesSettledWorkerMs: median(runs.map((r) => r.settledStats?.workerMs)),
    stripesLongestStrokeTaskMs: longest(tasks),
    stripesStrokes: runs.length,
    // Each stroke's [field drawn, stripes drawn, the core's computation] (ms), in order.
    stripesEachStroke: runs.map((r) => [r.fieldMs, r.stripesMs, r.stats?.ms].map((x) => Math.round(x * 10) / 10)),
    // The same strokes again in quick succession (the first waits for nothing): the later ones' fields, median.
    stripesQuickStrokeFieldMs: median(quick.slice(1)),
  };
}
