// Headless Chromium for the page tests (/usr/bin/chromium through npm playwright-core), shut
// off from the network: a fresh profile, no proxy, every host name but 127.0.0.1 unresolvable,
// and every request that does not go to `origin` aborted.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM = '/usr/bin/chromium';

/// Opens a page that may only talk to `origin` (http://127.0.0.1:PORT). `webgl`: WebGL in
/// software (SwiftShader) instead of no GPU at all. Console warnings and errors of the page
/// are appended to `warnings`. Returns {page, close}; close() removes the profile.
/// @throws Error when Chromium is missing or does not start within `timeoutMs`
export async function openPage(origin, { webgl = false, timeoutMs = 60000, warnings = [],
                                         viewport = null } = {}) {
  if (!fs.existsSync(CHROMIUM)) {
    throw new Error(`${CHROMIUM} missing (Debian chromium; scripts/install-deps.sh --test)`);
  }
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'cutaway-chromium-'));
  let context = null;
  const close = async () => {
    if (context) await context.close().catch(() => {});
    fs.rmSync(profile, { recursive: true, force: true });
  };
  try {
    // A persistent context is how playwright takes an explicit (here fresh) --user-data-dir.
    context = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      timeout: timeoutMs,
      ...(viewport ? { viewport } : {}),
      args: [
        '--headless', '--no-sandbox', '--disable-quic', '--no-first-run',
        ...(webgl ? ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'] : ['--disable-gpu']),
        '--disable-background-networking', '--disable-component-update', '--disable-sync',
        '--no-proxy-server', '--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1',
        '--disable-features=Translate,OptimizationHints,MediaRouter,DialMediaRouteProvider',
        '--disable-domain-reliability', '--no-pings', '--metrics-recording-only',
      ],
      env: { ...process.env, GOOGLE_API_KEY: 'no', GOOGLE_DEFAULT_CLIENT_ID: 'no',
             GOOGLE_DEFAULT_CLIENT_SECRET: 'no' },
    });
    await context.route('**/*', (route) =>
      route.request().url().startsWith(origin + '/') ? route.continue() : route.abort());
    const page = context.pages()[0] ?? (await context.newPage());
    // Every wait and action may take as long as the caller allows: the default (30 s) is short
    // for a page drawing WebGL in software on a machine busy with other tests.
    page.setDefaultTimeout(timeoutMs);
    page.on('console', (m) => {
      // Chromium's notes on how fast its software GL ran ("GPU stall due to ReadPixels") come
      // and go with the machine's load; they say nothing about the page.
      if (/GL Driver Message \(OpenGL, Performance,/.test(m.text())) return;
      if (m.type() === 'warning' || m.type() === 'error') warnings.push(`${m.type()}: ${m.text()}`);
    });
    page.on('pageerror', (e) => warnings.push(`pageerror: ${e.message}`));
    return { page, close };
  } catch (e) {
    await close();
    throw e;
  }
}

/// Starts `cutaway edit FILE --port 0 [EXTRA...]`; resolves with {child, origin} once it prints
/// its URL.
export function startEditor(cutaway, file, extra = []) {
  return new Promise((resolve, reject) => {
    const child = spawn(cutaway, ['edit', file, '--port', '0', ...extra],
                        { stdio: ['ignore', 'pipe', 'pipe'] });
    let seen = '';
    const look = (data) => {
      seen += data;
      const m = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(seen);
      if (m) resolve({ child, origin: `http://127.0.0.1:${m[1]}` });
    };
    child.stdout.on('data', look);
    child.stderr.on('data', look);
    child.on('exit', (code) => reject(new Error(`cutaway edit exited (${code}): ${seen}`)));
  });
}
