#!/usr/bin/env node
// A throwaway stand-in for the card's web server, for developing the page and its browser test while the
// firmware's HTTP server does not exist yet (docs/web.md "The page"). Not the firmware and not a
// reference: it serves web/assets/ plus registers.js (generated from registers.csv on start) and keeps a
// fake, in-memory implementation of the docs/web.md JSON API: sessions, CSRF, the password back-off and
// a crude drive whose output frequency ramps towards FA07 while FA06 has run and both priority bits set.
//
//   node tools/web/mock_api.js [--host 127.0.0.1] [--port 8088] [--model vf-mb1|vf-s15] [--verbose]
//
// Prints "ready http=HOST:PORT" once listening (port 0 picks a free one), like the firmware's ready line.
// Dev aids beyond the API: GET /mock/set?FC90=27&FC91=2048 sets monitor words (a trip, alarms) by hand.
'use strict';
const http = require('http');
const fs = require('fs');
const path = require('path');
const crypto = require('crypto');
const vm = require('vm');
const { execFileSync } = require('child_process');

const ROOT = path.resolve(__dirname, '..', '..');
const args = Object.fromEntries(process.argv.slice(2).map((a) => {
  const m = /^--([^=]+)(?:=(.*))?$/.exec(a);
  if (!m) { console.error(`mock_api: unknown argument ${a}`); process.exit(2); }
  return [m[1], m[2] === undefined ? true : m[2]];
}));
const HOST = args.host || '127.0.0.1';
const PORT = args.port === undefined ? 8088 : Number(args.port);
const MODEL = args.model || 'vf-mb1';
const ASSETS = path.join(ROOT, 'web', 'assets');

// The register table, from the same generator the build uses.
const registersJs = execFileSync('/usr/bin/python3', [path.join(ROOT, 'tools/web/gen_register_js.py'),
  '--csv', path.join(ROOT, 'hal/host/inverter_sim/registers.csv'), '--out', '-'], { encoding: 'utf8' });
const sandbox = {};
vm.runInNewContext(registersJs.replace('var IPE_REGISTERS', 'this.IPE_REGISTERS'), sandbox);
const TABLE = new Map();
const BY_TITLE = new Map();
for (const r of sandbox.IPE_REGISTERS) {
  const s15 = MODEL === 'vf-s15' && r[7] != null;
  const info = { number: r[0], title: r[1], fn: r[2], access: r[3], min: s15 ? r[7] : r[4], max: s15 ? r[8] : r[5],
    def: s15 ? r[9] : r[6], wdr: !!r[11] };
  TABLE.set(info.number, info);
  BY_TITLE.set(info.title, info);
}
const regs = new Map([...TABLE.values()].map((r) => [r.number, r.def & 0xffff]));
const get = (n) => regs.get(n) || 0;
const set = (n, v) => regs.set(n, v & 0xffff);
// A plausible card: actual address, MAC, rates, a device name.
[192, 168, 1, 50, 255, 255, 255, 0, 192, 168, 1, 1].forEach((v, i) => set('C' + (524 + i), v));
[0x02, 0x00, 0x5e, 0x10, 0x20, 0x30].forEach((v, i) => set('C' + (517 + i), v));
set('C502', 3);
[...'IPE002Z'].forEach((ch, i) => set('C0' + (81 + i), ch.charCodeAt(0)));

// ---------------------------------------------------------------------------------------------------
// The drive: ramps FD00 towards FA07 at fh per acc (0.1 s) while FA06 runs it with both priorities.
let running = false;
let lastTick = Date.now();
setInterval(() => {
  const now = Date.now();
  const dt = (now - lastTick) / 1000;
  lastTick = now;
  const fa06 = get('FA06');
  const tripped = get('FC90') !== 0;
  const command = (fa06 & 0x8000) && (fa06 & 0x0400) && !tripped;
  const target = command && (fa06 & 0x4000) ? Math.min(get('FA07'), get('0012')) : 0;
  const fh = get('0011');
  const out = get('FD00');
  let next = out;
  if (out < target) next = Math.min(target, out + fh * dt / (Math.max(1, get('0009')) / 10));
  else if (out > target) next = Math.max(target, out - fh * dt / (Math.max(1, get('0010')) / 10));
  next = Math.round(next);
  running = command || next > 0;
  set('FD00', next);
  set('FE00', next);
  set('FE02', target);
  set('FE03', running ? 2500 + Math.round(next / 5) : 0);
  set('FE05', Math.min(10000, Math.round(next * 10000 / Math.max(1, get('0014')))));
  const torque = !running ? 0 : next < target ? 9000 : next > target ? -4000 : 3000;
  set('FE18', torque);
  set('FD18', torque);
  let fd01 = 0x4000 | 0x2000;
  if (running) fd01 |= 0x0400;
  if (fa06 & 0x0200) fd01 |= 0x0200;
  if (tripped) fd01 = (fd01 | 0x0002) & ~0x2000;
  if (get('FC91')) fd01 |= 0x0004;
  set('FD01', fd01);
  set('FE01', fd01);
  set('FE07', (running ? 0x0001 : 0) | (tripped ? 0x0004 : 0));
}, 50);

