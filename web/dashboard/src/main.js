// The pit-lane dashboard: one Foxglove WebSocket connection to the daemon (same host and port as this page),
// a 3D view, live plots, the AS state banner, laps, faults, log, camera and the parameter panel.
import './style.css';
import { FoxgloveClient, seconds, fromBase64 } from './foxglove.js';
import { createView3D } from './view3d.js';
import { showFaultsInBanner } from './banner_faults.js';
import { TimePlot } from './plots.js';
import { ParamPanel } from './params.js';

const $ = (id) => document.getElementById(id);
const RAD2DEG = 180 / Math.PI;

// The page subscribes to what the daemon advertises (its channel table, daemon/telemetry/telemetry_channels.cpp) and shows
// each message by its schema, so a new channel of a known schema needs no change here. The simulator's ground
// truth (/truth/*, sim runs only) is subscribed while the truth overlay is on.
const isTruth = (topic) => topic.startsWith('/truth/');

// ?ws=ws://car:8080/ connects elsewhere (development with `npm run dev`); by default the page's own server.
const wsUrl = new URLSearchParams(location.search).get('ws') ??
  `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/`;

const { scene, sceneArrived } = createView3D($('view3d'), $('view3d-message'));
const plots = {
  speed: new TimePlot($('plot-speed'), {
    title: 'Speed', unit: 'km/h', minRange: 5,
    series: [{ label: 'v', color: '#4fc3f7' }, { label: 'target', color: '#ffb74d', dash: [6, 4] }, truthSeries('true v')],
  }),
  yaw: new TimePlot($('plot-yaw'), { title: 'Yaw rate', unit: '°/s', minRange: 5, series: [{ label: 'r', color: '#81c784' }, truthSeries('true r')] }),
  ay: new TimePlot($('plot-ay'), { title: 'Lateral acceleration', unit: 'm/s²', minRange: 1, series: [{ label: 'ay', color: '#e57373' }, truthSeries('true ay')] }),
  beta: new TimePlot($('plot-beta'), { title: 'Sideslip', unit: '°', minRange: 1, series: [{ label: 'β', color: '#ba68c8' }, truthSeries('true β')] }),
  // The filter's position bound from its covariance (also on the car) and, in sim runs with the truth overlay, the
  // true position error against it: an error above 3σ means the filter is overconfident.
  loc: new TimePlot($('plot-loc'), {
    title: 'Position error, filter σ', unit: 'm', minRange: 0.05, zeroBased: true,
    series: [{ label: '1σ', color: '#4fc3f7' }, { label: '3σ', color: '#4fc3f7', dash: [6, 4] },
             { label: 'error', color: '#ff8a65', hidden: true }],
  }),
};
function truthSeries(label) {
  return { label, color: '#f5f5f5', dash: [2, 3], hidden: true };
}

const hook = (window.__fsd = { webgl: scene.webgl, connected: false, topics: {}, status: [], scene: () => scene.counts(), positions: (topic) => scene.positions(topic), detections: (topic) => scene.detections?.(topic) ?? [], plots: {}, truth: { on: false, samples: 0 }, localization: { samples: 0, errors: [] }, loopClosures: [] });

function onVehicleState(m) {
  const t = seconds(m.timestamp);
  plots.speed.push(t, m.speed * 3.6, m.target_speed * 3.6);
  plots.yaw.push(t, m.yaw_rate * RAD2DEG);
  plots.ay.push(t, m.lateral_acceleration);
  plots.beta.push(t, m.sideslip * RAD2DEG);
  for (const [k, p] of Object.entries(plots)) hook.plots[k] = { samples: p.count, t: p.last?.t, values: p.last?.values };
  scene.setCar(m.x, m.y);
}

// The truth curves go last in each plot (white, dotted), beside the stack's estimate.
function onTruthState(m) {
  const t = seconds(m.timestamp);
  const last = (p) => p.series.length - 1;
  plots.speed.pushSeries(last(plots.speed), t, m.speed * 3.6);
  plots.yaw.pushSeries(last(plots.yaw), t, m.yaw_rate * RAD2DEG);
  plots.ay.pushSeries(last(plots.ay), t, m.lateral_acceleration);
  plots.beta.pushSeries(last(plots.beta), t, m.sideslip * RAD2DEG);
  hook.truth.samples++;
  hook.truth.last = m;
}

// The localization's view of itself: source, quality, and the 1σ / 3σ position bound from the covariance.
function onLocalization(m) {
  const t = seconds(m.timestamp);
  const sigma = m.position_sigma;
  $('loc-source').textContent = `${m.source}${m.quality ? ` · ${m.quality}` : ''}`;
  $('loc-sigma').textContent = Number.isFinite(sigma) ? `${(sigma * 100).toFixed(1)} / ${(3 * sigma * 100).toFixed(1)} cm` : 'no covariance';
  if (Number.isFinite(sigma)) plots.loc.push(t, sigma, 3 * sigma);
  const L = hook.localization;
  L.samples++;
  L.last = m;
}

