// The defaults in real time with the dashboard open (docs/benchmarks.md): `fsd run --sim` drives epfl_track_1's
// two laps on the defaults (every sensor, the perception and localization stages) while headless Chromium shows the
// dashboard the whole run. Prints the run's end-to-end latency (its scorecard's latency_ms, over the whole run)
// and the control loop's period, scraped from /metrics every 5 s (quantiles over the latest 1024 cycles each).
//
//   node bench/realtime_dashboard.mjs [report.json]     (from the project root; FSD_BINARY names the fsd binary)
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { chromiumArgs, chromiumPath, requireToolsOrSkip, root } from '../tests/browser/harness.mjs';

const { chromium } = requireToolsOrSkip();
const report = path.resolve(process.argv[2] ?? 'realtime.json');
const fsd = process.env.FSD_BINARY ?? path.join(root, 'build/daemon/fsd');
const proc = spawn(fsd, ['run', '--sim', '--port', '0', '--until-finished', '--laps', '2', '--report', report],
                   { cwd: root, stdio: ['ignore', 'pipe', 'pipe'] });
let out = '';
const port = await new Promise((resolve, reject) => {
  proc.stdout.on('data', (c) => {
    out += c;
    const m = /dashboard at http:\/\/[\w.]+:(\d+)\//.exec(out);
    if (m) resolve(Number(m[1]));
  });
  proc.stderr.on('data', () => {});
  proc.on('exit', (code) => reject(new Error(`fsd exited with ${code}: ${out}`)));
});
const exited = new Promise((resolve) => proc.on('exit', resolve));

const browser = await chromium.launch({ executablePath: chromiumPath, args: chromiumArgs });
const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
await page.goto(`http://127.0.0.1:${port}/`);

const quantile = (text, q) => {
  const m = new RegExp(`^fsd_control_period_seconds\\{quantile="${q}"\\} (\\S+)`, 'm').exec(text);
  return m ? Number(m[1]) * 1e3 : NaN;
};
const scrapes = [];
let done = false;
exited.then(() => { done = true; });
while (!done) {
  await new Promise((r) => setTimeout(r, 5000));
  try {
    const text = await (await fetch(`http://127.0.0.1:${port}/metrics`)).text();
    scrapes.push({ p50: quantile(text, '0.5'), p90: quantile(text, '0.9'), p99: quantile(text, '0.99') });
  } catch { /* the run ended */ }
}
await browser.close();

const card = JSON.parse(fs.readFileSync(report, 'utf8'));
const fmt = (x) => x.toFixed(1);
console.log(`verdict ${card.verdict.result ?? JSON.stringify(card.verdict)}, laps ${card.laps.map((l) => l.time_s).join(' / ')} s, ` +
            `cones hit ${card.cones_hit}`);
for (const [stage, s] of Object.entries(card.latency_ms)) console.log(`${stage}: p50 ${s.p50} ms, p99 ${s.p99} ms, max ${s.max} ms`);
const p99s = scrapes.map((s) => s.p99).filter(Number.isFinite).sort((a, b) => a - b);
console.log(`control period, ${scrapes.length} scrapes: p50 ${scrapes.map((s) => fmt(s.p50)).join(' ')}`);
console.log(`  p99 ${scrapes.map((s) => fmt(s.p99)).join(' ')} (median ${fmt(p99s[p99s.length >> 1])}, worst ${fmt(p99s.at(-1))})`);
