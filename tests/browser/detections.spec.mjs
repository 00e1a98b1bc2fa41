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
import fs from 'node:fs';
import path from 'node:path';
import { artifacts, root, chromiumArgs, chromiumPath, requireToolsOrSkip, startDaemon, stopDaemon, waitFor, zoomOnCar } from './harness.mjs';

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

// The track file's cones (the simulator's world; the map frame is the track's): position and colour by name.
const TRACK_CONES = fs.readFileSync(path.join(root, '../shared/tracks/epfl_track_1.csv'), 'utf8').trim().split('\n')
  .slice(1).map((l) => l.split(',')).filter((f) => f[0] !== 'car_start')
  .map(([tag, x, y]) => ({ tag, x: Number(x), y: Number(y) }));
// The dashboard's cone colours (web/channels.cpp colour_of), by name.
const PALETTE = { blue: [0.10, 0.35, 0.95], yellow: [1.0, 0.85, 0.05], orange: [1.0, 0.5, 0.0], big_orange: [1.0, 0.35, 0.0], unknown: [0.6, 0.6, 0.6] };
const colourName = (c) => Object.entries(PALETTE).find(([, v]) => Math.abs(v[0] - c.r) + Math.abs(v[1] - c.g) + Math.abs(v[2] - c.b) < 0.02)?.[0];

const quantile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(q * xs.length))];

test('detection boxes are drawn on their cones while driving, against the truth overlay', async () => {
  await waitFor(page, () => window.__fsd?.connected, null, 'the connection');
  await page.click('#truth');
  await waitFor(page, () => (window.__fsd.scene().topics['/truth/cones']?.cylinders ?? 0) > 0, null, 'the true cones');
  await waitFor(page, (v) => (window.__fsd.truth.last?.speed ?? 0) > v, MOVING, 'the car moving', 30000);
  const errors = [], along = [];
  const drawn = [];  // how each detection was drawn: solid or hollow, its colour, the nearest track cone's colour
  let looks = 0;
  const deadline = Date.now() + 40000;
  while (errors.length < SAMPLES_WANTED && Date.now() < deadline) {
    await page.waitForTimeout(250);
    for (const s of await page.evaluate(snapshot)) {
      if (s.speed < MOVING) continue;
      errors.push(Math.hypot(s.ex, s.ey));
      along.push(s.ex * Math.cos(s.yaw) + s.ey * Math.sin(s.yaw));  // + ahead of the cone in the direction of travel
    }
    for (const d of await page.evaluate(() => window.__fsd.detections('/perception/cones'))) {
      let best = null, d2 = Infinity;
      for (const c of TRACK_CONES) {
        const e = (d.x - c.x) ** 2 + (d.y - c.y) ** 2;
        if (e < d2) { d2 = e; best = c; }
      }
      drawn.push({ solid: d.solid, colour: colourName(d.color), truth: Math.sqrt(d2) < 0.5 ? best.tag : null });
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

  // Verified or not, in their colour: with the camera off nothing can be verified, so every detection is drawn
  // as an outline; each in one of the cone colours, and a named colour mostly the track file's for that cone.
  const named = drawn.filter((d) => d.truth && d.colour && d.colour !== 'unknown');
  const right = named.filter((d) => d.colour === d.truth).length;
  console.log(`# ${drawn.length} detections drawn: ${drawn.filter((d) => d.solid).length} solid; ` +
              `${named.length} with a named colour near a track cone, ${right} of them the track's colour`);
  assert.ok(drawn.length >= SAMPLES_WANTED, `only ${drawn.length} detections drawn`);
  assert.equal(drawn.filter((d) => d.solid).length, 0, 'a LiDAR-only detection drawn solid (as camera-verified)');
  assert.equal(drawn.filter((d) => !d.colour).length, 0, 'a detection drawn in a colour that is no cone colour');
  assert.ok(named.length >= 50 && right / named.length > 0.8,
            `${right} of ${named.length} detections in the track file's colour`);
});

// The localization's error against the truth beside the filter's own bound, and the true path beside the
// estimated one (the fused pose, the defaults'): the page's plot samples, bounded by what the fused pose achieves.
test('the localization error plot shows the error against the truth and the filter\'s 1-sigma bound', async () => {
  await waitFor(page, () => window.__fsd.localization.errors.length >= 30, null, 'localization error samples', 20000);
  const L = await page.evaluate(() => ({ errors: window.__fsd.localization.errors, last: window.__fsd.localization.last,
                                         plot: window.__fsd.plots.loc, scene: window.__fsd.scene().topics }));
  const e = L.errors.map((s) => s.error);
  const sigmas = L.errors.map((s) => s.sigma).filter((v) => v !== null);
  console.log(`# ${e.length} error samples: median ${quantile(e, 0.5).toFixed(3)} m, p90 ${quantile(e, 0.9).toFixed(3)} m; ` +
              `1σ median ${quantile(sigmas, 0.5)?.toFixed(3)} m; source ${L.last.source} (${L.last.quality})`);
  assert.equal(L.last.source, 'fused');
  assert.ok(e.every(Number.isFinite), 'a non-finite error');
  assert.ok(quantile(e, 0.5) < 0.25, `median position error ${quantile(e, 0.5)} m`);
  assert.ok(sigmas.length >= 30 && sigmas.every((v) => v > 0 && v < 1), 'the fused covariance gives a 1σ bound in (0, 1) m');
  assert.ok(L.plot.samples >= 30, 'the bound plotted');
  // Both paths drawn: the estimated trail (lap 1) and the true one.
  assert.ok((L.scene['/planning/paths']?.lines ?? 0) > 0, 'no estimated path');
  assert.ok((L.scene['/truth/path']?.lines ?? 0) > 0, 'no true path');
  await page.screenshot({ path: path.join(artifacts, 'dashboard-localization.png') });
});