// ---------------------------------------------------------------------------------------------------
// Sessions, CSRF, passwords and the back-off (docs/web.md "Access")
const passwords = { read: 'USER', write: 'USER' };
const sessions = new Map();   // id -> {csrf, level, used, changed}
const IDLE_MS = 15 * 60 * 1000;
const WRITE_MS = 10 * 60 * 1000;
const backoff = { failures: 0, until: 0 };
const rand = () => crypto.randomBytes(16).toString('hex');
function sessionOf(req) {
  const m = /(?:^|;\s*)ipe_session=([0-9a-f]{32})/.exec(req.headers.cookie || '');
  const s = m && sessions.get(m[1]);
  if (!s) return null;
  const now = Date.now();
  if (now - s.used > IDLE_MS) { sessions.delete(m[1]); return null; }
  if (s.level === 'write' && now - s.changed > WRITE_MS) s.level = 'read';
  s.used = now;
  return s;
}
// null when the attempt may go on; else [status, body, headers] of the refusal.
function backoffRefusal() {
  const left = backoff.until - Date.now();
  if (left <= 0) return null;
  return [429, { error: 'too many failed attempts', retry_after_ms: left }, { 'Retry-After': String(Math.ceil(left / 1000)) }];
}
function passwordFailed() {
  backoff.failures++;
  if (backoff.failures < 3) return [401, { error: 'wrong password' }];
  const wait = Math.min(60000, 1000 * 2 ** (backoff.failures - 3));
  backoff.until = Date.now() + wait;
  return [401, { error: 'wrong password', retry_after_ms: wait }];
}
const defaults = () => passwords.read === 'USER' || passwords.write === 'USER';

// ---------------------------------------------------------------------------------------------------
// Register access as the card would answer it
function writeRegister(number, value) {
  const r = TABLE.get(number);
  if (!r) return [404, { error: 'no such register' }];
  if (r.access !== 'rw') return [409, { error: 'read only' }];
  if (!Number.isInteger(value) || value < 0 || value > 0xffff) return [422, { error: 'out of range' }];
  const v = r.min < 0 && value >= 0x8000 ? value - 0x10000 : value;
  if (v < r.min || v > r.max) return [422, { error: `out of range (${r.min}..${r.max})` }];
  if (!r.wdr && running) return [409, { error: 'not while the drive runs' }];
  set(number, value);
  return [200, { number, value }];
}
// The register a scanner menu entry names (c001-c006 / c021-c026), from the function text.
function menuTarget(number) {
  const r = TABLE.get(number);
  const m = /menu: ([^;)]*)/.exec(r.fn);
  const code = get(number);
  for (const part of m[1].split(', ')) {
    const p = /^(\d+)(?:-(\d+))? (\S+)$/.exec(part);
    if (!p) continue;
    const span = /^(F[A-E])(\d\d)-\1(\d\d)$/.exec(p[3]);
    if (p[2] && span && code >= +p[1] && code <= +p[2]) return span[1] + String(+span[2] + code - +p[1]).padStart(2, '0');
    if (!p[2] && +p[1] === code) return TABLE.has(p[3]) ? p[3] : BY_TITLE.has(p[3]) ? BY_TITLE.get(p[3]).number : null;
  }
  return null;
}
const scannerWords = (first) => [0, 1, 2, 3, 4, 5].map((i) => {
  const t = menuTarget('C' + String(first + i).padStart(3, '0'));
  return t ? get(t) : 0;
});
const range = (prefix, first, count) => Array.from({ length: count }, (_, i) => get(prefix + String(first + i).padStart(3, '0')));
const started = Date.now();
const counter = (perSecond) => Math.floor((Date.now() - started) / 1000 * perSecond);

