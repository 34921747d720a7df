#!/usr/bin/env node
// The card's page in a real browser (Debian's chromium driven by playwright-core), against the card's web
// server: login, the drive monitor following a running drive, a
// parameter change with the write password checked in the inverter, a wrong write password and a
// refusal shown, every menu visited with a screenshot, and the passwords changed in Administration.
//
//   node tests/browser/web_ui.js --url=http://127.0.0.29:8080 [--screenshots=DIR]
//        [--drive=api|modbus:HOST:PORT|control:SOCKET] [--verify=api|modbus:HOST:PORT|control:SOCKET]
//        [--password=USER] [--keep-passwords] [--channels-only]
//
// --drive: how the test runs the drive (FA07 = 50 Hz, FA06 = 0xC400: run forward with command and
// frequency priority) and stops it at the end: through the card's own API in a second session ("api",
// the default), Modbus TCP with /usr/bin/python3 + pymodbus, or the host firmware's control socket
// (tools/card-ctl, "set fa06 ..."). --verify: how the test reads a register on its own to check what the
// page wrote (default: the --drive channel). Exit status 0 when every check passed; 1 with "FAIL: ..."
// on the first failure (a screenshot failure.png is saved); 2 for a usage error. --channels-only checks
// the two side channels alone (FA07 written through --drive reads back through --verify), no browser.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { execFileSync } = require('child_process');

const ROOT = path.resolve(__dirname, '..', '..');
const opts = {};
for (const a of process.argv.slice(2)) {
  const m = /^--([a-z-]+)(?:=(.*))?$/.exec(a);
  if (!m) usage(`unknown argument ${a}`);
  opts[m[1]] = m[2] === undefined ? true : m[2];
}
function usage(why) {
  console.error(`web_ui.js: ${why}\nusage: node tests/browser/web_ui.js --url=http://HOST:PORT [--screenshots=DIR] ` +
    '[--drive=api|modbus:HOST:PORT|control:SOCKET] [--verify=...] [--password=USER] [--keep-passwords] [--channels-only]');
  process.exit(2);
}
if (!opts.url) usage('--url is required');
const BASE = opts.url.replace(/\/$/, '');
const SHOTS = path.resolve(opts.screenshots || path.join(ROOT, 'build', 'web-screenshots'));
const PASSWORD = opts.password || 'USER';
const DRIVE = opts.drive || 'api';
const VERIFY = opts.verify || DRIVE;
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

let playwright;
try {
  playwright = require('playwright-core');
} catch (e) {
  console.error('FAIL: playwright-core is not installed (npm ci in the repository, or tools/setup)');
  process.exit(1);
}