// Sim runs with the truth overlay: the true position error, beside the filter's bound.
function onLocalizationError(m) {
  const t = seconds(m.timestamp);
  plots.loc.pushSeries(plots.loc.series.length - 1, t, m.position_error);
  $('loc-error-row').hidden = false;
  $('loc-error').textContent = `${(m.position_error * 100).toFixed(1)} cm, ${(m.yaw_error * RAD2DEG).toFixed(2)}°`;
  const L = hook.localization;
  L.errors.push({ t, error: m.position_error, sigma: L.last?.position_sigma ?? null });
  if (L.errors.length > 2000) L.errors.shift();
}

// Loop closures: a line each in the panel, a marker in the error plot, a toast for one that happens while watching.
let loopsSeen = null;
function onLoopClosures(m) {
  const list = m.loop_closures ?? [];
  $('loop-count').textContent = list.length;
  $('loop-closures').replaceChildren(...[...list].reverse().map((c) => {
    const li = document.createElement('li');
    li.textContent = loopText(c);
    return li;
  }));
  for (const c of list) plots.loc.mark(c.t, `loop ${c.lap}`);
  if (loopsSeen !== null && list.length > loopsSeen) showToast(`Loop closed · ${loopText(list[list.length - 1])}`);
  loopsSeen = list.length;
  hook.loopClosures = list;
}
const loopText = (c) => `${c.t.toFixed(1)} s  loop ${c.lap}: moved ${(c.shift * 100).toFixed(0)} cm, ` +
  `${(c.dyaw * RAD2DEG).toFixed(2)}° on ${c.pairs} cones (rms ${(c.rms * 100).toFixed(0)} cm)`;

let toastTimer = null;
function showToast(text) {
  const el = $('toast');
  el.textContent = text;
  el.hidden = false;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => (el.hidden = true), 10000);
}

const AS_CLASS = { Off: 'as-off', Ready: 'as-ready', Driving: 'as-driving', Emergency: 'as-emergency', Finished: 'as-finished' };
const fmtTime = (s) => (Number.isFinite(s) ? `${Math.floor(s / 60)}:${(s % 60).toFixed(2).padStart(5, '0')}` : '–');

function onAsStatus(m) {
  const banner = $('banner');
  banner.className = `banner ${AS_CLASS[m.as_state] ?? 'as-off'}`;
  $('as-state').textContent = m.as_state.toUpperCase();
  $('mission').textContent = m.mission;
  // m.lap is the lap being driven (after the finish the last one); the clock is frozen once the car stopped.
  $('lap').textContent = m.laps_total > 0 ? `lap ${m.lap}/${m.laps_total}` : `lap ${m.lap}`;
  $('lap-time').textContent = fmtTime(m.lap_time);
  $('control-mode').textContent = m.control_mode || '–';
  $('res-ebs').textContent = `${m.res_emergency ? 'RES EMERGENCY' : m.res_go ? 'GO' : '–'} / ${m.ebs_active ? 'EBS ACTIVE' : 'released'}`;
  const list = $('lap-times');
  list.replaceChildren(...m.lap_times.map((t, i) => {
    const li = document.createElement('li');
    li.textContent = `lap ${i + 1}: ${fmtTime(t)}`;
    return li;
  }));
  hook.as = m;
}

function onFaults(m) {
  const list = $('faults');
  const items = [...m.faults].reverse().map((f) => {
    const li = document.createElement('li');
    li.className = f.active ? 'active' : '';
    li.textContent = `${f.t.toFixed(1)} s  ${f.source}: ${f.what}${f.action ? ` → ${f.action}` : ''}`;
    return li;
  });
  if (!items.length) {
    const li = document.createElement('li');
    li.className = 'none';
    li.textContent = 'none';
    items.push(li);
  }
  list.replaceChildren(...items);
  $('fault-count').textContent = m.faults.filter((f) => f.active).length;
  showFaultsInBanner($('banner-faults'), m.faults);
  hook.faults = m.faults;
}

const LOG_LEVEL = ['?', 'debug', 'info', 'warn', 'error', 'fatal'];
function addLog(level, name, text) {
  const list = $('log');
  const li = document.createElement('li');
  li.className = `l${level}`;
  li.textContent = `${LOG_LEVEL[level] ?? '?'} [${name}] ${text}`;
  list.prepend(li);
  while (list.children.length > 60) list.lastChild.remove();
}

let imageUrl = null;
function onImage(m) {
  $('camera-panel').hidden = false;
  const blob = new Blob([fromBase64(m.data)], { type: `image/${m.format === 'jpg' ? 'jpeg' : m.format}` });
  if (imageUrl) URL.revokeObjectURL(imageUrl);
  imageUrl = URL.createObjectURL(blob);
  $('camera').src = imageUrl;
}