const ROUTES = {
  'GET /api/session': (req, s) => [200, { level: s ? s.level : 'none', defaults: defaults() }],
  'POST /api/login': (req, s, body) => {
    const refused = backoffRefusal();
    if (refused) return refused;
    if (!body || body.password !== passwords.read) return passwordFailed();
    backoff.failures = 0;
    if (sessions.size >= 8) sessions.delete([...sessions.entries()].sort((a, b) => a[1].used - b[1].used)[0][0]);
    const id = rand();
    const csrf = rand();
    sessions.set(id, { csrf, level: 'read', used: Date.now(), changed: Date.now() });
    return [200, { level: 'read', csrf, defaults: defaults() },
      { 'Set-Cookie': `ipe_session=${id}; Path=/; HttpOnly; SameSite=Strict` }];
  },
  'POST /api/logout': (req, s) => { for (const [k, v] of sessions) if (v === s) sessions.delete(k); return [204]; },
  'POST /api/elevate': (req, s, body) => {
    const refused = backoffRefusal();
    if (refused) return refused;
    if (!body || body.password !== passwords.write) return passwordFailed();
    backoff.failures = 0;
    s.level = 'write';
    s.changed = Date.now();
    return [200, { level: 'write' }];
  },
  'POST /api/passwords': (req, s, body) => {
    if (!body || !['read', 'write'].includes(body.which)) return [400, { error: 'which must be read or write' }];
    const p = body.password;
    if (typeof p !== 'string' || !p || Buffer.byteLength(p) > 32) return [400, { error: 'password empty or longer than 32 bytes' }];
    passwords[body.which] = p;
    s.changed = Date.now();
    return [204];
  },
  'GET /api/monitor': () => [200, {
    link: 'ok', model: MODEL, age_ms: 40 + Math.floor(Math.random() * 200), protocol: get('C500') ? 'ethernetip' : 'modbus',
    registers: Object.fromEntries(['FD00', 'FD01', 'FE02', 'FE03', 'FE05', 'FE18', 'FC90', 'FC91', 'FE06', 'FE07'].map((n) => [n, get(n)])),
    leds: { ms: get('FC90') ? 'red-flashing' : 'green', ns: 'green', lnk_l: 'green-flashing', lnk_r: 'off' },
  }],
  'GET /api/registers': (req, s, body, query) => {
    const numbers = (query.get('numbers') || '').split(',').filter(Boolean);
    if (!numbers.length || numbers.length > 32) return [400, { error: 'give 1 to 32 numbers' }];
    return [200, { values: numbers.map((n) => (TABLE.has(n) ? { number: n, value: get(n) } : { number: n, error: 'no such register' })) }];
  },
  'POST /api/registers': (req, s, body) => {
    if (!body || typeof body.number !== 'string') return [400, { error: 'number and value required' }];
    s.changed = Date.now();
    return writeRegister(body.number, body.value);
  },
  'GET /api/network': () => {
    const name = range('C', 81, 16);
    const end = name.indexOf(0);
    return [200, {
      mac: range('C', 517, 6).map((b) => b.toString(16).padStart(2, '0')).join(':'),
      config: { c500: get('C500'), c501: get('C501'), c504: get('C504'), c505_c516: range('C', 505, 12), c554: get('C554'),
        device_name: String.fromCharCode(...name.slice(0, end < 0 ? 16 : end)) },
      actual: { c524_c535: range('C', 524, 12), c502: get('C502'), c503: get('C503'), c536: get('C536') },
    }];
  },
  'POST /api/network/reset': (req, s, body) => {
    if (!body || body.confirm !== true) return [400, { error: 'confirm required' }];
    return [202, {}];
  },
  'GET /api/modbus-scanner': () => [200, {
    menus: { c001_c006: range('C', 1, 6), c021_c026: range('C', 21, 6) },
    master: { c600_c603: range('C', 600, 4), c604: get('C604') }, c523: get('C523'),
    live: { command: scannerWords(1), monitor: scannerWords(21) }, loss_action: false,
  }],
  'GET /api/eip-scanner': () => [200, {
    connections: [{ originator: '192.168.1.10', o_to_t: 102, t_to_o: 152, o_to_t_rpi_us: 10000, t_to_o_rpi_us: 10000,
      o_to_t_api_us: 10000, t_to_o_api_us: 10000, run: true, timeout_ms: 40, multicast: false, class: 1 }],
    live: { command: scannerWords(1), monitor: scannerWords(21) },
  }],
  'GET /api/statistics': () => [200, {
    ports: [
      { port: 'L', link: true, speed: 100, full_duplex: true,
        counters: { rx_frames: counter(55), tx_frames: counter(48), rx_bytes: counter(5200), tx_bytes: counter(4100), rx_errors: 0, crc_errors: 0, collisions: 0 } },
      { port: 'R', link: false, speed: 10, full_duplex: false,
        counters: { rx_frames: 0, tx_frames: 0, rx_bytes: 0, tx_bytes: 0, rx_errors: 0, crc_errors: 0, collisions: 0 } },
    ],
    lwip: {
      link: { xmit: counter(48), recv: counter(55), drop: 0, err: 0 },
      ip: { xmit: counter(47), recv: counter(54), drop: 0, chkerr: 0 },
      tcp: { xmit: counter(40), recv: counter(42), drop: 0, rexmit: 0, memerr: 0 },
      udp: { xmit: counter(6), recv: counter(9), drop: 0 },
      mem: { heap_used: 5120, heap_max: 8192, heap_err: 0 },
    },
  }],
};
// Which calls need what: login/session need nothing; the rest a session; changes CSRF and write level.
const NEEDS_WRITE = new Set(['POST /api/passwords', 'POST /api/registers', 'POST /api/network/reset']);

