import base from './playwright.config.mjs';
export default { ...base, webServer: { ...base.webServer, command: 'node scripts/serve.mjs --root /tmp/devdist' } };
