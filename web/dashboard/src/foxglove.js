// A client of the Foxglove WebSocket protocol v1 (the same protocol Foxglove Studio speaks): it subscribes to
// the advertised channels its `wants(channel)` accepts as soon as they are advertised, decodes binary message
// data, handles parameters, and reconnects by itself with a growing back-off.
const SUBPROTOCOL = 'foxglove.websocket.v1';
const OP_MESSAGE_DATA = 0x01;
const OP_TIME = 0x02;

export class FoxgloveClient {
  // handlers: { onState(state, detail), onServerInfo(info), onAdvertise(channels), onStatus(msg),
  //             onMessage(topic, tNs, payload, channel), onParameterValues(params, id), onTime(tNs) }
  constructor(url, wants, handlers) {
    this.url = url;
    this.wants = wants;
    this.h = handlers;
    this.channels = new Map();      // channel id → channel
    this.subs = new Map();          // subscription id → channel
    this.nextSub = 1;
    this.nextRequest = 1;
    this.retryMs = 500;
    this.ws = null;
    this.decoder = new TextDecoder();
    this.stats = { messages: 0, bytes: 0 };
    this.closedByUser = false;
  }

  connect() {
    this.closedByUser = false;
    this.h.onState?.('connecting');
    let ws;
    try {
      ws = new WebSocket(this.url, [SUBPROTOCOL]);
    } catch (e) {
      this.scheduleReconnect(String(e));
      return;
    }
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onopen = () => {
      this.retryMs = 500;
      this.channels.clear();
      this.subs.clear();
      this.h.onState?.('connected');
    };
    ws.onmessage = (ev) => this.onMessage(ev.data);
    ws.onclose = (ev) => {
      if (this.ws !== ws) return;
      this.ws = null;
      if (!this.closedByUser) this.scheduleReconnect(ev.reason || `code ${ev.code}`);
    };
    ws.onerror = () => {};  // onclose follows and reconnects
  }

  close() {
    this.closedByUser = true;
    this.ws?.close(1000, 'bye');
  }

  scheduleReconnect(why) {
    const delay = this.retryMs;
    this.retryMs = Math.min(this.retryMs * 2, 5000);
    this.h.onState?.('reconnecting', { delay, why });
    setTimeout(() => this.connect(), delay);
  }

  send(obj) {
    if (this.ws?.readyState === WebSocket.OPEN) {
      this.ws.send(JSON.stringify(obj));
      return true;
    }
    return false;
  }

  onMessage(data) {
    if (typeof data === 'string') {
      let msg;
      try {
        msg = JSON.parse(data);
      } catch {
        return;
      }
      this.onJson(msg);
      return;
    }
    const view = new DataView(data);
    if (view.byteLength < 1) return;
    const op = view.getUint8(0);
    if (op === OP_MESSAGE_DATA && view.byteLength >= 13) {
      const channel = this.subs.get(view.getUint32(1, true));
      if (!channel) return;
      const tNs = view.getBigUint64(5, true);
      this.stats.messages++;
      this.stats.bytes += data.byteLength;
      let payload;
      try {
        payload = JSON.parse(this.decoder.decode(new Uint8Array(data, 13)));
      } catch {
        return;
      }
      this.h.onMessage?.(channel.topic, tNs, payload, channel);
    } else if (op === OP_TIME && view.byteLength >= 9) {
      this.h.onTime?.(view.getBigUint64(1, true));
    }
  }

  onJson(msg) {
    switch (msg.op) {
      case 'serverInfo':
        this.serverInfo = msg;
        this.h.onServerInfo?.(msg);
        if (msg.capabilities?.includes('parametersSubscribe')) this.send({ op: 'subscribeParameterUpdates', parameterNames: [] });
        break;
      case 'advertise': {
        for (const ch of msg.channels ?? []) this.channels.set(ch.id, ch);
        this.h.onAdvertise?.(this.channels);
        this.refresh();
        break;
      }
      case 'unadvertise':
        for (const id of msg.channelIds ?? []) {
          this.channels.delete(id);
          for (const [sid, ch] of this.subs) if (ch.id === id) this.subs.delete(sid);
        }
        this.h.onAdvertise?.(this.channels);
        break;
      case 'status':
        this.h.onStatus?.(msg);
        break;
      case 'parameterValues':
        this.h.onParameterValues?.(msg.parameters ?? [], msg.id);
        break;
      default:
        break;
    }
  }

  // Subscribes to every advertised channel `wants` accepts now and unsubscribes from the others (after a change of
  // what is wanted, e.g. the truth overlay turned on or off).
  refresh() {
    const subscribed = new Set([...this.subs.values()].map((ch) => ch.id));
    const subscriptions = [];
    for (const ch of this.channels.values()) {
      if (subscribed.has(ch.id) || ch.encoding !== 'json' || !this.wants(ch)) continue;
      const id = this.nextSub++;
      this.subs.set(id, ch);
      subscriptions.push({ id, channelId: ch.id });
    }
    if (subscriptions.length) this.send({ op: 'subscribe', subscriptions });
    const gone = [...this.subs].filter(([, ch]) => !this.wants(ch)).map(([id]) => id);
    for (const id of gone) this.subs.delete(id);
    if (gone.length) this.send({ op: 'unsubscribe', subscriptionIds: gone });
  }

  hasTopic(topic) {
    for (const ch of this.channels.values()) if (ch.topic === topic) return true;
    return false;
  }

  getParameters(names = []) {
    const id = `get-${this.nextRequest++}`;
    this.send({ op: 'getParameters', parameterNames: names, id });
    return id;
  }

  // `token` is our extension of setParameters (see docs/dashboard.md); Foxglove Studio passes ?token= instead.
  setParameters(parameters, token) {
    const id = `set-${this.nextRequest++}`;
    const msg = { op: 'setParameters', parameters, id };
    if (token) msg.token = token;
    return this.send(msg) ? id : null;
  }
}

// Seconds from a Foxglove {sec, nsec} time.
export function seconds(t) {
  return t ? t.sec + t.nsec * 1e-9 : 0;
}

// Standard base64 → bytes.
export function fromBase64(s) {
  const bin = atob(s);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}
