// The parameter panel: the list comes from /api/params (type, unit, bounds, doc); values stay live through the
// Foxglove parameter subscription; changes go out as setParameters with the token the user typed, and the
// server's refusals are shown as they come.
export class ParamPanel {
  constructor({ table, tokenInput, applyButton, feedback, client }) {
    this.table = table;
    this.tokenInput = tokenInput;
    this.feedback = feedback;
    this.client = client;
    this.rows = new Map();  // key → { info, input, row }
    this.pending = null;    // { id, values }
    this.values = {};
    this.tokenInput.value = sessionStorage.getItem('fsd-token') ?? '';
    this.tokenInput.addEventListener('change', () => sessionStorage.setItem('fsd-token', this.tokenInput.value));
    applyButton.addEventListener('click', () => this.apply());
  }

  async load() {
    try {
      const res = await fetch('api/params', { cache: 'no-store' });
      const body = await res.json();
      this.tuningEnabled = body.tuning_enabled;
      this.render(body.params ?? []);
      if (!this.tuningEnabled) this.say('Tuning is disabled on this car (no token configured).', 'info');
    } catch (e) {
      this.say(`Cannot load parameters: ${e}`, 'error');
    }
  }

  render(params) {
    const body = this.table.tBodies[0];
    body.replaceChildren();
    this.rows.clear();
    for (const p of params) {
      const row = body.insertRow();
      row.title = p.doc;
      const name = row.insertCell();
      name.textContent = p.key;
      name.className = 'pname';
      const cell = row.insertCell();
      const input = document.createElement('input');
      input.dataset.key = p.key;
      if (p.type === 'boolean') {
        input.type = 'checkbox';
        input.checked = !!p.value;
      } else {
        input.type = 'number';
        input.step = p.type === 'integer' ? '1' : 'any';
        if (p.min !== null) input.min = p.min;
        if (p.max !== null) input.max = p.max;
        input.value = p.value;
      }
      input.disabled = !this.tuningEnabled;
      input.addEventListener('input', () => row.classList.add('edited'));
      cell.append(input);
      const unit = row.insertCell();
      unit.className = 'unit';
      unit.textContent = [p.unit, p.min !== null || p.max !== null ? `${p.min ?? '−∞'}…${p.max ?? '∞'}` : '']
        .filter(Boolean).join(' ');
      this.rows.set(p.key, { info: p, input, row });
      this.values[p.key] = p.value;
    }
  }

  readInput({ info, input }) {
    if (info.type === 'boolean') return input.checked;
    const v = Number(input.value);
    return info.type === 'integer' ? Math.round(v) : v;
  }

  apply() {
    const parameters = [];
    for (const [key, r] of this.rows)
      if (r.row.classList.contains('edited')) parameters.push({ name: key, value: this.readInput(r) });
    if (!parameters.length) {
      this.say('Nothing changed.', 'info');
      return;
    }
    const token = this.tokenInput.value.trim();
    sessionStorage.setItem('fsd-token', token);
    const id = this.client.setParameters(parameters, token);
    if (!id) {
      this.say('Not connected.', 'error');
      return;
    }
    this.pending = { id, values: Object.fromEntries(parameters.map((p) => [p.name, p.value])), refused: null };
    this.say('Sending…', 'info');
  }

  // parameterValues from the server: a reply to our request (id) or an update.
  onValues(params, id) {
    for (const p of params) {
      this.values[p.name] = p.value;
      const r = this.rows.get(p.name);
      if (!r) continue;
      const mine = this.pending && id === this.pending.id;
      if (!r.row.classList.contains('edited') || mine) {
        if (r.info.type === 'boolean') r.input.checked = !!p.value;
        else r.input.value = p.value;
        r.row.classList.remove('edited');
      }
    }
    if (this.pending && id === this.pending.id) {
      const ok = Object.entries(this.pending.values).every(([k, v]) => this.values[k] === v);
      if (ok && !this.pending.refused) this.say(`Applied: ${Object.keys(this.pending.values).join(', ')}`, 'ok');
      else this.say(`Refused: ${this.pending.refused ?? 'the server kept the old values'}`, 'error');
      this.pending = null;
    }
  }

  // Status messages from the server: a refusal of our request arrives just before its parameterValues.
  onStatus(msg) {
    if (msg.level >= 2 && this.pending && /arameter/.test(msg.message)) this.pending.refused = msg.message;
  }

  say(text, kind) {
    this.feedback.textContent = text;
    this.feedback.className = `feedback ${kind}`;
    this.last = { text, kind };
  }
}
