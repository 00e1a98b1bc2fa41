// Browser test of the pit-lane dashboard: headless Chromium (Debian's) driven by playwright-core against
// fsd-web-demo (the web server with synthetic telemetry on epfl_track_1) until `fsd run --sim` serves it.
// Checks that the 3D view renders the cones, the plots move, a parameter change with the token takes effect
// and one without is refused, the page reconnects by itself and makes no request elsewhere; and that Foxglove's
// own client library (@foxglove/ws-protocol, what Foxglove Studio uses) understands the server. Screenshots go
// to test-artifacts/. Exits 77 (CTest: skipped) when Chromium or the dashboard's node_modules are missing.
//
//   node tests/browser/dashboard.spec.mjs     (from the project root; FSD_WEB_DEMO names the demo binary)
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const chromiumPath = process.env.FSD_CHROMIUM ?? '/usr/bin/chromium';
const dashboard = path.join(root, 'web/dashboard');
const demoBinary = process.env.FSD_WEB_DEMO ?? path.join(root, 'build/web/fsd-web-demo');
const artifacts = path.join(root, 'test-artifacts');
const TOKEN = 'pit-lane-test-token';

for (const [what, file] of [['chromium', chromiumPath], ['playwright-core', path.join(dashboard, 'node_modules/playwright-core')],
                            ['the built dashboard', path.join(dashboard, 'dist/index.html')], ['fsd-web-demo', demoBinary]]) {
  if (!fs.existsSync(file)) {
    console.log(`skipped: ${what} not found (${file}); deploy/install-deps.sh and the build provide it`);
    process.exit(77);
  }
}
const requireDev = createRequire(path.join(dashboard, 'package.json'));
const { chromium } = requireDev('playwright-core');

