// The IPE002Z card's page (docs/web.md "The page"): a client of the card's JSON API (/api/...) and nothing
// else. Plain JavaScript, no framework, no build step; registers.js (generated from registers.csv) comes
// first and defines IPE_REGISTERS.
'use strict';
(() => {
  // ---------------------------------------------------------------------------------------------------
  // Helpers
  const $ = (id) => document.getElementById(id);
  function el(tag, props, ...kids) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(props || {})) {
      if (v == null || v === false) continue;
      if (k === 'class') e.className = v;
      else if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v === true ? '' : v);
    }
    for (const k of kids.flat()) if (k != null && k !== false) e.append(k.nodeType ? k : String(k));
    return e;
  }
  const hex = (w, digits = 4) => '0x' + (w & 0xffff).toString(16).toUpperCase().padStart(digits, '0');
  const secs = (ms) => Math.max(1, Math.ceil(ms / 1000));
  const setText = (id, text) => { const e = $(id); if (e && e.textContent !== text) e.textContent = text; };
  class UserError extends Error {}

  // ---------------------------------------------------------------------------------------------------
  // The register table (registers.js) and value formatting
  const REGS = new Map();
  const BY_TITLE = new Map();
  for (const r of window.IPE_REGISTERS || []) {
    const reg = {
      number: r[0], title: r[1], fn: r[2], access: r[3], mb1: [r[4], r[5], r[6]],
      s15: r[7] == null ? null : [r[7], r[8], r[9]], unit: r[10], wdr: !!r[11], afterReset: !!r[12], models: r[13],
    };
    REGS.set(reg.number, reg);
    BY_TITLE.set(reg.title, reg);
  }
  const reg = (number) => REGS.get(number) ||
    { number, title: number.toLowerCase(), fn: '', access: 'ro', mb1: [0, 65535, 0], s15: null, unit: '-', models: 'both' };
  const cnum = (n) => 'C' + String(n).padStart(3, '0');   // c081 -> "C081"

  let model = 'unknown';
  const limits = (r) => (model === 'vf-s15' && r.s15) || r.mb1;   // [min, max, default]
  const onModel = (r) => r.models === 'both' || r.models === model || model === 'unknown';
  function unitOf(r) {
    if (r.unit === '-' || r.unit === 'bits' || r.unit === 'char') return { kind: r.unit, dec: 0, sym: '' };
    const [step, sym] = r.unit.split(' ');
    return { kind: 'num', dec: (step.split('.')[1] || '').length, sym: sym === 'degC' ? '\u00b0C' : sym };
  }
  const signedWord = (r, w) => (r.mb1[0] < 0 && w >= 0x8000 ? w - 0x10000 : w);
  // The number shown for a raw value (no unit): 100 with unit "0.1 s" -> "10.0".
  function scaled(r, raw) {
    const u = unitOf(r);
    return u.kind === 'num' ? (raw / 10 ** u.dec).toFixed(u.dec) : String(raw);
  }
  function withUnit(r, text) { const u = unitOf(r); return u.sym ? text + ' ' + u.sym : text; }
  function fmtValue(r, w) {
    const u = unitOf(r);
    if (u.kind === 'bits') return hex(w);
    if (u.kind === 'char') return w === 0 ? '0 (end)' : (w >= 32 && w < 127 ? `'${String.fromCharCode(w)}' ` : '') + hex(w, 2);
    const text = withUnit(r, scaled(r, signedWord(r, w)));
    const opt = options(r);
    const name = opt && opt.get(w);
    return name ? `${text} (${name})` : text;
  }
  function fmtRange(r) {
    const [lo, hi] = limits(r);
    if (unitOf(r).kind === 'bits') return `${hex(lo)}..${hex(hi)}`;
    return withUnit(r, `${scaled(r, lo)}..${scaled(r, hi)}`);
  }

  // Choices named in the function text: "Protocol (0 Modbus TCP, 1 EtherNet/IP)", "(menu: 0 none, 1 FA06,
  // ..., 26-30 FD23-FD27; 4, 7 reserved)". A Map value -> name, or null when the text names fewer than two.
  const optionCache = new Map();
  function options(r) {
    if (optionCache.has(r.number)) return optionCache.get(r.number);
    let map = null;
    const m = /\(([^()]*)\)/.exec(r.fn);
    if (m) {
      map = new Map();
      for (const part of m[1].replace(/^menu:\s*/, '').split(';')[0].split(', ')) {
        const p = /^(\d+)(?:-(\d+))? (.+)$/.exec(part.trim());
        if (!p) continue;
        const name = p[3].replace(/^= /, '');
        const span = /^([0-9A-F]{2})(\d\d)-\1(\d\d)$/.exec(name);
        if (p[2] && span) {
          for (let v = +p[1]; v <= +p[2]; v++) map.set(v, span[1] + String(+span[2] + v - +p[1]).padStart(2, '0'));
        } else if (!p[2]) map.set(+p[1], name);
      }
      if (map.size < 2) map = null;
    }
    optionCache.set(r.number, map);
    return map;
  }
  // The function text without a scanner menu's list of choices (those show as names).
  const shortFn = (r) => r.fn.replace(/\s*\(menu:[^)]*\)/, '');
  // A scanner menu entry ("FA06", "acc") with the register it names: "FA06 fa06", "acc (0009)".
  function menuTarget(name) {
    if (REGS.has(name)) return REGS.get(name);
    return BY_TITLE.get(name) || null;
  }
  function menuLabel(r, code) {
    const name = (options(r) || new Map()).get(code);
    if (name == null) return `${code} (reserved)`;
    const t = menuTarget(name);
    if (!t) return `${code}: ${name}`;
    return t.title === t.number.toLowerCase() ? `${code}: ${t.number}` : `${code}: ${t.title} (${t.number})`;
  }

  // ---------------------------------------------------------------------------------------------------
  // The JSON API
  const session = { level: 'none', defaults: false, csrf: sessionStorage.getItem('ipe-csrf') || '' };
  class ApiError extends Error {
    constructor(status, message, body) { super(message); this.status = status; this.body = body; }
  }
  async function api(method, path, body) {
    const headers = {};
    const init = { method, headers, credentials: 'same-origin', cache: 'no-store' };
    if (method !== 'GET') {
      if (path !== '/api/login') headers['X-CSRF-Token'] = session.csrf;
      if (body !== undefined) { headers['Content-Type'] = 'application/json'; init.body = JSON.stringify(body); }
    }
    let res;
    try { res = await fetch(path, init); } catch (e) { throw new ApiError(0, 'no answer from the card', null); }
    const text = await res.text();
    let data = null;
    try { data = text ? JSON.parse(text) : null; } catch (e) { data = null; }
    if (res.ok) return data;
    const err = new ApiError(res.status, (data && data.error) || `HTTP ${res.status} ${res.statusText}`, data);
    err.retryMs = (data && data.retry_after_ms) || (Number(res.headers.get('Retry-After')) * 1000) || 0;
    if (res.status === 401 && path !== '/api/login' && path !== '/api/elevate') sessionEnded();
    throw err;
  }
  function describe(x) {
    if (!(x instanceof ApiError)) return x.message;
    let text = x.message + (x.status ? ` (HTTP ${x.status})` : '');
    if (x.retryMs) text += `; wait ${secs(x.retryMs)} s`;
    return text;
  }
  function applySession(s) {
    session.level = s.level || 'none';
    session.defaults = !!s.defaults;
    $('defaults-banner').hidden = !session.defaults || session.level === 'none';
    const lv = $('session-level');
    lv.textContent = session.level === 'none' ? '' : session.level === 'write' ? 'write access' : 'read access';
    lv.className = 'level ' + session.level;
    $('logout').hidden = session.level === 'none';
  }
  async function refreshSession() {
    try { applySession(await api('GET', '/api/session')); } catch (e) { /* the next call shows it */ }
    return session.level;
  }
  async function elevate(password) {
    if (!password) throw new UserError('Enter the write password.');
    try {
      const r = await api('POST', '/api/elevate', { password });
      applySession({ level: (r && r.level) || 'write', defaults: session.defaults });
    } catch (x) {
      if (x.status === 401) {
        if (await refreshSession() === 'none') { sessionEnded(); throw new UserError('The session has ended.'); }
        throw new UserError('Wrong write password' + (x.retryMs ? `; wait ${secs(x.retryMs)} s before the next attempt.` : '.'));
      }
      if (x.status === 429) throw new UserError(`Too many failed password attempts: wait ${secs(x.retryMs)} s.`);
      throw x;
    }
  }
  // Writes [[number, word], ...] one after the other; the first refusal stops and names the register.
  async function writeRegisters(list) {
    for (const [number, value] of list) {
      try {
        await api('POST', '/api/registers', { number, value });
      } catch (x) {
        if (x.status === 403 && /write password/i.test(x.message)) {
          applySession({ level: 'read', defaults: session.defaults });
          $('edit-password-row').hidden = false;
          throw new UserError('The write access has expired: enter the write password again.');
        }
        x.message = `${reg(number).title} (${number}): ${x.message}`;
        throw x;
      }
    }
  }
  async function readRegisters(numbers) {
    const values = new Map();
    for (let i = 0; i < numbers.length; i += 32) {
      const r = await api('GET', '/api/registers?numbers=' + numbers.slice(i, i + 32).join(','));
      for (const v of r.values) values.set(v.number, v);
    }
    return values;
  }

  // ---------------------------------------------------------------------------------------------------
  // Login screen
  let loginTimer = 0;
  function showLogin(message) {
    document.body.classList.add('logged-out');
    $('login').hidden = false;
    $('page').replaceChildren();
    stopPage();
    setText('login-error', message || '');
    $('login-password').focus();
  }
  function sessionEnded() {
    if (document.body.classList.contains('logged-out')) return;
    applySession({ level: 'none' });
    showLogin('The session has ended: log in again.');
  }
  // The back-off: the button stays off and the wait counts down.
  function loginWait(ms, why) {
    const until = Date.now() + ms;
    const button = $('login-submit');
    clearInterval(loginTimer);
    const tick = () => {
      const left = until - Date.now();
      if (left <= 0) { clearInterval(loginTimer); button.disabled = false; setText('login-error', why); return; }
      button.disabled = true;
      setText('login-error', `${why} Wait ${secs(left)} s before the next attempt.`);
    };
    tick();
    loginTimer = setInterval(tick, 250);
  }
  $('login-form').addEventListener('submit', async (e) => {
    e.preventDefault();
    const field = $('login-password');
    setText('login-error', '');
    try {
      const r = await api('POST', '/api/login', { password: field.value });
      session.csrf = r.csrf;
      sessionStorage.setItem('ipe-csrf', r.csrf);
      field.value = '';
      applySession(r);
      enterApp();
    } catch (x) {
      field.select();
      if (x.status === 429) loginWait(x.retryMs || 1000, 'Too many failed attempts.');
      else if (x.status === 401 && x.retryMs) loginWait(x.retryMs, 'Wrong password.');
      else if (x.status === 401) setText('login-error', 'Wrong password.');
      else setText('login-error', describe(x));
    }
  });
  $('logout').addEventListener('click', async () => {
    try { await api('POST', '/api/logout'); } catch (e) { /* gone anyway */ }
    sessionStorage.removeItem('ipe-csrf');
    session.csrf = '';
    applySession({ level: 'none' });
    showLogin('Logged out.');
  });

  // ---------------------------------------------------------------------------------------------------
  // Edit dialog: spec = {title, info, fields: [elements], okText, prepare() -> job (throws UserError),
  // action(job) (async), done()}. Asks for the write password when the session is not at write level.
  const dialog = $('edit-dialog');
  let dialogSpec = null;
  function openDialog(spec) {
    dialogSpec = spec;
    setText('edit-title', spec.title);
    setText('edit-info', spec.info || '');
    $('edit-fields').replaceChildren(...(spec.fields || []));
    $('edit-password-row').hidden = session.level === 'write';
    $('edit-password').value = '';
    setText('edit-error', '');
    setText('edit-ok', spec.okText || 'Write');
    $('edit-ok').disabled = false;
    dialog.showModal();
    const first = dialog.querySelector('#edit-fields input, #edit-fields select') || $('edit-password');
    if (first) { first.focus(); if (first.select) first.select(); }
  }
  $('edit-cancel').addEventListener('click', () => dialog.close());
  $('edit-form').addEventListener('submit', async (e) => {
    e.preventDefault();
    const spec = dialogSpec;
    const ok = $('edit-ok');
    setText('edit-error', '');
    ok.disabled = true;
    try {
      const job = spec.prepare ? spec.prepare() : null;
      if (session.level !== 'write') await elevate($('edit-password').value);
      $('edit-password-row').hidden = true;
      await spec.action(job);
      dialog.close();
      if (spec.done) spec.done(job);
    } catch (x) {
      setText('edit-error', describe(x));
    } finally {
      ok.disabled = false;
    }
  });
  function field(label, input) {
    return el('div', { class: 'field' }, el('label', { for: input.id, text: label }), input);
  }
  // The input for one register's new value, in its unit step; parse() gives the raw word.
  function valueInput(r, current) {
    const u = unitOf(r);
    const [lo, hi] = limits(r);
    const opts = options(r);
    // A list of choices for the scanner menus, and for codes whose every value is named.
    const menu = /^c0[02][1-6]$/.test(r.title);
    let input;
    if (opts && (menu || (hi - lo < 64 && Array.from({ length: hi - lo + 1 }, (_, i) => lo + i).every((v) => opts.has(v))))) {
      input = el('select', { id: 'edit-value' });
      for (const [v, name] of opts) {
        if (v >= lo && v <= hi) input.append(el('option', { value: v, text: menu ? menuLabel(r, v) : `${v}: ${name}` }));
      }
      if (current != null) input.value = String(current);
    } else if (u.kind === 'num' || u.kind === '-') {
      input = el('input', { id: 'edit-value', type: 'number', step: u.dec ? (1 / 10 ** u.dec).toFixed(u.dec) : '1',
        min: scaled(r, lo), max: scaled(r, hi) });
      if (current != null) input.value = scaled(r, signedWord(r, current));
    } else {
      input = el('input', { id: 'edit-value', type: 'text', placeholder: u.kind === 'char' ? 'a character or 0-127' : '0x0000' });
      if (current != null) input.value = u.kind === 'char' ? (current ? String.fromCharCode(current) : '') : hex(current);
    }
    const parse = () => {
      const text = input.value.trim();
      let raw;
      if (u.kind === 'char' && text.length === 1 && !/\d/.test(text)) raw = text.charCodeAt(0);
      else if (u.kind === 'char' && text === '') raw = 0;
      else if (/^0x[0-9a-f]+$/i.test(text) && u.kind !== 'num') raw = parseInt(text, 16);
      else {
        const v = Number(text);
        if (text === '' || !Number.isFinite(v)) throw new UserError('Enter a number.');
        raw = Math.round(v * 10 ** u.dec);
        if (Math.abs(raw - v * 10 ** u.dec) > 1e-6) throw new UserError(`Use steps of ${r.unit.split(' ')[0]}.`);
      }
      if (raw < lo || raw > hi) throw new UserError(`Out of range: ${fmtRange(r)}.`);
      return raw & 0xffff;
    };
    return { input, parse };
  }
  function editRegister(r, current, done) {
    const { input, parse } = valueInput(r, current);
    openDialog({
      title: `${r.title} (${r.number})`,
      info: `${shortFn(r)}. Range ${fmtRange(r)}` + (current != null ? `; now ${fmtValue(r, current)}.` : '.') +
        (r.afterReset ? ' Takes effect after the communication reset.' : ''),
      fields: [field('New value' + (unitOf(r).sym ? ` (${unitOf(r).sym})` : ''), input)],
      prepare: () => [[r.number, parse()]],
      action: writeRegisters,
      done: (job) => { toast(`${r.title} = ${fmtValue(r, job[0][1])}`); if (done) done(); },
    });
  }
  // Four octet registers as one dotted address.
  const dotted = (words) => words.join('.');
  function editAddress(label, first, words, done) {
    const input = el('input', { id: 'edit-value', type: 'text', value: dotted(words), placeholder: '192.168.0.10' });
    const numbers = [0, 1, 2, 3].map((i) => cnum(first + i));
    openDialog({
      title: `${label} (${numbers[0].toLowerCase()}-${numbers[3].toLowerCase()})`,
      info: 'Takes effect after the communication reset.',
      fields: [field(label, input)],
      prepare: () => {
        const parts = input.value.trim().split('.');
        if (parts.length !== 4 || !parts.every((p) => /^\d{1,3}$/.test(p) && +p <= 255)) throw new UserError('Enter four numbers 0-255: a.b.c.d');
        return parts.map((p, i) => [numbers[i], +p]);
      },
      action: writeRegisters,
      done: () => { toast(`${label} = ${input.value.trim()}`); if (done) done(); },
    });
  }
  function editDeviceName(current, done) {
    const input = el('input', { id: 'edit-value', type: 'text', value: current, maxlength: 16 });
    openDialog({
      title: 'Device name (c081-c096)',
      info: 'Up to 16 ASCII characters; also the DHCP host name.',
      fields: [field('Device name', input)],
      prepare: () => {
        const text = input.value;
        if (text.length > 16 || !/^[\x20-\x7e]*$/.test(text)) throw new UserError('Up to 16 printable ASCII characters.');
        return Array.from({ length: 16 }, (_, i) => [cnum(81 + i), i < text.length ? text.charCodeAt(i) : 0]);
      },
      action: writeRegisters,
      done: () => { toast(`Device name = ${input.value}`); if (done) done(); },
    });
  }

  let toastTimer = 0;
  function toast(text, bad) {
    const t = $('toast');
    t.textContent = text;
    t.className = bad ? 'bad' : '';
    t.hidden = false;
    clearTimeout(toastTimer);
    toastTimer = setTimeout(() => { t.hidden = true; }, 3500);
  }

  // ---------------------------------------------------------------------------------------------------
  // Pages, menus and polling
  const MENUS = [
    { id: 'monitoring', label: 'Monitoring', pages: ['drive-monitor', 'drive-parameters'] },
    { id: 'network', label: 'Network setup', pages: ['network', 'modbus-scanner', 'eip-scanner', 'administration'] },
    { id: 'diagnostics', label: 'Diagnostics', pages: ['statistics'] },
  ];
  const PAGES = {
    'drive-monitor': { title: 'Drive monitor', render: driveMonitor },
    'drive-parameters': { title: 'Drive parameters', render: driveParameters },
    network: { title: 'Network parameters', render: networkPage },
    'modbus-scanner': { title: 'Modbus scanner', render: modbusScanner },
    'eip-scanner': { title: 'EthIP scanner', render: eipScanner },
    administration: { title: 'Administration', render: administration },
    statistics: { title: 'TCP/IP statistics', render: statistics },
  };
  let generation = 0;
  function stopPage() { generation++; live('idle'); }
  // Calls fn now and then every `ms` after the start of the previous call (never two at once) while the
  // page that started it is shown.
  function poll(ms, fn) {
    const gen = generation;
    const loop = async () => {
      if (gen !== generation) return;
      const start = performance.now();
      try {
        await fn();
        if (gen === generation) live('ok');
      } catch (x) {
        if (gen === generation) live('bad', describe(x));
      }
      if (gen === generation) setTimeout(loop, Math.max(0, ms - (performance.now() - start)));
    };
    loop();
  }
  function live(stateName, why) {
    const e = $('live');
    e.classList.remove('ok', 'bad', 'beat');
    if (stateName !== 'idle') {
      e.classList.add(stateName);
      if (stateName === 'ok') { void e.offsetWidth; e.classList.add('beat'); }
    }
    setText('live-text', stateName === 'ok' ? 'live' : stateName === 'bad' ? 'no data' : 'idle');
    e.title = why || (stateName === 'ok' ? 'Updating' : stateName === 'bad' ? 'No answer' : 'Nothing is polled on this page');
  }

  function buildMenus() {
    const main = $('main-menu');
    for (const m of MENUS) main.append(el('a', { id: 'menu-' + m.id, href: '#/' + m.pages[0], text: m.label }));
    $('menu-toggle').addEventListener('click', () => {
      const hidden = document.body.classList.toggle('no-side-menu');
      $('menu-toggle').setAttribute('aria-expanded', String(!hidden));
      localStorage.setItem('ipe-side-menu', hidden ? 'hidden' : 'shown');
    });
    if (localStorage.getItem('ipe-side-menu') === 'hidden') document.body.classList.add('no-side-menu');
  }
  function route() {
    if (session.level === 'none') return;
    const [name, arg] = location.hash.replace(/^#\/?/, '').split('/');
    const id = PAGES[name] ? name : 'drive-monitor';
    const menu = MENUS.find((m) => m.pages.includes(id));
    for (const m of MENUS) $('menu-' + m.id).classList.toggle('active', m === menu);
    $('side-menu').replaceChildren(el('h2', { text: menu.label }),
      ...menu.pages.map((p) => el('a', { id: 'nav-' + p, href: '#/' + p, class: p === id ? 'active' : null, text: PAGES[p].title })),
      // The card's EDS file, for adding the card to a scanner's project (docs/file-object.md).
      ...(menu.id === 'network' ? [el('a', { id: 'nav-eds', href: '/api/eds', download: true, text: 'Download EDS' })] : []));
    stopPage();
    const page = $('page');
    page.replaceChildren(el('h1', { text: PAGES[id].title }));
    document.title = `${PAGES[id].title} - IPE002Z`;
    PAGES[id].render(page, arg);
    refreshSession();
  }
  function enterApp() {
    document.body.classList.remove('logged-out');
    $('login').hidden = true;
    api('GET', '/api/monitor').then((m) => { model = m.model || model; }).catch(() => {}).finally(route);
  }
  // A status line under a page's title: errors of its calls.
  function statusLine(page) {
    const s = el('p', { class: 'status', role: 'status' });
    page.append(s);
    return (text, bad) => { s.textContent = text || ''; s.classList.toggle('error', !!bad); };
  }
  function table(head, rows, cls) {
    return el('table', { class: cls || null },
      el('thead', {}, el('tr', {}, head.map((h) => el('th', { text: h })))), el('tbody', {}, rows));
  }
  function section(title, ...kids) { return el('section', { class: 'card' }, el('h2', { text: title }), kids); }

  // ---------------------------------------------------------------------------------------------------
  // Drive monitor
  const TRIPS = new Map([
    [0, 'no trip'], [1, 'oc1 over-current during acceleration'], [2, 'oc2 over-current during deceleration'],
    [3, 'oc3 over-current at constant speed'], [4, 'ocl over-current in the load at start-up'], [5, 'oca arm short circuit'],
    [8, 'ephi input phase failure'], [9, 'epho output phase failure'], [10, 'op1 overvoltage during acceleration'],
    [11, 'op2 overvoltage during deceleration'], [12, 'op3 overvoltage at constant speed'], [13, 'ol1 inverter overload'],
    [14, 'ol2 motor overload'], [16, 'oh overheat'], [17, 'e emergency stop'], [18, 'eep1 EEPROM fault (write)'],
    [19, 'eep2 EEPROM fault (read)'], [20, 'eep3 EEPROM fault (internal)'], [21, 'err2 RAM fault'], [22, 'err3 ROM fault'],
    [23, 'err4 CPU fault'], [24, 'err5 RS485 communication error'], [26, 'err7 current detector fault'],
    [27, 'err8 network error'], [29, 'uc undercurrent'], [30, 'up1 main circuit undervoltage'], [32, 'ot over-torque'],
    [34, 'ef2 ground fault'], [37, 'oc1p element over-current during acceleration'],
    [38, 'oc2p element over-current during deceleration'], [39, 'oc3p element over-current at constant speed'],
    [41, 'etyp inverter type error'], [46, 'oh2 external thermal input'], [47, 'sout PM motor step-out'],
    [50, 'e-18 VIA cable break'], [51, 'e-19 CPU fault'], [52, 'e-20 excess torque boost'], [53, 'e-21 CPU fault'],
    [55, 'e-23 option fault'], [84, 'etn1 auto-tuning error'],
  ]);
  const ALARMS = ['over-current', 'inverter overload', 'motor overload', 'overheat', 'overvoltage',
    'main circuit undervoltage', 'main device overheat', 'undercurrent', 'over-torque', 'braking resistor overload',
    'cumulative operation hours', 'option communication', 'serial communication', 'MOFF (MS relay off)',
    'stop after momentary power failure', 'stop after ll continuance time'];
  const INPUTS = ['F', 'R', 'RES', 'S1', 'S2', 'S3', 'VIB', 'VIA'];
  const OUTPUTS = ['RY-RC', 'OUT', 'FL'];
  const LEDS = [['ms', 'MS'], ['ns', 'NS'], ['lnk_l', 'LNK L'], ['lnk_r', 'LNK R']];
  const MON_VALUES = [
    ['FD00', 'output-frequency', 'Output frequency'], ['FE02', 'frequency-command', 'Frequency command'],
    ['FE03', 'output-current', 'Output current'], ['FE05', 'output-voltage', 'Output voltage'], ['FE18', 'torque', 'Torque'],
  ];
  function lamp(id, label) { return el('span', { id, class: 'lamp' }, el('i'), label); }
  function driveMonitor(page) {
    const status = statusLine(page);
    page.append(
      el('div', { class: 'tiles' },
        el('div', { class: 'tile state' },
          el('div', { class: 'badges' }, el('span', { id: 'mon-run', class: 'badge' }, '-'),
            el('span', { id: 'mon-direction', class: 'badge' }, '-'), el('span', { id: 'mon-tripped', class: 'badge' }, '-'),
            el('span', { id: 'mon-alarm', class: 'badge' }, '-'), el('span', { id: 'mon-ready', class: 'badge' }, '-')),
          el('div', { class: 'small muted' }, 'FD01 ', el('span', { id: 'mon-fd01' }, '-'), ' \u00b7 link ',
            el('span', { id: 'mon-link' }, '-'), ' \u00b7 ', el('span', { id: 'mon-model' }, '-'), ' \u00b7 ',
            el('span', { id: 'mon-protocol' }, '-'), ' \u00b7 age ', el('span', { id: 'mon-age' }, '-'))),
        MON_VALUES.map(([n, id, label]) => el('div', { class: 'tile' },
          el('div', { class: 'label' }, label, el('small', { text: n })), el('div', { id: 'mon-' + id, class: 'value' }, '-')))),
      el('div', { class: 'cards' },
        section('Trip and alarms',
          el('p', {}, 'Trip (FC90): ', el('b', { id: 'mon-trip' }, '-'), ' ', el('span', { id: 'mon-trip-code', class: 'muted' })),
          el('p', {}, 'Alarms (FC91): ', el('b', { id: 'mon-alarms' }, '-')),
          el('div', { class: 'lamps alarms' }, ALARMS.map((a, i) => lamp('mon-alarm-' + i, a)))),
        el('div', { class: 'stack' }, section('Terminals',
          el('p', { class: 'muted' }, 'Inputs (FE06) ', el('span', { id: 'mon-fe06' })),
          el('div', { class: 'lamps' }, INPUTS.map((t) => lamp('mon-in-' + t, t))),
          el('p', { class: 'muted' }, 'Outputs (FE07) ', el('span', { id: 'mon-fe07' })),
          el('div', { class: 'lamps' }, OUTPUTS.map((t) => lamp('mon-out-' + t, t)))),
        section('Card LEDs', el('div', { class: 'lamps leds' },
          LEDS.map(([k, label]) => el('span', { class: 'led' }, el('i', { id: 'mon-led-' + k + '-lamp' }), label, ' ',
            el('span', { id: 'mon-led-' + k, class: 'muted' }, '-'))))))));
    const badge = (id, text, cls) => { setText(id, text); $(id).className = 'badge ' + (cls || ''); };
    poll(400, async () => {
      let m;
      try { m = await api('GET', '/api/monitor'); } catch (x) { status(describe(x), true); throw x; }
      status('');
      model = m.model || model;
      const r = m.registers || {};
      const fd01 = r.FD01;
      if (fd01 != null) {
        badge('mon-run', fd01 & 0x400 ? 'Run' : 'Stop', fd01 & 0x400 ? 'on' : '');
        badge('mon-direction', fd01 & 0x200 ? 'Reverse' : 'Forward');
        badge('mon-tripped', fd01 & 0x2 ? 'Tripped' : 'Not tripped', fd01 & 0x2 ? 'bad' : '');
        badge('mon-alarm', fd01 & 0x4 ? 'Alarm' : 'No alarm', fd01 & 0x4 ? 'warn' : '');
        badge('mon-ready', fd01 & 0x4000 ? 'Ready' : 'Not ready', fd01 & 0x4000 ? 'on' : '');
        setText('mon-fd01', hex(fd01));
      }
      for (const [n, id] of MON_VALUES) setText('mon-' + id, r[n] == null ? '-' : fmtValue(reg(n), r[n]));
      if (r.FC90 != null) {
        setText('mon-trip', TRIPS.get(r.FC90) || 'unknown trip code');
        setText('mon-trip-code', r.FC90 ? `(code ${r.FC90})` : '');
        $('mon-trip').className = r.FC90 ? 'bad' : '';
      }
      if (r.FC91 != null) {
        const on = ALARMS.filter((_, i) => r.FC91 & (1 << i));
        setText('mon-alarms', on.length ? on.join(', ') : 'none');
        ALARMS.forEach((_, i) => $('mon-alarm-' + i).classList.toggle('warn', !!(r.FC91 & (1 << i))));
      }
      if (r.FE06 != null) { setText('mon-fe06', hex(r.FE06)); INPUTS.forEach((t, i) => $('mon-in-' + t).classList.toggle('on', !!(r.FE06 & (1 << i)))); }
      if (r.FE07 != null) { setText('mon-fe07', hex(r.FE07)); OUTPUTS.forEach((t, i) => $('mon-out-' + t).classList.toggle('on', !!(r.FE07 & (1 << i)))); }
      for (const [k] of LEDS) {
        const v = String((m.leds || {})[k] || 'off');
        setText('mon-led-' + k, v);
        const color = /green/.test(v) ? 'green' : /red/.test(v) ? 'red' : /amber|orange|yellow/.test(v) ? 'amber' : 'off';
        $('mon-led-' + k + '-lamp').className = color + (/blink|flash/.test(v) ? ' blink' : '');
      }
      setText('mon-link', m.link || '-');
      setText('mon-model', (m.model || 'unknown').toUpperCase());
      setText('mon-protocol', m.protocol === 'ethernetip' ? 'EtherNet/IP' : m.protocol === 'modbus' ? 'Modbus TCP' : '-');
      setText('mon-age', m.age_ms == null ? '-' : `${m.age_ms} ms`);
      if (m.age_ms > 2000) status(`The drive data is ${secs(m.age_ms)} s old (drive link ${m.link}).`, true);
    });
  }

  // ---------------------------------------------------------------------------------------------------
  // Drive parameters
  const GROUPS = [
    ['fundamental', 'Fundamental (0xxx)', (r) => r.number[0] === '0' && !/^f\d{3}$/.test(r.title)],
    ['extended', 'Extended (Fxxx)', (r) => /^f\d{3}$/.test(r.title)],
    ['communication', 'Communication (Cxxx)', (r) => r.number[0] === 'C'],
    ['commands', 'Commands (FAxx)', (r) => r.number.startsWith('FA')],
    ['monitors', 'Monitors (FB-FExx)', (r) => /^F[B-E]/.test(r.number)],
  ];
  function driveParameters(page, arg) {
    const group = GROUPS.find((g) => g[0] === arg) || GROUPS[0];
    const status = statusLine(page);
    const rows = [...REGS.values()].filter((r) => group[2](r) && onModel(r));
    const values = new Map();
    const body = el('tbody');
    for (const r of rows) {
      const editable = r.access === 'rw';
      body.append(el('tr', { id: 'par-' + r.number },
        el('td', { class: 'mono', text: r.title }), el('td', { class: 'mono', text: r.number }),
        el('td', { class: 'fn', text: shortFn(r), title: r.fn }), el('td', { id: `par-${r.number}-value`, class: 'num', text: '...' }),
        el('td', { class: 'range', text: r.unit === 'char' ? 'ASCII' : fmtRange(r) }),
        el('td', {}, editable
          ? el('button', { id: `par-${r.number}-edit`, type: 'button', class: 'small', text: 'Edit',
            onclick: () => editRegister(r, values.get(r.number), refresh) })
          : el('span', { class: 'muted small', text: r.access === 'option' ? 'set by the card' : 'read only' }))));
    }
    page.append(el('div', { class: 'split' },
      el('nav', { class: 'groups' }, GROUPS.map(([id, label]) => el('a', { id: 'grp-' + id, href: `#/drive-parameters/${id}`,
        class: id === group[0] ? 'active' : null, text: label }))),
      el('div', { class: 'grow' },
        el('p', { class: 'muted' }, `${rows.length} registers; ranges for ${model === 'vf-s15' ? 'VF-S15' : 'VF-MB1'}. `,
          el('button', { id: 'par-refresh', type: 'button', class: 'small ghost', text: 'Refresh', onclick: () => refresh() })),
        el('table', { class: 'params' },
          el('thead', {}, el('tr', {}, ['Title', 'No.', 'Function', 'Value', 'Range', ''].map((h) => el('th', { text: h, class: h === 'Function' ? 'fn' : null })))), body))));
    async function refresh() {
      try {
        const got = await readRegisters(rows.map((r) => r.number));
        for (const r of rows) {
          const v = got.get(r.number);
          const cell = $(`par-${r.number}-value`);
          if (!cell) return;
          if (v && v.value != null) { values.set(r.number, v.value); cell.textContent = fmtValue(r, v.value); cell.title = hex(v.value); cell.classList.remove('error'); } else {
            cell.textContent = 'error';
            cell.title = (v && v.error) || 'no answer';
            cell.classList.add('error');
          }
        }
        status('');
      } catch (x) { status(describe(x), true); throw x; }
    }
    if (group[0] === 'monitors' || group[0] === 'commands') poll(1000, refresh); else refresh();
  }

  // ---------------------------------------------------------------------------------------------------
  // Network parameters
  function networkPage(page) {
    const status = statusLine(page);
    const box = el('div', { class: 'cards' });
    page.append(box, el('p', {}, el('button', { id: 'net-reset', type: 'button', class: 'warn', text: 'Apply (communication reset)',
      onclick: () => openDialog({
        title: 'Communication reset',
        info: 'The card restarts its network side with the configuration held in the inverter (f899 = 1). ' +
          'Every connection drops, and the page may lose the card for a few seconds. Continue?',
        okText: 'Reset',
        action: () => api('POST', '/api/network/reset', { confirm: true }),
        done: () => toast('Communication reset requested.'),
      }) }), ' ', el('span', { class: 'muted', text: 'Most settings take effect after the communication reset.' })));
    const enumText = (number, w) => { const o = options(reg(number)); return `${(o && o.get(w)) || w}`; };
    const edit = (fn) => el('button', { type: 'button', class: 'small', text: 'Edit', onclick: fn });
    async function load() {
      let n;
      try { n = await api('GET', '/api/network'); } catch (x) { status(describe(x), true); return; }
      status('');
      const c = n.config;
      const a = n.actual;
      const row = (id, label, no, value, button) => el('tr', { id: 'net-' + id },
        el('td', { text: label }), el('td', { class: 'mono', text: no }), el('td', { id: `net-${id}-value`, text: value }),
        button === undefined ? null : el('td', {}, button));
      const enumRow = (id, label, number, w) => row(id, label, number.toLowerCase(), enumText(number, w),
        edit(() => editRegister(reg(number), w, load)));
      const addrRow = (id, label, first, words) => row(id, label, `c${first}-c${first + 3}`, dotted(words),
        edit(() => editAddress(label, first, words, load)));
      box.replaceChildren(
        section('Configuration', table(['Setting', 'Parameter', 'Value', ''], [
          enumRow('protocol', 'Protocol', 'C500', c.c500),
          enumRow('rate', 'Rate setting', 'C501', c.c501),
          enumRow('ip-mode', 'IP mode', 'C504', c.c504),
          addrRow('ip', 'IP address', 505, c.ip),
          addrRow('mask', 'Subnet mask', 509, c.netmask),
          addrRow('gateway', 'Gateway', 513, c.gateway),
          row('name', 'Device name', 'c081-c096', c.device_name || '(none)', edit(() => editDeviceName(c.device_name || '', load))),
          row('web', 'Web server', 'c554', enumText('C554', c.c554), ''),
        ], 'settings')),
        section('Actual', table(['Item', 'Parameter', 'Value'], [
          row('mac', 'MAC address', 'c517-c522', n.mac),
          row('actual-ip', 'IP address', 'c524-c527', dotted(a.ip)),
          row('actual-mask', 'Subnet mask', 'c528-c531', dotted(a.netmask)),
          row('actual-gateway', 'Gateway', 'c532-c535', dotted(a.gateway)),
          row('rate-l', 'Actual rate, port L', 'c502', enumText('C502', a.c502)),
          row('rate-r', 'Actual rate, port R', 'c503', enumText('C503', a.c503)),
          row('error', 'Ethernet error', 'c536', enumText('C536', a.c536)),
        ], 'settings')));
    }
    load();
  }

  // ---------------------------------------------------------------------------------------------------
  // Scanner words (Modbus IO scanning and the EtherNet/IP assemblies 102/152 use the same c001-c006 and
  // c021-c026 menus)
  function scannerTables(prefix, menus, live, reload, names) {
    const part = (title, first, words, liveWords) => section(title, table(['Word', 'Parameter', 'Config', 'Live', ''],
      words.map((w, i) => {
        const r = reg(cnum(first + i));
        const t = menuTarget((options(r) || new Map()).get(w) || '');
        const lw = liveWords ? liveWords[i] : null;
        return el('tr', { id: `${prefix}-${r.title}` },
          el('td', { text: `${i + 1}` }), el('td', { class: 'mono', text: r.title }),
          el('td', { id: `${prefix}-${r.title}-config`, text: menuLabel(r, w), title: t ? t.fn : null }),
          el('td', { id: `${prefix}-${r.title}-live`, class: 'num', text: liveText(t, lw) }),
          el('td', {}, el('button', { type: 'button', class: 'small', text: 'Edit', onclick: () => editRegister(r, w, reload) })));
      }), 'settings'));
    return [part(names[0], 1, menus.c001_c006, live && live.command), part(names[1], 21, menus.c021_c026, live && live.monitor)];
  }
  function modbusScanner(page) {
    const status = statusLine(page);
    const box = el('div', { class: 'cards' });
    page.append(box);
    let shownConfig = '';
    const load = async () => {
      let s;
      try { s = await api('GET', '/api/modbus-scanner'); } catch (x) { status(describe(x), true); throw x; }
      status('');
      const key = JSON.stringify([s.menus, s.master, s.c523, s.loss_action]);
      if (key === shownConfig) {   // only the live words changed: keep the DOM (and the buttons) as they are
        s.menus.c001_c006.forEach((w, i) => updateLive('mb', cnum(1 + i), w, s.live.command[i]));
        s.menus.c021_c026.forEach((w, i) => updateLive('mb', cnum(21 + i), w, s.live.monitor[i]));
        return;
      }
      shownConfig = key;
      const m = s.master;
      const c523 = reg('C523');
      box.replaceChildren(
        section('IO scanning', table(['Setting', 'Parameter', 'Value', ''], [
          el('tr', {}, el('td', { text: 'IO scan active' }), el('td', { class: 'mono', text: 'c604' }),
            el('td', { id: 'mb-c604-value', text: `${(options(reg('C604')) || new Map()).get(m.c604) || m.c604}` }),
            el('td', {}, el('button', { type: 'button', class: 'small', text: 'Edit', onclick: () => editRegister(reg('C604'), m.c604, reload) }))),
          el('tr', {}, el('td', { text: 'IP master (0.0.0.0 = any)' }), el('td', { class: 'mono', text: 'c600-c603' }),
            el('td', { id: 'mb-master-value', text: dotted(m.c600_c603) }),
            el('td', {}, el('button', { type: 'button', class: 'small', text: 'Edit', onclick: () => editAddress('IP master', 600, m.c600_c603, reload) }))),
          el('tr', {}, el('td', { text: 'Network time-out' }), el('td', { class: 'mono', text: 'c523' }),
            el('td', { id: 'mb-c523-value', text: s.c523 ? fmtValue(c523, s.c523) : 'disabled' }),
            el('td', {}, el('button', { type: 'button', class: 'small', text: 'Edit', onclick: () => editRegister(c523, s.c523, reload) }))),
          el('tr', {}, el('td', { text: 'Communication loss action in force' }), el('td', { class: 'mono', text: 'c101' }),
            el('td', { id: 'mb-loss-value', text: s.loss_action ? 'yes' : 'no', class: s.loss_action ? 'error' : null }), el('td')),
        ], 'settings')),
        ...scannerTables('mb', s.menus, s.live, reload, ['Output words (master \u2192 drive, c001-c006)', 'Input words (drive \u2192 master, c021-c026)']));
    };
    const reload = () => { shownConfig = ''; return load().catch(() => {}); };
    poll(1000, load);
  }
  const liveText = (t, lw) => (lw == null || !t ? '-' : fmtValue(t, lw));
  function updateLive(prefix, number, w, lw) {
    const r = reg(number);
    setText(`${prefix}-${r.title}-live`, liveText(menuTarget((options(r) || new Map()).get(w) || ''), lw));
  }
  function eipScanner(page) {
    const status = statusLine(page);
    const conns = el('div');
    const map = el('div', { class: 'cards' });
    page.append(section('Connections', conns), map);
    let menus = null;
    const loadMenus = async () => {
      const nums = [1, 2, 3, 4, 5, 6, 21, 22, 23, 24, 25, 26].map(cnum);
      const v = await readRegisters(nums);
      const w = (n) => (v.get(n) && v.get(n).value != null ? v.get(n).value : 0);
      menus = { c001_c006: nums.slice(0, 6).map(w), c021_c026: nums.slice(6).map(w) };
    };
    const ms = (us) => (us / 1000).toFixed(us % 1000 ? 1 : 0);
    let shown = false;
    const load = async () => {
      let s;
      try {
        if (!menus) await loadMenus();
        s = await api('GET', '/api/eip-scanner');
      } catch (x) { status(describe(x), true); throw x; }
      status('');
      const list = s.connections || [];
      conns.replaceChildren(list.length ? table(
        ['Originator', 'Type', 'O\u2192T', 'T\u2192O', 'API O\u2192T / T\u2192O', 'Mode', 'Timeout', 'Multicast'],
        list.map((c, i) => el('tr', { id: 'eip-conn-' + i },
          el('td', { class: 'mono', text: c.originator }), el('td', { text: c.kind }),
          el('td', { text: c.class === 1 ? `assembly ${c.o_to_t}` : '-' }),
          el('td', { text: c.class === 1 ? `assembly ${c.t_to_o}` : '-' }),
          el('td', { class: 'num', text: `${ms(c.o_to_t_api_us)} / ${ms(c.t_to_o_api_us)} ms` }),
          el('td', { text: c.run ? 'run' : 'idle', class: c.run ? 'ok' : 'warn' }),
          el('td', { class: 'num', text: `${c.timeout_ms} ms` }), el('td', { text: c.multicast ? 'yes' : 'no' }))), 'settings')
        : el('p', { id: 'eip-none', class: 'muted', text: 'No EtherNet/IP connection.' }));
      if (!shown) {
        shown = true;
        map.replaceChildren(...scannerTables('eip', menus, s.live, reload,
          ['Assembly 102: output words (scanner \u2192 drive, c001-c006)', 'Assembly 152: input words (drive \u2192 scanner, c021-c026)']));
      } else {
        menus.c001_c006.forEach((w, i) => updateLive('eip', cnum(1 + i), w, s.live.command[i]));
        menus.c021_c026.forEach((w, i) => updateLive('eip', cnum(21 + i), w, s.live.monitor[i]));
      }
    };
    const reload = () => { menus = null; shown = false; return load().catch(() => {}); };
    poll(1000, load);
  }

  // ---------------------------------------------------------------------------------------------------
  // Administration
  function administration(page) {
    const current = el('input', { id: 'admin-current', type: 'password', autocomplete: 'off' });
    const currentRow = el('div', { class: 'narrow' }, field('Current write password', current));
    currentRow.hidden = session.level === 'write';
    page.append(el('p', { class: 'muted', text: 'The read password opens the pages; the write password allows changes. ' +
      'Both are "USER" out of the box. At most 32 bytes.' }), currentRow, el('div', { class: 'cards forms' }, ...['read', 'write'].map((which) => {
      const pw = el('input', { id: `admin-${which}-new`, type: 'password', autocomplete: 'new-password' });
      const again = el('input', { id: `admin-${which}-confirm`, type: 'password', autocomplete: 'new-password' });
      const msg = el('p', { id: `admin-${which}-message`, role: 'alert' });
      const form = el('form', { id: `admin-${which}`, class: 'card narrow' }, el('h2', { text: `${which === 'read' ? 'Read' : 'Write'} password` }),
        field('New password', pw), field('Again', again), el('button', { id: `admin-${which}-save`, type: 'submit', text: 'Change' }), msg);
      form.addEventListener('submit', async (e) => {
        e.preventDefault();
        msg.className = 'error';
        try {
          if (!pw.value) throw new UserError('Enter the new password.');
          if (new TextEncoder().encode(pw.value).length > 32) throw new UserError('At most 32 bytes.');
          if (pw.value !== again.value) throw new UserError('The two entries differ.');
          if (session.level !== 'write') await elevate(current.value);
          currentRow.hidden = true;
          await api('POST', '/api/passwords', { which, password: pw.value });
          pw.value = again.value = '';
          msg.className = 'ok';
          msg.textContent = `The ${which} password has been changed.`;
          refreshSession();
        } catch (x) {
          if (x.status === 403) { applySession({ level: 'read', defaults: session.defaults }); currentRow.hidden = false; }
          msg.textContent = describe(x);
        }
      });
      return form;
    })));
  }

  // ---------------------------------------------------------------------------------------------------
  // TCP/IP statistics: whatever keys arrive, as tables
  function kvTables(obj, title) {
    const scalars = Object.entries(obj).filter(([, v]) => v === null || typeof v !== 'object');
    const nested = Object.entries(obj).filter(([, v]) => v !== null && typeof v === 'object');
    const out = [];
    if (scalars.length) {
      out.push(el('div', { class: 'kv' }, title ? el('h3', { text: title }) : null,
        el('table', {}, el('tbody', {}, scalars.map(([k, v]) => el('tr', {}, el('th', { text: k }),
          el('td', { class: 'num', text: typeof v === 'boolean' ? (v ? 'yes' : 'no') : String(v) })))))));
    }
    for (const [k, v] of nested) out.push(...kvTables(v, title ? `${title}.${k}` : k));
    return out;
  }
  // LLDP neighbours heard on the card's ports (docs/network.md "LLDP"), then the LLDP counters
  function lldpSection(lldp) {
    const { neighbours = [], ...counters } = lldp;
    return section('LLDP neighbours', neighbours.length ? table(['Port', 'Chassis ID', 'Port ID', 'System name',
      'Management address', 'TTL'], neighbours.map((n, i) => el('tr', { id: `lldp-${i}` },
      el('td', { text: n.port }), el('td', { class: 'mono', text: n.chassis }), el('td', { class: 'mono', text: n.port_id }),
      el('td', { text: n.name }), el('td', { class: 'mono', text: n.mgmt || '-' }), el('td', { class: 'num', text: `${n.ttl} s` }))))
      : el('p', { id: 'lldp-none', class: 'muted', text: 'No LLDP neighbour.' }), el('div', { class: 'kvs' }, kvTables(counters, '')));
  }
  function statistics(page) {
    const status = statusLine(page);
    const box = el('div');
    page.append(box);
    poll(2000, async () => {
      let s;
      try { s = await api('GET', '/api/statistics'); } catch (x) { status(describe(x), true); throw x; }
      status('');
      const ports = (s.ports || []).map((p) => section(`Port ${p.port}`,
        el('p', { id: `stat-port-${p.port}`, class: p.link ? 'ok' : 'muted',
          text: p.link ? `link up, ${p.speed} Mbit/s, ${p.full_duplex ? 'full' : 'half'} duplex` : 'no link' }),
        el('div', { class: 'kvs' }, kvTables(p.counters || {}, ''))));
      const rest = Object.fromEntries(Object.entries(s).filter(([k]) => !['ports', 'lwip', 'ring', 'lldp'].includes(k)));
      box.replaceChildren(el('div', { class: 'cards' }, ports),
        s.ring ? section('Ring (DLR)', el('p', { id: 'stat-ring', class: s.ring.network_status === 'normal' ? 'ok' : 'warn',
          text: `${s.ring.topology}, ${s.ring.network_status}, supervisor ${s.ring.supervisor}` }),
          el('div', { class: 'kvs' }, kvTables(s.ring, ''))) : '',
        s.lldp ? lldpSection(s.lldp) : '',
        s.lwip ? section('lwIP', el('div', { class: 'kvs' }, kvTables(s.lwip, ''))) : '',
        Object.keys(rest).length ? section('Other', el('div', { class: 'kvs' }, kvTables(rest, ''))) : '');
    });
  }

  // ---------------------------------------------------------------------------------------------------
  // Start
  buildMenus();
  window.addEventListener('hashchange', route);
  (async () => {
    try {
      applySession(await api('GET', '/api/session'));
    } catch (x) {
      showLogin(describe(x));
      return;
    }
    if (session.level === 'none' || !session.csrf) showLogin();
    else enterApp();
  })();
})();