class Failure extends Error {}
const fail = (message) => { throw new Failure(message); };
const ok = (message) => console.log(`ok: ${message}`);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// ---------------------------------------------------------------------------------------------------
// Side channels: run the drive and read registers without the page.
class ApiChannel {
  constructor() { this.cookie = ''; this.csrf = ''; }
  async call(method, p, body) {
    const headers = { cookie: this.cookie };
    if (method === 'POST') { headers['X-CSRF-Token'] = this.csrf; headers['Content-Type'] = 'application/json'; }
    const res = await fetch(BASE + p, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
    const text = await res.text();
    const setCookie = res.headers.get('set-cookie');
    if (setCookie) this.cookie = setCookie.split(';')[0];
    if (!res.ok) fail(`side channel: ${method} ${p} answered ${res.status} ${text}`);
    return text ? JSON.parse(text) : null;
  }
  async open() {
    if (this.csrf) return;
    this.csrf = (await this.call('POST', '/api/login', { password: PASSWORD })).csrf;
    await this.call('POST', '/api/elevate', { password: PASSWORD });
  }
  async write(number, value) { await this.open(); await this.call('POST', '/api/registers', { number, value }); }
  async read(number) {
    await this.open();
    const v = (await this.call('GET', `/api/registers?numbers=${number}`)).values[0];
    if (v.value == null) fail(`side channel: reading ${number}: ${v.error}`);
    return v.value;
  }
}
class ModbusChannel {
  constructor(endpoint) { [this.host, this.port] = endpoint.split(':'); }
  run(code) {
    const script = `import sys\nfrom pymodbus.client import ModbusTcpClient\n` +
      `c = ModbusTcpClient(sys.argv[1], port=int(sys.argv[2]), timeout=3)\n` +
      `if not c.connect(): sys.exit("cannot connect to Modbus " + sys.argv[1] + ":" + sys.argv[2])\n${code}\nc.close()\n`;
    try {
      return execFileSync('/usr/bin/python3', ['-c', script, this.host, this.port], { encoding: 'utf8', timeout: 15000 }).trim();
    } catch (e) { return fail(`Modbus side channel: ${(e.stderr || e.message).trim()}`); }
  }
  async write(number, value) {
    this.run(`r = c.write_register(0x${number}, ${value}, slave=1)\nif r.isError(): sys.exit("write ${number}: " + str(r))`);
  }
  async read(number) {
    return Number(this.run(`r = c.read_holding_registers(0x${number}, 1, slave=1)\n` +
      `if r.isError(): sys.exit("read ${number}: " + str(r))\nprint(r.registers[0])`));
  }
}
class ControlChannel {
  constructor(socket) { this.socket = socket; }
  ctl(command) {
    try {
      return execFileSync(path.join(ROOT, 'tools', 'card-ctl'), [this.socket, command], { encoding: 'utf8', timeout: 15000 });
    } catch (e) { return fail(`control socket: '${command}': ${(e.stdout || '') + (e.stderr || e.message)}`); }
  }
  async write(number, value) { this.ctl(`set ${number} ${value}`); }
  async read(number) {
    const m = /= (-?\d+) \(0x/.exec(this.ctl(`get ${number}`));
    if (!m) fail(`control socket: cannot read ${number}`);
    return Number(m[1]);
  }
}
function channel(spec) {
  if (spec === 'api') return new ApiChannel();
  if (spec.startsWith('modbus:')) return new ModbusChannel(spec.slice(7));
  if (spec.startsWith('control:')) return new ControlChannel(spec.slice(8));
  return usage(`unknown channel ${spec}`);
}
const drive = channel(DRIVE);
const verify = VERIFY === DRIVE ? drive : channel(VERIFY);

// ---------------------------------------------------------------------------------------------------
// The browser
let browser;
let page;
let userDir;
let shotNumber = 0;
async function shot(name) {
  const file = path.join(SHOTS, `${String(++shotNumber).padStart(2, '0')}-${name}.png`);
  // A modal dialog's backdrop covers the viewport only: those screenshots show the viewport.
  await page.screenshot({ path: file, fullPage: !(await page.isVisible('#edit-dialog')) });
  console.log(`   screenshot ${path.relative(process.cwd(), file)}`);
}
const text = async (selector) => ((await page.textContent(selector)) || '').trim();
async function waitText(selector, test, what, timeout = 8000) {
  const end = Date.now() + timeout;
  let last = '';
  while (Date.now() < end) {
    last = (await page.locator(selector).count()) ? await text(selector) : '(missing)';
    if (test(last)) return last;
    await sleep(100);
  }
  return fail(`${what}: ${selector} shows '${last}' after ${timeout} ms`);
}
const visible = (selector, what, timeout = 8000) =>
  page.waitForSelector(selector, { state: 'visible', timeout }).catch(() => fail(`${what}: ${selector} not visible`));
async function goTo(menu, sub, ready) {
  await page.click(`#menu-${menu}`);
  await page.click(`#nav-${sub}`);
  await visible(ready, `page ${sub}`);
  const banner = await page.isVisible('#defaults-banner');
  return banner;
}
const hz = (s) => { const m = /^(-?\d+\.\d\d) Hz$/.exec(s); return m ? Number(m[1]) : NaN; };

async function main() {
  fs.mkdirSync(SHOTS, { recursive: true });
  userDir = fs.mkdtempSync(path.join(os.tmpdir(), 'ipe-web-ui-'));
  const context = await playwright.chromium.launchPersistentContext(userDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
      '--disable-sync', '--no-first-run'],
    viewport: { width: 1280, height: 860 },
  });
  browser = context;
  page = context.pages()[0] || await context.newPage();
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(e.message));
  // Refused API calls (401, 403, 409, ...) are part of the test; a file the page misses is not.
  page.on('console', (m) => { if (m.type() === 'error' && !/^Failed to load resource/.test(m.text())) pageErrors.push(m.text()); });
  page.on('response', (r) => { if (!new URL(r.url()).pathname.startsWith('/api/') && r.status() >= 400) pageErrors.push(`${r.url()}: ${r.status()}`); });
  const external = [];
  // By origin: the browser drops a default port from the URLs it requests (http://host:80 -> http://host).
  const origin = new URL(BASE).origin;
  page.on('request', (r) => { if (new URL(r.url()).origin !== origin) external.push(r.url()); });

  // Login: a wrong password is refused, the right one opens the drive monitor.
  const res = await page.goto(BASE + '/').catch((e) => fail(`cannot load ${BASE}/: ${e.message}`));
  if (!res.ok()) fail(`GET ${BASE}/ answered ${res.status()}`);
  await visible('#login-password', 'login screen');
  await shot('login');
  // Wrong passwords until the back-off shows (from the third failure on, docs/web.md "Access").
  let backoff = '';
  for (let attempt = 1; attempt <= 4 && !backoff; attempt++) {
    await page.fill('#login-password', 'WRONG');
    await page.click('#login-submit', { timeout: 65000 });
    const t = await waitText('#login-error', (s) => /wrong password|too many/i.test(s), `wrong read password ${attempt}`);
    if (attempt === 1 && !/^wrong password\.$/i.test(t)) fail(`first wrong password: "${t}"`);
    if (/wait \d+ s/i.test(t)) backoff = t;
    await sleep(200);
  }
  if (!backoff) fail('four wrong read passwords showed no back-off wait');
  ok(`wrong read passwords refused, then the back-off shows: "${backoff}"`);
  await shot('login-backoff');
  await page.waitForSelector('#login-submit:not([disabled])', { timeout: 65000 });
  await page.fill('#login-password', PASSWORD);
  await page.click('#login-submit');
  await visible('#mon-output-frequency', 'drive monitor after login');
  if (!(await page.isVisible('#defaults-banner'))) fail('no banner about the default passwords after login');
  ok('logged in with the read password; the default-password banner shows');
  await page.reload();
  await visible('#mon-output-frequency', 'drive monitor after a reload (session kept)');
  if (await page.isVisible('#login-password')) fail('a reload asked for the password again');
  ok('a reload keeps the session (the CSRF token is in sessionStorage)');

  // Drive monitor: polled at least twice a second, and the frequency climbs once the drive runs.
  const f0 = hz(await waitText('#mon-output-frequency', (t) => !Number.isNaN(hz(t)), 'output frequency'));
  let monitorCalls = 0;
  const countMonitor = (r) => { if (r.url().endsWith('/api/monitor')) monitorCalls++; };
  page.on('request', countMonitor);
  await sleep(2000);
  page.off('request', countMonitor);
  if (monitorCalls < 4) fail(`the drive monitor polled /api/monitor ${monitorCalls} times in 2 s (at least 4 expected)`);
  await waitText('#live-text', (t) => t === 'live', 'live indicator');
  ok(`drive monitor: ${f0.toFixed(2)} Hz at rest, ${monitorCalls} polls in 2 s, live indicator on`);
  await shot('drive-monitor-stopped');

  await drive.write('FA07', 5000);
  await drive.write('FA06', 0xC400);
  const readings = [];
  const end = Date.now() + 20000;
  while (Date.now() < end) {
    const f = hz(await text('#mon-output-frequency'));
    if (!Number.isNaN(f) && (readings.length === 0 || f !== readings[readings.length - 1])) readings.push(f);
    if (readings.length >= 4) break;
    await sleep(300);
  }
  const climbing = readings.length >= 4 && readings.every((f, i) => i === 0 || f > readings[i - 1]) && readings[3] > f0;
  if (!climbing) fail(`the output frequency did not climb after the run command: ${readings.join(', ')} Hz`);
  await waitText('#mon-run', (t) => t === 'Run', 'run state');
  ok(`drive started through ${DRIVE}: output frequency ${readings.map((f) => f.toFixed(2)).join(' -> ')} Hz, state Run`);
  await shot('drive-monitor-running');

  // Drive parameters: acc with a wrong, then the right write password; then a refusal (fh while running).
  await goTo('monitoring', 'drive-parameters', '#par-0009-value');
  const acc0 = await waitText('#par-0009-value', (t) => /s$/.test(t), 'acc value');
  const accNew = acc0 === '7.5 s' ? '8.0' : '7.5';
  await shot('drive-parameters');
  await page.click('#par-0009-edit');
  await visible('#edit-dialog', 'edit dialog');
  if (!(await page.isVisible('#edit-password'))) fail('the edit dialog asks no write password at read level');
  await page.fill('#edit-value', accNew);
  await page.fill('#edit-password', 'WRONG');
  await page.click('#edit-ok');
  const refusal = await waitText('#edit-error', (t) => /wrong write password/i.test(t), 'wrong write password');
  ok(`wrong write password refused: "${refusal}"`);
  await shot('edit-wrong-password');
  await page.fill('#edit-password', PASSWORD);
  await page.click('#edit-ok');
  await page.waitForSelector('#edit-dialog', { state: 'hidden', timeout: 8000 })
    .catch(async () => fail(`the edit dialog stayed open: "${await text('#edit-error')}"`));
  await waitText('#par-0009-value', (t) => t === `${accNew} s`, 'acc after the change');
  const accRaw = await verify.read('0009');
  if (accRaw !== Math.round(Number(accNew) * 10)) fail(`acc in the inverter is ${accRaw}, expected ${Number(accNew) * 10}`);
  ok(`acc ${acc0} -> ${accNew} s through the page; the inverter holds ${accRaw} (read through ${VERIFY})`);
  if (await page.isVisible('#edit-password-row')) fail('write level kept no state');

  await page.click('#par-0011-edit');
  await visible('#edit-dialog', 'edit dialog (fh)');
  if (await page.isVisible('#edit-password')) fail('the dialog asks the write password again at write level');
  await page.fill('#edit-value', '80.00');
  await page.click('#edit-ok');
  const refused = await waitText('#edit-error', (t) => t.length > 0, 'refusal of fh while running');
  if (!/409/.test(refused)) fail(`fh while running: expected a 409 refusal, the dialog shows "${refused}"`);
  ok(`fh while running refused, the dialog shows "${refused}"`);
  await shot('edit-refused-while-running');
  await page.click('#edit-cancel');

  await page.click('#grp-extended');
  await waitText('#par-0500-value', (t) => /s$/.test(t), 'extended group (f500)');
  await page.click('#grp-monitors');
  await waitText('#par-FD00-value', (t) => /Hz$/.test(t), 'monitors group (FD00)');
  await shot('drive-parameters-monitors');
  await page.click('#grp-communication');
  await waitText('#par-C500-value', (t) => t.length > 0 && t !== '...', 'communication group (c500)');
  ok('parameter groups: extended, monitors and communication read');

  // Every other page, with the default-password banner on each.
  const pages = [
    ['network', 'network', '#net-ip-value'],
    ['network', 'modbus-scanner', '#mb-c001-config'],
    ['network', 'eip-scanner', '#eip-c001-config'],
    ['network', 'administration', '#admin-read-new'],
    ['diagnostics', 'statistics', '[id^=stat-port-]'],
  ];
  for (const [menu, sub, ready] of pages) {
    const banner = await goTo(menu, sub, ready);
    if (!banner) fail(`no default-password banner on ${sub}`);
    await sleep(300);
    await shot(sub);
  }
  // The statistics page (the last one visited) has the LLDP table; the loopback port has no neighbour.
  await waitText('#lldp-none', (t) => t === 'No LLDP neighbour.', 'LLDP neighbours on the statistics page');
  ok(`pages visited: ${pages.map((p) => p[1]).join(', ')}`);

  await goTo('network', 'network', '#net-ip-value');
  await page.click('#net-reset');
  await visible('#edit-dialog', 'communication reset confirmation');
  if (!/Communication reset/.test(await text('#edit-title'))) fail('the reset button opened no confirmation');
  await shot('network-reset-confirmation');
  await page.click('#edit-cancel');
  ok('network: the communication reset asks for a confirmation');

  await page.click('#menu-toggle');
  if (await page.isVisible('#side-menu')) fail('the toggle button did not hide the left menu');
  await shot('menu-hidden');
  await page.click('#menu-toggle');
  if (!(await page.isVisible('#side-menu'))) fail('the toggle button did not show the left menu again');
  ok('the toggle button hides and shows the left menu');

  // Administration: new passwords; the banner goes; the old read password no longer logs in.
  if (!opts['keep-passwords']) {
    await goTo('network', 'administration', '#admin-read-new');
    for (const [which, pw] of [['read', 'READ-2'], ['write', 'WRITE-2']]) {
      if (await page.isVisible('#admin-current')) await page.fill('#admin-current', PASSWORD);
      await page.fill(`#admin-${which}-new`, pw);
      await page.fill(`#admin-${which}-confirm`, pw);
      await page.click(`#admin-${which}-save`);
      await waitText(`#admin-${which}-message`, (t) => /changed/.test(t), `${which} password change`);
    }
    await page.waitForSelector('#defaults-banner', { state: 'hidden', timeout: 5000 })
      .catch(() => fail('the default-password banner stays after both passwords changed'));
    await shot('administration-changed');
    await page.click('#logout');
    await visible('#login-password', 'login after logout');
    await page.fill('#login-password', PASSWORD);
    await page.click('#login-submit');
    await waitText('#login-error', (t) => /wrong password/i.test(t), 'old read password after the change');
    await page.fill('#login-password', 'READ-2');
    await page.click('#login-submit');
    await visible('#side-menu a.active', 'the page after login with the new password');
    ok('passwords changed; the banner went; the old read password is refused, the new one logs in');
  }

  await drive.write('FA06', 0);
  if (external.length) fail(`the page requested outside resources: ${external.join(', ')}`);
  if (pageErrors.length) fail(`errors in the page: ${pageErrors.join(' | ')}`);
  ok('no page errors, no outside requests');
}

async function channelsOnly() {
  for (const value of [1234, 0]) {
    await drive.write('FA07', value);
    const got = await verify.read('FA07');
    if (got !== value) fail(`FA07 written as ${value} through ${DRIVE} reads ${got} through ${VERIFY}`);
  }
  console.log(`PASS: side channels: FA07 written through ${DRIVE} reads back through ${VERIFY}`);
}
if (opts['channels-only']) {
  channelsOnly().catch((e) => { console.error(`FAIL: ${e instanceof Failure ? e.message : e.stack || e}`); process.exit(1); });
} else main().then(async () => {
  await browser.close();
  fs.rmSync(userDir, { recursive: true, force: true });
  console.log(`PASS: web page against ${BASE} (screenshots in ${SHOTS})`);
}, async (e) => {
  console.error(`FAIL: ${e instanceof Failure ? e.message : e.stack || e}`);
  if (page) await page.screenshot({ path: path.join(SHOTS, 'failure.png'), fullPage: true }).catch(() => {});
  if (browser) await browser.close().catch(() => {});
  if (userDir) fs.rmSync(userDir, { recursive: true, force: true });
  process.exit(1);
});