// Starts the demo server; resolves with { proc, port } once it prints its address.
function startDemo(port = 0) {
  return new Promise((resolve, reject) => {
    const proc = spawn(demoBinary, ['--port', String(port), '--token', TOKEN, '--duration', '300'],
                       { cwd: root, env: { ...process.env, FSD_WEB_TOKEN: TOKEN }, stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    const timer = setTimeout(() => reject(new Error(`demo did not start: ${out}`)), 15000);
    proc.stdout.on('data', (d) => {
      out += d;
      const m = /listening on http:\/\/[\d.]+:(\d+)\//.exec(out);
      if (m) {
        clearTimeout(timer);
        resolve({ proc, port: Number(m[1]) });
      }
    });
    proc.stderr.on('data', () => {});
    proc.on('exit', (code) => reject(new Error(`demo exited with ${code}: ${out}`)));
  });
}

function stopDemo(demo) {
  return new Promise((resolve) => {
    if (demo.proc.exitCode !== null) return resolve();
    demo.proc.on('exit', resolve);
    demo.proc.kill('SIGTERM');
  });
}

async function waitFor(page, fn, arg, what, timeout = 15000) {
  try {
    await page.waitForFunction(fn, arg, { timeout, polling: 100 });
  } catch (e) {
    throw new Error(`timed out waiting for ${what}`);
  }
}

let demo, browser, page;
const requests = [];

before(async () => {
  fs.mkdirSync(artifacts, { recursive: true });
  demo = await startDemo();
  browser = await chromium.launch({
    executablePath: chromiumPath,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
           '--disable-sync', '--no-first-run'],
  });
  page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('request', (r) => requests.push(r.url()));
  page.on('pageerror', (e) => console.log('page error:', e.message));
  await page.goto(`http://127.0.0.1:${demo.port}/`);
});

after(async () => {
  await browser?.close();
  if (demo) await stopDemo(demo);
});

// Pixels of the 3D canvas in the cone colours (the renderer keeps its drawing buffer for this).
function conePixels() {
  const gl = document.querySelector('#view3d canvas');
  const c = document.createElement('canvas');
  c.width = gl.width;
  c.height = gl.height;
  const g = c.getContext('2d');
  g.drawImage(gl, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let blue = 0, yellow = 0;
  for (let i = 0; i < d.length; i += 4) {
    const [r, gr, b] = [d[i], d[i + 1], d[i + 2]];
    if (b > 140 && r < 90 && b > gr + 40) blue++;
    if (r > 170 && gr > 140 && b < 90) yellow++;
  }
  return { blue, yellow };
}

test('the 3D view renders the cone map, the car and the point cloud', async () => {
  await waitFor(page, () => window.__fsd?.connected, null, 'the WebSocket connection');
  await waitFor(page, () => (window.__fsd.scene().topics['/map/cones']?.cylinders ?? 0) >= 30, null, '30 cones on the map');
  const counts = await page.evaluate(() => window.__fsd.scene());
  assert.equal(counts.topics['/vehicle/car'].cubes, 1);
  assert.ok(counts.points > 500, `point cloud has ${counts.points} points`);
  assert.ok(counts.topics['/planning/paths'].lines >= 1);
  await page.screenshot({ path: path.join(artifacts, 'dashboard-wide.png') });
  const px = await page.evaluate(conePixels);
  assert.ok(px.blue > 20 && px.yellow > 20, `cone-coloured pixels: ${JSON.stringify(px)}`);
  await page.click('#topdown');
  await page.waitForTimeout(300);
  await page.screenshot({ path: path.join(artifacts, 'dashboard-topdown.png') });
});

test('the plots move with the vehicle state', async () => {
  await waitFor(page, () => (window.__fsd.plots.speed?.samples ?? 0) > 10, null, 'speed samples');
  const a = await page.evaluate(() => ({ ...window.__fsd.plots.speed }));
  await page.waitForTimeout(1000);
  const b = await page.evaluate(() => ({ ...window.__fsd.plots.speed }));
  assert.ok(b.samples > a.samples + 20, `speed samples ${a.samples} → ${b.samples}`);
  assert.ok(b.t > a.t + 0.5, `plot time ${a.t} → ${b.t}`);
  for (const k of ['yaw', 'ay', 'beta']) assert.ok((await page.evaluate((k) => window.__fsd.plots[k].samples, k)) > 10, k);
  assert.match(await page.textContent('#as-state'), /DRIVING|READY|OFF/);
});

async function apiValue(key) {
  const res = await fetch(`http://127.0.0.1:${demo.port}/api/params`);
  return (await res.json()).params.find((p) => p.key === key).value;
}

async function setSpeed(value, token) {
  await page.fill('#token', token);
  await page.fill('input[data-key="demo.target_speed"]', String(value));
  await page.click('#apply');
}

test('a parameter change without the token is refused and changes nothing', async () => {
  await waitFor(page, () => document.querySelector('input[data-key="demo.target_speed"]'), null, 'the parameter panel');
  await setSpeed(9, '');
  await waitFor(page, () => /Refused/.test(document.querySelector('#params-feedback').textContent), null, 'the refusal');
  assert.match(await page.textContent('#params-feedback'), /token/);
  assert.equal(await page.getAttribute('#params-feedback', 'class'), 'feedback error');
  assert.equal(await page.inputValue('input[data-key="demo.target_speed"]'), '6');  // reverted to the server's value
  assert.equal(await apiValue('demo.target_speed'), 6);
  await page.screenshot({ path: path.join(artifacts, 'dashboard-param-refused.png') });
  await setSpeed(9, 'wrong-token');
  await waitFor(page, () => /Refused/.test(document.querySelector('#params-feedback').textContent), null, 'the second refusal');
  assert.equal(await apiValue('demo.target_speed'), 6);
});

test('a parameter change with the token takes effect on the car', async () => {
  await setSpeed(9, TOKEN);
  await waitFor(page, () => /Applied/.test(document.querySelector('#params-feedback').textContent), null, 'the confirmation');
  assert.equal(await apiValue('demo.target_speed'), 9);
  // The car's target speed follows (km/h in the plot).
  await waitFor(page, () => Math.abs(window.__fsd.plots.speed.values[1] - 9 * 3.6) < 1e-6, null, 'target speed 32.4 km/h');
  await waitFor(page, () => window.__fsd.plots.speed.values[0] > 8.5 * 3.6, null, 'the car speeding up', 8000);
  const history = await (await fetch(`http://127.0.0.1:${demo.port}/api/params/history`)).json();
  assert.equal(history.at(-1).new, 9);
  assert.match(history.at(-1).who, /^web 127\.0\.0\.1:\d+ \(token ok\)$/);
  await page.screenshot({ path: path.join(artifacts, 'dashboard-param-applied.png') });
});

test("Foxglove's client library (as in Foxglove Studio) subscribes, decodes and sets parameters", async () => {
  const { FoxgloveClient } = requireDev('@foxglove/ws-protocol');
  const WebSocket = requireDev('ws');
  const client = new FoxgloveClient({
    ws: new WebSocket(`ws://127.0.0.1:${demo.port}/?token=${TOKEN}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]),
  });
  const seen = { info: null, channels: new Map(), states: [], time: null, params: new Map(), errors: [] };
  const done = new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`incomplete: ${JSON.stringify({ info: !!seen.info, channels: seen.channels.size, states: seen.states.length, time: seen.time !== null, params: [...seen.params.keys()] })}`)), 15000);
    const check = () => {
      if (seen.info && seen.states.length >= 5 && seen.time !== null && seen.params.has('set')) {
        clearTimeout(timer);
        resolve();
      }
    };
    client.on('serverInfo', (info) => { seen.info = info; check(); });
    client.on('error', (e) => seen.errors.push(String(e)));
    client.on('advertise', (channels) => {
      for (const ch of channels) seen.channels.set(ch.id, ch);
      const state = channels.find((c) => c.topic === '/vehicle/state');
      if (state) {
        seen.stateSub = client.subscribe(state.id);
        client.getParameters(['demo.lookahead'], 'get');
        client.setParameters([{ name: 'demo.lookahead', value: 30 }], 'set');
      }
    });
    client.on('message', (m) => {
      if (m.subscriptionId !== seen.stateSub) return;
      seen.states.push({ t: m.timestamp, body: JSON.parse(new TextDecoder().decode(m.data)) });
      check();
    });
    client.on('time', (t) => { seen.time = t.timestamp; check(); });
    client.on('parameterValues', (p) => { seen.params.set(p.id, p.parameters); check(); });
  });
  try {
    await done;
  } finally {
    client.close();
  }
  assert.deepEqual(seen.errors, []);
  assert.ok(seen.info.capabilities.includes('parameters') && seen.info.capabilities.includes('parametersSubscribe'));
  const byTopic = new Map([...seen.channels.values()].map((c) => [c.topic, c]));
  assert.equal(byTopic.get('/map/cones').schemaName, 'foxglove.SceneUpdate');
  assert.equal(byTopic.get('/lidar/points').schemaName, 'foxglove.PointCloud');
  assert.equal(byTopic.get('/log').schemaName, 'foxglove.Log');
  for (const ch of seen.channels.values()) {
    assert.equal(ch.encoding, 'json');
    assert.equal(JSON.parse(ch.schema).title, ch.schemaName);
  }
  const last = seen.states.at(-1);
  assert.equal(typeof last.t, 'bigint');
  assert.equal(last.t, BigInt(last.body.timestamp.sec) * 1000000000n + BigInt(last.body.timestamp.nsec));
  assert.ok(Number.isFinite(last.body.speed) && Number.isFinite(last.body.yaw_rate));
  assert.equal(seen.params.get('get')[0].name, 'demo.lookahead');
  assert.deepEqual(seen.params.get('set'), [{ name: 'demo.lookahead', value: 30, type: 'float64' }]);
  assert.equal(await apiValue('demo.lookahead'), 30);
});

test('usable on a tablet in portrait', async () => {
  const tablet = await browser.newPage({ viewport: { width: 820, height: 1180 }, isMobile: true, hasTouch: true, deviceScaleFactor: 2 });
  await tablet.goto(`http://127.0.0.1:${demo.port}/`);
  await waitFor(tablet, () => (window.__fsd?.scene().topics['/map/cones']?.cylinders ?? 0) > 10, null, 'cones on the tablet');
  await waitFor(tablet, () => (window.__fsd.plots.speed?.samples ?? 0) > 50, null, 'plots on the tablet');
  const layout = await tablet.evaluate(() => {
    const r = (s) => document.querySelector(s).getBoundingClientRect();
    return { banner: r('#banner'), view: r('.view3d'), plots: r('.plots'), width: document.documentElement.scrollWidth };
  });
  assert.ok(layout.width <= 820, `no horizontal scrolling (${layout.width}px)`);
  assert.ok(layout.view.width > 780 && layout.plots.top >= layout.view.bottom - 1, 'one column: 3D view above the plots');
  assert.ok(layout.banner.height >= 90, 'banner readable from the pit wall');
  await tablet.screenshot({ path: path.join(artifacts, 'dashboard-tablet.png'), fullPage: true });
  await tablet.close();
});

test('the page reconnects by itself when the server comes back', async () => {
  const port = demo.port;
  await stopDemo(demo);
  await waitFor(page, () => !window.__fsd.connected, null, 'the disconnect');
  assert.match(await page.textContent('#link-text'), /reconnecting|connecting/);
  assert.equal(await page.textContent('#as-state'), 'NO LINK');
  demo = await startDemo(port);
  await waitFor(page, () => window.__fsd.connected, null, 'the reconnect', 20000);
  await waitFor(page, () => (window.__fsd.scene().topics['/map/cones']?.cylinders ?? 0) > 0, null, 'cones after the reconnect');
});

test('the page makes no request to any other host', () => {
  const hosts = new Set(requests.map((u) => new URL(u).host));
  assert.deepEqual([...hosts], [`127.0.0.1:${demo.port}`]);
});