function send(res, status, body, headers) {
  const text = body === undefined ? '' : JSON.stringify(body);
  res.writeHead(status, Object.assign(text ? { 'Content-Type': 'application/json' } : {}, { 'Cache-Control': 'no-store' }, headers || {}));
  res.end(text);
}
const TYPES = { '.html': 'text/html; charset=utf-8', '.css': 'text/css; charset=utf-8', '.js': 'text/javascript; charset=utf-8' };

const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://card');
  const chunks = [];
  req.on('data', (c) => chunks.push(c));
  req.on('end', () => {
    if (args.verbose) console.log(`${req.method} ${req.url}`);
    if (url.pathname.startsWith('/mock/set')) {
      for (const [k, v] of url.searchParams) set(k.toUpperCase(), Number(v));
      return send(res, 200, { ok: true });
    }
    if (!url.pathname.startsWith('/api/')) {
      if (req.method !== 'GET') return send(res, 405, { error: 'method not allowed' });
      const name = url.pathname === '/' ? 'index.html' : url.pathname.slice(1);
      if (name === 'registers.js') {
        res.writeHead(200, { 'Content-Type': TYPES['.js'] });
        return res.end(registersJs);
      }
      const file = path.join(ASSETS, path.basename(name));
      if (name.includes('/') || !fs.existsSync(file)) return send(res, 404, { error: 'not found' });
      res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
      return res.end(fs.readFileSync(file));
    }
    const key = `${req.method} ${url.pathname}`;
    const handler = ROUTES[key];
    if (!handler) return send(res, 404, { error: 'no such call' });
    const s = sessionOf(req);
    let body = null;
    if (req.method === 'POST' && chunks.length) {
      try { body = JSON.parse(Buffer.concat(chunks).toString('utf8')); } catch (e) { return send(res, 400, { error: 'bad JSON' }); }
    }
    if (key !== 'GET /api/session' && key !== 'POST /api/login') {
      if (!s) return send(res, 401, { error: 'no session' });
      if (req.method === 'POST' && req.headers['x-csrf-token'] !== s.csrf) return send(res, 403, { error: 'CSRF token missing or wrong' });
      if (NEEDS_WRITE.has(key) && s.level !== 'write') return send(res, 403, { error: 'write password required' });
    }
    const [status, answer, headers] = handler(req, s, body, url.searchParams);
    send(res, status, answer, headers);
  });
});
server.listen(PORT, HOST, () => {
  const a = server.address();
  console.log(`ready http=${a.address}:${a.port} model=${MODEL}`);
});
process.on('SIGTERM', () => process.exit(0));
process.on('SIGINT', () => process.exit(0));
