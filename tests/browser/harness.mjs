// What the browser tests share: where Chromium, playwright-core, the built dashboard and fsd are (exit 77,
// CTest's "skipped", when one is missing), starting `fsd run --sim` on a free port with a configuration, and
// waiting on the page.
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const chromiumPath = process.env.FSD_CHROMIUM ?? '/usr/bin/chromium';
export const artifacts = path.join(root, 'test-artifacts');
const dashboard = path.join(root, 'web/dashboard');
const fsdBinary = process.env.FSD_BINARY ?? path.join(root, 'build/daemon/fsd');

// require() from the dashboard's node_modules (playwright-core, @foxglove/ws-protocol).
export const requireDev = createRequire(path.join(dashboard, 'package.json'));

export function requireToolsOrSkip() {
  for (const [what, file] of [['chromium', chromiumPath], ['playwright-core', path.join(dashboard, 'node_modules/playwright-core')],
                              ['the built dashboard', path.join(dashboard, 'dist/index.html')], ['fsd', fsdBinary]]) {
    if (!fs.existsSync(file)) {
      console.log(`skipped: ${what} not found (${file}); deploy/install-deps.sh and the build provide it`);
      process.exit(77);
    }
  }
  fs.mkdirSync(artifacts, { recursive: true });
  return requireDev('playwright-core');
}

export const chromiumArgs = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
                             '--disable-component-update', '--disable-sync', '--no-first-run'];

// Starts `fsd run --sim` with `config` (an object, written to a temporary file) on `port` (0: any free one);
// resolves with { proc, port, out, log } once it prints the dashboard's address.
export function startDaemon(config, { env = {}, port = 0 } = {}) {
  const configFile = path.join(os.tmpdir(), `fsd-browser-${process.pid}-${Date.now()}.json`);
  fs.writeFileSync(configFile, JSON.stringify(config));
  return new Promise((resolve, reject) => {
    const proc = spawn(fsdBinary, ['run', '--sim', '--port', String(port), '--config', configFile],
                       { cwd: root, env: { ...process.env, ...env }, stdio: ['ignore', 'pipe', 'pipe'] });
    const d = { proc, port: 0, out: '', log: '', configFile };
    const timer = setTimeout(() => reject(new Error(`fsd did not start: ${d.out}\n${d.log}`)), 20000);
    proc.stdout.on('data', (chunk) => {
      d.out += chunk;
      const m = /dashboard at http:\/\/[\w.]+:(\d+)\//.exec(d.out);
      if (m && !d.port) {
        clearTimeout(timer);
        d.port = Number(m[1]);
        resolve(d);
      }
    });
    proc.stderr.on('data', (chunk) => { d.log += chunk; });
    proc.on('exit', (code) => reject(new Error(`fsd exited with ${code}: ${d.out}\n${d.log}`)));
  });
}

export function stopDaemon(d) {
  return new Promise((resolve) => {
    fs.rmSync(d.configFile, { force: true });
    if (d.proc.exitCode !== null) return resolve();
    d.proc.on('exit', resolve);
    d.proc.kill('SIGTERM');
  });
}

export async function waitFor(page, fn, arg, what, timeout = 15000) {
  try {
    await page.waitForFunction(fn, arg, { timeout, polling: 100 });
  } catch (e) {
    throw new Error(`timed out waiting for ${what}`);
  }
}

// A closer look from above: zooms the 3D view in on the car (the view follows it), for a screenshot.
export async function zoomOnCar(page) {
  const box = await page.locator('#view3d canvas').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  for (let i = 0; i < 6; i++) await page.mouse.wheel(0, -250);
  await page.waitForTimeout(400);
}
