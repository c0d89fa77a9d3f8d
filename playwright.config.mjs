// End-to-end tests in Debian's Chromium (never a downloaded browser) with software WebGL (SwiftShader).
// Software rendering is slow and the machine may be busy: one worker, generous time-outs.
import { defineConfig } from '@playwright/test';

const PORT = Number(process.env.TVF_TEST_PORT || 8191);
// Embedding tests (tests/e2e/embed.spec.mjs): a plain static host (no COOP/COEP) with a strict CSP.
const EMBED_PORT = Number(process.env.TVF_EMBED_PORT || PORT + 100);

export default defineConfig({
  testDir: 'tests/e2e',
  testMatch: '**/*.spec.mjs',
  outputDir: 'test-results',
  workers: 1,
  fullyParallel: false,
  retries: 0,
  timeout: 180_000,
  expect: { timeout: 30_000 },
  reporter: [['list']],
  use: {
    baseURL: `http://127.0.0.1:${PORT}/`,
    browserName: 'chromium',
    headless: true,
    viewport: { width: 1024, height: 720 },
    actionTimeout: 30_000,
    navigationTimeout: 60_000,
    screenshot: 'only-on-failure',
    // A trace records screenshots and DOM snapshots all through every test, kept or not: views.spec.mjs took 40.9 s
    // without, 47.2 s with (the CPU its launcher counts: 25.4 and 31.1 s). Off unless asked for
    // (TVF_E2E_TRACE=retain-on-failure, or `--trace on` on the command line) to look into a failure.
    trace: process.env.TVF_E2E_TRACE || 'off',
    launchOptions: {
      executablePath: process.env.TVF_CHROMIUM || '/usr/bin/chromium',
      args: [
        '--disable-gpu',
        '--disable-quic',
        '--enable-unsafe-swiftshader',
        '--use-angle=swiftshader',
        '--no-first-run',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
      ],
    },
  },
  webServer: [
    {
      // Rebuilding the web part is cheap (esbuild) and keeps `npx playwright test` from testing a stale bundle;
      // the wasm core must already be built (npm run build:wasm).
      // TVF_E2E_PREBUILT (scripts/e2e-queue.mjs): the page as `npm run build` left it, which another run's
      // server may be serving.
      command: `${process.env.TVF_E2E_PREBUILT ? '' : 'node scripts/build-web.mjs && '}node scripts/serve.mjs`,
      url: `http://127.0.0.1:${PORT}/`,
      env: { PORT: String(PORT) },
      reuseExistingServer: false,
      timeout: 120_000,
      stdout: 'pipe',
      stderr: 'pipe',
    },
    {
      command: 'mkdir -p .cache/embed-site && touch .cache/embed-site/index.html && node scripts/serve.mjs --root .cache/embed-site --plain --csp',
      url: `http://127.0.0.1:${EMBED_PORT}/index.html`,
      env: { PORT: String(EMBED_PORT) },
      reuseExistingServer: false,
      timeout: 60_000,
      stdout: 'pipe',
      stderr: 'pipe',
    },
  ],
});