function onImageBoxes(m) {
  const img = $('camera'), c = $('camera-overlay');
  if (!img.naturalWidth) return;
  c.width = img.naturalWidth;
  c.height = img.naturalHeight;
  const g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  const css = (k) => `rgba(${k.r * 255},${k.g * 255},${k.b * 255},${k.a})`;
  for (const p of m.points ?? []) {
    g.strokeStyle = css(p.outline_color);
    g.lineWidth = p.thickness || 2;
    g.beginPath();
    p.points.forEach((q, i) => (i ? g.lineTo(q.x, q.y) : g.moveTo(q.x, q.y)));
    g.closePath();
    g.stroke();
  }
  g.font = '14px system-ui, sans-serif';
  for (const t of m.texts ?? []) {
    g.fillStyle = css(t.text_color);
    g.fillText(t.text, t.position.x, t.position.y);
  }
}

function sceneUpdate(topic, m) {
  sceneArrived();
  scene.applySceneUpdate(topic, m);
}

// By schema name: how a message is shown.
const bySchema = {
  'foxglove.SceneUpdate': (m, topic) => (isTruth(topic) ? scene.applySceneUpdate(topic, m) : sceneUpdate(topic, m)),
  'foxglove.PointCloud': (m) => {
    sceneArrived();
    scene.applyPointCloud(m);
  },
  'foxglove.CompressedImage': onImage,
  'foxglove.ImageAnnotations': onImageBoxes,
  'foxglove.Log': (m) => addLog(m.level, m.name, m.message),
  'fsd.VehicleState': onVehicleState,
  'fsd.TruthVehicleState': onTruthState,
  'fsd.AsStatus': onAsStatus,
  'fsd.Faults': onFaults,
  'fsd.Localization': onLocalization,
  'fsd.LocalizationError': onLocalizationError,
  'fsd.LoopClosures': onLoopClosures,
};

function setLink(state, detail) {
  const link = $('link');
  link.className = `link ${state}`;
  $('link-text').textContent =
    state === 'connected' ? 'connected' : state === 'reconnecting' ? `reconnecting in ${(detail.delay / 1000).toFixed(1)} s` : 'connecting…';
  hook.connected = state === 'connected';
  if (state !== 'connected') {
    $('banner').className = 'banner as-off';
    $('as-state').textContent = 'NO LINK';
  }
}

let panel;
const wants = (ch) => bySchema[ch.schemaName] !== undefined && (!isTruth(ch.topic) || hook.truth.on);
const client = new FoxgloveClient(wsUrl, wants, {
  onState: setLink,
  onServerInfo: () => panel.load(),
  onAdvertise: (channels) => {
    // Only sim runs have a ground truth to overlay.
    const available = [...channels.values()].some((ch) => isTruth(ch.topic));
    $('truth').disabled = !available;
    $('truth').title = available ? "the simulator's ground truth over what the stack sees" : 'no ground truth: not a simulated run';
  },
  onStatus: (msg) => {
    hook.status.push(msg);
    panel.onStatus(msg);
    if (msg.level >= 1) addLog(msg.level === 2 ? 4 : 3, 'server', msg.message);
  },
  onParameterValues: (params, id) => panel.onValues(params, id),
  onMessage: (topic, tNs, payload, channel) => {
    hook.topics[topic] = (hook.topics[topic] ?? 0) + 1;
    try {
      bySchema[channel.schemaName]?.(payload, topic);
    } catch (e) {
      console.error(topic, e);
    }
  },
});
// ~60 rows would push the faults and the log thousands of pixels down on a phone or a tablet in portrait.
$('params-panel').open = !matchMedia('(max-width: 1000px)').matches;
panel = new ParamPanel({ table: $('params'), tokenInput: $('token'), applyButton: $('apply'), feedback: $('params-feedback'), client });
hook.params = panel;
client.connect();

// Message rate in the connection indicator.
let lastCount = 0;
setInterval(() => {
  if (!hook.connected) return;
  const n = client.stats.messages;
  $('link-text').textContent = `connected · ${n - lastCount} msg/s`;
  lastCount = n;
}, 1000);

$('follow').addEventListener('click', (e) => {
  scene.follow = !scene.follow;
  e.currentTarget.classList.toggle('on', scene.follow);
});
$('topdown').addEventListener('click', () => scene.topDown());

// Truth overlay: off by default, remembered in this browser.
function setTruthOverlay(on) {
  hook.truth.on = on;
  localStorage.setItem('fsd-truth-overlay', on ? '1' : '0');
  $('truth').classList.toggle('on', on);
  $('truth').setAttribute('aria-pressed', String(on));
  $('legend-truth').hidden = !on;
  client.refresh();
  for (const p of Object.values(plots)) p.setVisible(p.series.length - 1, on);
  if (!on) {
    for (const ch of client.channels.values()) if (isTruth(ch.topic)) scene.removeTopic(ch.topic);
    hook.truth.samples = 0;
    $('loc-error-row').hidden = true;
  }
}
$('truth').addEventListener('click', () => setTruthOverlay(!hook.truth.on));
setTruthOverlay(localStorage.getItem('fsd-truth-overlay') === '1');
