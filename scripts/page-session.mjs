// The app served from dist/ and Debian's Chromium with software GL, for the measurement scripts that drive the
// real page outside the test runner (texture-sweep.mjs, material-preview-pictures.mjs, bench-web-quad.mjs), and
// a CPU profile of the page (bench-web.mjs too). Never a downloaded browser: TVF_CHROMIUM or /usr/bin/chromium.
import { spawn } from 'node:child_process';
import { existsSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from '@playwright/test';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');

// scripts/serve.mjs on this port, resolved once it listens; kill() ends it.
export async function startServer(port) {
  const server = spawn(process.execPath, [resolve(ROOT, 'scripts/serve.mjs')], {
    env: { ...process.env, PORT: String(port) },
    stdio: ['ignore', 'pipe', 'inherit'],
  });
  await new Promise((ok, fail) => {
    server.stdout.on('data', (d) => String(d).includes('http://') && ok());
    server.on('exit', (code) => fail(new Error(`the server exited (${code})`)));
  });
  return server;
}

// The value after `name` on the command line, or fallback.
export function argument(name, fallback) {
  const i = process.argv.indexOf(name);
  return i > 0 ? process.argv[i + 1] : fallback;
}

// Ends the script (named in the message) when the page is not built in dist/.
export function requireBuiltPage(script) {
  if (existsSync(resolve(ROOT, 'dist/index.html'))) return;
  console.error(`${script}: dist/ not found; run npm run build:wasm && npm run build:web`);
  process.exit(1);
}

// The page served on `port` and Debian's Chromium around fn(browser, baseURL), both ended whatever happens; a
// failure is reported as `script: ` and the first line of its message, with exit code 1.
export async function withServedPage(script, port, fn) {
  const server = await startServer(port);
  const browser = await launchChromium();
  try {
    await fn(browser, `http://127.0.0.1:${port}/`);
  } catch (err) {
    console.error(`${script}: ${err.message.split('\n')[0]}`);
    process.exitCode = 1;
  } finally {
    await browser.close();
    server.kill();
  }
}

export function launchChromium() {
  return chromium.launch({
    executablePath: process.env.TVF_CHROMIUM || '/usr/bin/chromium',
    args: ['--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--no-first-run', '--disable-background-networking'],
  });
}

// A CPU profile of the page's main thread from now until stop(), written to file (nothing when file is null).
export async function startProfile(page, file) {
  if (!file) return { stop: async () => {} };
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 100 });
  await cdp.send('Profiler.start');
  return { stop: async () => writeFileSync(file, JSON.stringify((await cdp.send('Profiler.stop')).profile)) };
}
