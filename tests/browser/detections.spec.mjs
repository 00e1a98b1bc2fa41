// Browser test: the detection boxes are drawn on their cones while the car drives (issue #18). `fsd run --sim`
// in real time on the car's own LiDAR perception (run.perception_source = lidar; the camera model off to hold
// real time on a 2-core machine next to Chromium). A detection set is some 0.1 s old when it reaches the
// telemetry; drawn with the pose of that instant it sits on its cone, drawn with the pose of now it sits
// v · age ahead of it (0.5–1 m at racing speed). The page's boxes are checked against the truth overlay's cones
// (the simulator's, an independent truth) as the page draws both. A screenshot goes to test-artifacts/.
//
//   node tests/browser/detections.spec.mjs     (from the project root; FSD_BINARY names the fsd binary)
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { artifacts, chromiumArgs, chromiumPath, requireToolsOrSkip, startDaemon, stopDaemon, waitFor, zoomOnCar } from './harness.mjs';

const { chromium } = requireToolsOrSkip();
const MOVING = 3.0;          // m/s: samples below this say nothing about where a late box is drawn
const SAMPLES_WANTED = 150;  // boxes compared while moving

let daemon, browser, page;

before(async () => {
  daemon = await startDaemon({
    web: { bind: '127.0.0.1' },
    run: { perception_source: 'lidar' },
    sim: { enable_camera: false },
    control: { planner: { time_budget: 0.5 } },
  });
  browser = await chromium.launch({ executablePath: chromiumPath, args: chromiumArgs });
  page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  page.on('pageerror', (e) => console.log('page error:', e.message));
  await page.goto(`http://127.0.0.1:${daemon.port}/`);
});

after(async () => {
  await browser?.close();
  if (daemon) await stopDaemon(daemon);
});

// One look at the page: every detection box, the nearest true cone to it, and the true car's heading and speed.
function snapshot() {
  const f = window.__fsd;
  const truth = f.truth.last;
  const cones = f.positions('/truth/cones');
  return f.positions('/perception/cones').map((b) => {
    let best = null, d2 = Infinity;
    for (const c of cones) {
      const e = (b.x - c.x) ** 2 + (b.y - c.y) ** 2;
      if (e < d2) { d2 = e; best = c; }
    }
    return best && { ex: b.x - best.x, ey: b.y - best.y, yaw: truth.yaw, speed: truth.speed };
  }).filter(Boolean);
}

const quantile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(q * xs.length))];

test('detection boxes are drawn on their cones while driving, against the truth overlay', async () => {
  await waitFor(page, () => window.__fsd?.connected, null, 'the connection');
  await page.click('#truth');
  await waitFor(page, () => (window.__fsd.scene().topics['/truth/cones']?.cylinders ?? 0) > 0, null, 'the true cones');
  await waitFor(page, (v) => (window.__fsd.truth.last?.speed ?? 0) > v, MOVING, 'the car moving', 30000);
  const errors = [], along = [];
  let looks = 0;
  const deadline = Date.now() + 40000;
  while (errors.length < SAMPLES_WANTED && Date.now() < deadline) {
    await page.waitForTimeout(250);
    for (const s of await page.evaluate(snapshot)) {
      if (s.speed < MOVING) continue;
      errors.push(Math.hypot(s.ex, s.ey));
      along.push(s.ex * Math.cos(s.yaw) + s.ey * Math.sin(s.yaw));  // + ahead of the cone in the direction of travel
    }
    looks++;
  }
  // Zoomed in on the car: boxes (translucent cubes) inside the truth overlay's wireframe cones.
  await zoomOnCar(page);
  await page.screenshot({ path: path.join(artifacts, 'dashboard-detections.png') });

  const median = quantile(errors, 0.5), p90 = quantile(errors, 0.9);
  const medianAlong = quantile(along, 0.5);
  console.log(`# ${errors.length} boxes in ${looks} looks while moving: distance to the true cone median ` +
              `${median?.toFixed(3)} m, p90 ${p90?.toFixed(3)} m; along the travel median ${medianAlong?.toFixed(3)} m`);
  assert.ok(errors.length >= SAMPLES_WANTED, `only ${errors.length} boxes seen while moving`);
  // LiDAR cone positions are within ~0.1 m; a box drawn with the newest pose would be 0.3 m or more ahead.
  assert.ok(median < 0.2, `boxes ${median.toFixed(3)} m from their cones (median)`);
  assert.ok(p90 < 0.35, `boxes ${p90.toFixed(3)} m from their cones (p90)`);
  assert.ok(Math.abs(medianAlong) < 0.12, `boxes ${medianAlong.toFixed(3)} m ahead of their cones (median, along the travel)`);
});
