// A small canvas plot of values over time: a sliding window, autoscaled, redrawn at most once per frame.
export class TimePlot {
  // series: [{ label, color, dash?, hidden? }]; the first ones take push(), the others pushSeries()
  constructor(canvas, { title, unit, series, windowS = 30, minRange = 1, zeroBased = false }) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.title = title;
    this.unit = unit;
    this.series = series.map((s) => ({ ...s, t: [], v: [] }));
    this.windowS = windowS;
    this.minRange = minRange;
    this.zeroBased = zeroBased;  // the axis starts at 0 (magnitudes)
    this.dirty = true;
    this.count = 0;
    this.markers = [];  // { t, label }: vertical lines (events)
    new ResizeObserver(() => {
      this.dirty = true;
    }).observe(canvas);
    const loop = () => {
      if (this.dirty) this.draw();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  // One sample per series at time t (s); null skips a series.
  push(t, ...values) {
    const first = this.series[0];
    if (first.t.length && t < first.t[first.t.length - 1] - 1) this.clear();  // time went back: a new run
    values.forEach((v, i) => {
      const s = this.series[i];
      if (v === null || v === undefined || !Number.isFinite(v)) return;
      s.t.push(t);
      s.v.push(v);
      while (s.t.length && s.t[0] < t - this.windowS) {
        s.t.shift();
        s.v.shift();
      }
    });
    this.count++;
    this.last = { t, values };
    this.dirty = true;
  }

  // One sample of series i alone (a curve from another topic, e.g. the ground truth).
  pushSeries(i, t, v) {
    const s = this.series[i];
    if (!Number.isFinite(v)) return;
    s.t.push(t);
    s.v.push(v);
    while (s.t.length && s.t[0] < t - this.windowS) {
      s.t.shift();
      s.v.shift();
    }
    this.dirty = true;
  }

  // Shows or hides series i; hiding forgets its samples.
  setVisible(i, visible) {
    const s = this.series[i];
    s.hidden = !visible;
    if (!visible) s.t.length = s.v.length = 0;
    this.dirty = true;
  }

  // A vertical line at time t with a label (an event, e.g. a loop closure).
  mark(t, label) {
    if (!Number.isFinite(t) || this.markers.some((m) => m.t === t)) return;
    this.markers.push({ t, label });
    if (this.markers.length > 20) this.markers.shift();
    this.dirty = true;
  }

  samples(i) {
    return this.series[i].t.length;
  }

  clear() {
    for (const s of this.series) s.t.length = s.v.length = 0;
    this.markers.length = 0;
  }

  draw() {
    this.dirty = false;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, this.canvas.clientWidth), h = Math.max(1, this.canvas.clientHeight);
    if (this.canvas.width !== Math.round(w * dpr) || this.canvas.height !== Math.round(h * dpr)) {
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
    }
    const g = this.ctx;
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    g.font = '12px system-ui, sans-serif';
    // The latest values go right of the title, or on a second row when the plot is too narrow for both.
    const legendW = this.series.reduce((sum, s) => sum + (!s.hidden && s.v.length ? g.measureText(`${s.label} ${s.v[s.v.length - 1].toFixed(2)}`).width + 12 : 0), 0);
    const twoRows = g.measureText(`${this.title} [${this.unit}]`).width + 44 + legendW + 8 > w;
    const padL = 44, padR = 8, padT = twoRows ? 36 : 22, padB = 18;
    const pw = w - padL - padR, ph = h - padT - padB;

    let tMax = -Infinity, lo = Infinity, hi = -Infinity;
    for (const s of this.series) {
      if (s.t.length) tMax = Math.max(tMax, s.t[s.t.length - 1]);
      for (const v of s.v) {
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    }
    g.font = '12px system-ui, sans-serif';
    g.fillStyle = '#cfd6e0';
    g.textBaseline = 'top';
    g.fillText(`${this.title} [${this.unit}]`, padL, 4);
    if (!Number.isFinite(tMax)) return;
    if (hi - lo < this.minRange) {
      const mid = (hi + lo) / 2;
      lo = mid - this.minRange / 2;
      hi = mid + this.minRange / 2;
    }
    const margin = (hi - lo) * 0.08;
    lo -= margin;
    hi += margin;
    if (this.zeroBased) {
      lo = 0;
      hi = Math.max(hi, this.minRange);
    }
    const tMin = tMax - this.windowS;
    const X = (t) => padL + ((t - tMin) / this.windowS) * pw;
    const Y = (v) => padT + (1 - (v - lo) / (hi - lo)) * ph;

    // Grid and axis labels.
    g.strokeStyle = '#2b313b';
    g.lineWidth = 1;
    g.fillStyle = '#8c96a5';
    g.textBaseline = 'middle';
    for (let i = 0; i <= 4; i++) {
      const v = lo + ((hi - lo) * i) / 4, y = Y(v);
      g.beginPath();
      g.moveTo(padL, y);
      g.lineTo(padL + pw, y);
      g.stroke();
      g.fillText(v.toFixed(Math.abs(hi - lo) < 5 ? 2 : 1), 2, y);
    }
    if (lo < 0 && hi > 0) {
      g.strokeStyle = '#4a5362';
      g.beginPath();
      g.moveTo(padL, Y(0));
      g.lineTo(padL + pw, Y(0));
      g.stroke();
    }
    g.textBaseline = 'top';
    g.fillText(`−${this.windowS} s`, padL, padT + ph + 3);

    // Event markers within the window.
    for (const m of this.markers) {
      if (m.t < tMin || m.t > tMax) continue;
      const x = X(m.t);
      g.strokeStyle = '#ffd400';
      g.setLineDash([4, 3]);
      g.beginPath();
      g.moveTo(x, padT);
      g.lineTo(x, padT + ph);
      g.stroke();
      g.setLineDash([]);
      g.fillStyle = '#ffd400';
      g.fillText(m.label, Math.min(x + 3, padL + pw - g.measureText(m.label).width), padT + 2);
    }
    g.fillStyle = '#8c96a5';

    // The series, and the latest values in the title row.
    let legendX = w - padR;
    g.textAlign = 'right';
    for (let k = this.series.length - 1; k >= 0; k--) {
      const s = this.series[k];
      if (s.hidden) continue;
      g.strokeStyle = s.color;
      g.lineWidth = 2;
      g.setLineDash(s.dash ?? []);
      g.beginPath();
      for (let i = 0; i < s.t.length; i++) {
        const x = X(s.t[i]), y = Y(s.v[i]);
        if (i === 0) g.moveTo(x, y);
        else g.lineTo(x, y);
      }
      g.stroke();
      g.setLineDash([]);
      if (s.v.length) {
        g.fillStyle = s.color;
        const text = `${s.label} ${s.v[s.v.length - 1].toFixed(2)}`;
        g.fillText(text, legendX, twoRows ? 19 : 4);
        legendX -= g.measureText(text).width + 12;
      }
    }
    g.textAlign = 'left';
  }
}
