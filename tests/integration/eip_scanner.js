#!/usr/bin/env node
// Class 1 I/O with an independent originator: st-ethernet-ip's I/O scanner (IO.Scanner, package.json at
// the repository root) opens an exclusive-owner connection to the card and runs the simulated drive
// through it, as a PLC would (docs/eip-tests.md "integration.eip_scanner").
//
// usage: node eip_scanner.js CARD_IP CONTROL_SOCKET PROFILE [RPI_MS]
//   PROFILE 21:  O->T assembly 21 (4 bytes), T->O assembly 71 (4 bytes)
//   PROFILE 100: O->T assembly 100 (8 bytes: FA06, FA07, 2 scanner words), T->O 150 (8 bytes)
//   RPI_MS: both directions, default 10 (st-ethernet-ip refuses less than 8)
//   The card must run with c500=1, c101=1 (a Forward_Close of the owner is a loss: action "continue"),
//   acc=dec=2.0 s and f856=2; eip_scanner_tap.sh checks that before it runs this.
//
// Phases (each wait bounded; the expected bytes are docs/drive-profile.md's worked examples):
//   connect      the Forward_Open st-ethernet-ip sends (sizes, RPIs, path), the card's reply, the
//                card's stats (cip.connections = 1, io.received/io.sent rising at the RPI), the T->O
//                datagrams (format, sequence numbers, period) and the first input (stopped, ready)
//   start        forward 60 Hz / 1800 rpm: FA06/FA07 in the simulated inverter, its output frequency
//                ramping up, the input assembly climbing and then exactly "at reference"
//   stop         the output frequency ramping down to 0, the input stopped and ready
//   trip         the simulated inverter trips (E): the input shows the fault
//   fault reset  through the assembly (21: byte 0 bit 2, 100: FA06 bit 13, 0 -> 1): trip cleared
//   close        Forward_Close, then st-ethernet-ip closes its TCP connection (without UnRegisterSession):
//                the connection, the session and the TCP connection are gone from the card's stats; the
//                close counts as an owner close (a loss; c101 = 1: the inverter does not trip); the T->O
//                period over the whole run is the RPI
// Prints "ok: ..." lines; exits 1 with "FAIL: ..." on the first mismatch, 2 on a usage error.
"use strict";

const net = require("net");
const { IO } = require("st-ethernet-ip");

const [cardIp, controlPath, profileName, rpiArg] = process.argv.slice(2);
const RPI_MS = rpiArg === undefined ? 10 : Number(rpiArg);
if (!cardIp || !controlPath || !["21", "100"].includes(profileName) || !(RPI_MS >= 8)) {
  console.error("usage: node eip_scanner.js CARD_IP CONTROL_SOCKET 21|100 [RPI_MS >= 8]");
  process.exit(2);
}

let phase = "start-up";
function fail(message) {
  console.error(`FAIL: [${profileName}, ${phase}] ${message}`);
  process.exit(1);
}
function ok(message) {
  console.log(`ok: [${profileName}] ${message}`);
}
// A last resort: nothing here may hang the test.
setTimeout(() => fail("eip_scanner.js did not finish within 45 s"), 45000).unref();

const hex = (buffer) => Buffer.from(buffer).toString("hex").replace(/(..)(?!$)/g, "$1 ").toUpperCase();
const H = (text) => Buffer.from(text.replace(/\s+/g, ""), "hex");
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: nothing within ${ms} ms`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

// ---- The profiles: docs/drive-profile.md (f856 = 2: 1800 rpm = 60.00 Hz = FA07 6000) ----------------

// 71: byte 0 = At Reference, Ref From Net, Ctrl From Net, Ready, Running2, Running1, Warning, Faulted;
// byte 1 = Control Supervisor state; bytes 2-3 = actual speed, rpm.
const decode71 = (b) => ({
  running: (b[0] & 0x0c) !== 0, faulted: (b[0] & 0x01) !== 0, ready: (b[0] & 0x10) !== 0,
  atReference: (b[0] & 0x80) !== 0, state: b[1], speed: b.readUInt16LE(2),
});
// 150: word 1 = FD01 (bit 10 running, bit 1 tripped, bit 14 ready), word 2 = FD00 (0.01 Hz), words 3-4 =
// the monitor words c021 = 1 (FD01), c022 = 2 (FD00).
const decode150 = (b) => {
  const fd01 = b.readUInt16LE(0);
  return { running: (fd01 & 0x0400) !== 0, faulted: (fd01 & 0x0002) !== 0, ready: (fd01 & 0x4000) !== 0,
           atReference: false, state: fd01, speed: b.readUInt16LE(2) };
};

const PROFILES = {
  21: {
    output: 21, input: 71, size: 4, decode: decode71, unit: "rpm", target: 1800,
    // docs: stop 00 00 -> 10 03 00 00 (Ready, state 3 Ready)
    idle: { out: "00 00 00 00", in: "10 03 00 00" },
    // docs: forward 1800 rpm 61 00 08 07 -> F4 04 08 07 (FA06 C400h, FA07 1770h, state 4 Enabled)
    start: { out: "61 00 08 07", in: "F4 04 08 07", fa06: 0xc400, fa07: 6000,
             // Ready (with Ctrl/Ref From Net once FA06 C400h is written), Running1 in state 4 Enabled, then
             // At Reference, never before the drive runs (docs/eip-tests.md "Findings": fixed).
             pattern: /^(10 03,)?(70 03,)?74 04,F4 04$/, moving: "74 04" },
    // Run Fwd 0 with NetCtrl/NetRef kept: FA06 C000h (decelerate), then Ready + Ctrl/Ref From Net, state 3
    stop: { out: "60 00 08 07", in: "70 03 00 00", fa06: 0xc000, fa07: 6000,
            // decelerating: Running1 in state 5 Stopping, then Ready in state 3 ("74 04": the new FD00 below
            // FE02 while the FD01 of the same input still shows RUN on)
            pattern: /^(F4 04,)?(74 04,)?74 05,70 03$/, moving: "74 05" },
    // Faulted + Ctrl/Ref From Net, state 7 Faulted, speed 0
    faulted: "61 07 00 00",
    // Fault reset 0 -> 1 (byte 0 bit 2) with NetCtrl/NetRef
    reset: { out: "64 00 08 07" },
  },
  100: {
    output: 100, input: 150, size: 8, decode: decode150, unit: "0.01 Hz", target: 6000,
    // docs: stop 00 00 -> 00 48 00 00; words 3-4: FD01, FD00 again (c021 = 1, c022 = 2)
    idle: { out: "00 00 00 00 00 00 00 00", in: "00 48 00 00 00 48 00 00" },
    // docs: forward 60 Hz 00 C4 70 17 -> 00 64 70 17; words 3-4 go to c001 = FA06 / c002 = FA07, which
    // words 1-2 own (not written)
    start: { out: "00 C4 70 17 00 00 00 00", in: "00 64 70 17 00 64 70 17", fa06: 0xc400, fa07: 6000,
             // FD01 4800h (standby) then 6400h (running, RUN on)
             pattern: /^(00 48,)?00 64$/, moving: "00 64" },
    // FD01 4400h (running, RUN off: decelerating), then 4000h: standby with ST on, which FA06 bit 11 = 0
    // gives while FA06 has the command priority (docs' 4800h, ST off, is the stop without priority above)
    stop: { out: "00 C0 70 17 00 00 00 00", in: "00 40 00 00 00 40 00 00", fa06: 0xc000, fa07: 6000,
            pattern: /^(00 64,)?00 44,00 40$/, moving: "00 44" },
    // FD01 tripped at standstill by E: bit 0 (FL, fault relay), bit 1 (tripped, "EMG" in 150), bit 12
    // (emergency stop)
    faulted: "03 10 00 00 03 10 00 00",
    // FA06 bit 13 (reset trip) 0 -> 1, priorities kept
    reset: { out: "00 E0 70 17 00 00 00 00" },
  },
};
const P = PROFILES[profileName];

// ---- The control socket (docs/simulator.md "Control commands"), asynchronous --------------------------
// Never block the event loop: st-ethernet-ip answers each T->O datagram with an O->T one from it.

function control(command, ms = 3000) {
  return withTimeout(new Promise((resolve, reject) => {
    const socket = net.createConnection(controlPath);
    let buffer = "";
    const lines = [];
    socket.on("connect", () => socket.write(`${command}\n`));
    socket.on("data", (chunk) => {
      buffer += chunk.toString();
      let at;
      while ((at = buffer.indexOf("\n")) >= 0) {
        const line = buffer.slice(0, at);
        buffer = buffer.slice(at + 1);
        if (line === "ok") {
          socket.destroy();
          resolve(lines);
          return;
        }
        if (line.startsWith("error")) {
          socket.destroy();
          reject(new Error(`control '${command}': ${line}`));
          return;
        }
        lines.push(line);
      }
    });
    socket.on("error", (error) => reject(new Error(`control '${command}': ${error.message}`)));
  }), ms, `control '${command}'`);
}

async function status() {
  const lines = await control("status");
  return JSON.parse(lines.find((line) => line.startsWith("{")));
}

async function stats() {
  const values = {};
  for (const line of await control("stats")) {
    const at = line.indexOf("=");
    if (at > 0) values[line.slice(0, at)] = line.slice(at + 1);
  }
  for (const name of ["cip.connections", "io.received", "io.sent", "cip.close_requests", "cip.loss_owner_closes", "eip.sessions", "eip.connections", "cip.missed_productions", "cip.dropped_datagrams", "cip.connection_timeouts"]) {
    if (!(name in values)) fail(`stats has no ${name}`);
  }
  return values;
}
const num = (values, name) => Number(values[name]);

// Polls `probe` (async) every `interval` ms until `accept(value)` or `limit` ms; returns the value.
async function waitFor(what, probe, accept, limit, interval = 50) {
  const deadline = Date.now() + limit;
  let value;
  for (;;) {
    value = await probe();
    if (accept(value)) return value;
    if (Date.now() > deadline) fail(`${what}: not within ${limit} ms; last ${JSON.stringify(value)}`);
    await sleep(interval);
  }
}

// ---- The scanner and what it receives ----------------------------------------------------------------

let scanner = null;
let conn = null;
let connected = null;    // resolves on st-ethernet-ip's "connected" event
let closing = false;

// Everything st-ethernet-ip writes on its TCP connection (the Forward_Open and Forward_Close among it),
// and its Forward_Open reply.
const tcpWrites = [];
let openReply = null;

// Every T->O datagram of the connection, checked (docs/connections.md "Class 1 datagram"), and the
// input data it carries, kept with its arrival time.
const inputs = [];       // {t, data} of every datagram
const arrivals = [];
let lastEncap = null;
let lastCipSeq = null;
let encapGaps = 0;
let maxGap = 0;          // the longest pause between two T->O datagrams as this process saw them
function lastGap() {
  return arrivals.length ? `(last T->O ${Date.now() - arrivals[arrivals.length - 1]} ms ago)` : "(no T->O datagrams)";
}

function onDatagram(data, from) {
  if (from.address !== cardIp || data.length < 10 || conn.TOid === 0 || data.readUInt32LE(6) !== conn.TOid) return;
  const t = Date.now();
  const size = P.size;
  // Modeless T->O: count 2, 0x8002 (8): connection ID, encapsulation sequence; 0x00B1 (2 + size):
  // CIP sequence count, data.
  if (data.length !== 20 + size || data.readUInt16LE(0) !== 2 || data.readUInt16LE(2) !== 0x8002 ||
      data.readUInt16LE(4) !== 8 || data.readUInt16LE(14) !== 0x00b1 || data.readUInt16LE(16) !== 2 + size) {
    fail(`T->O datagram: ${hex(data)}`);
  }
  const encap = data.readUInt32LE(10);
  const cipSeq = data.readUInt16LE(18);
  if (lastEncap !== null) {
    // Every production advances both sequence numbers by one (a lost datagram shows as a gap).
    const step = (encap - lastEncap) >>> 0;
    const cipStep = (cipSeq - lastCipSeq) & 0xffff;
    if (step === 0 || step >= 0x80000000) fail(`T->O encapsulation sequence ${lastEncap} then ${encap}`);
    if (cipStep !== (step & 0xffff)) fail(`T->O CIP sequence ${lastCipSeq} then ${cipSeq} (encapsulation +${step})`);
    if (step !== 1) encapGaps += step - 1;
  }
  lastEncap = encap;
  lastCipSeq = cipSeq;
  if (arrivals.length) maxGap = Math.max(maxGap, t - arrivals[arrivals.length - 1]);
  arrivals.push(t);
  inputs.push({ t, data: Buffer.from(data.subarray(20)) });
}

// st-ethernet-ip's own watchdog (Connection._checkStatus, every 1 s) declares the connection lost when the
// last T->O datagram is more than 4 x RPI old (40 ms at 10 ms), and then opens a new connection while
// the old one still owns the output (0x0106 until the card's watchdog expires). It requests a timeout
// multiplier of 32 (RPI x 32 = 320 ms) in its own Forward_Open, and the card's watchdog uses that. On
// a loaded machine a 40 ms pause of the scheduler is enough to trip it (docs/eip-tests.md "Findings"),
// so the check is replaced here by the same logic with the timeout the connection really has, and
// without the re-open (a loss fails this test anyway).
const CONNECTION_TIMEOUT_MS = RPI_MS * 32;
function checkStatus(that) {
  if (Date.now() - that.lastDataTime > CONNECTION_TIMEOUT_MS) {
    if (that.connected) {
      that.emit("disconnected", null);
      that.TOid = 0;
    }
    that.connected = false;
  } else {
    if (!that.connected) that.emit("connected", null);
    that.connected = true;
  }
}

// Creates the scanner (UDP 2222) and its connection; st-ethernet-ip registers a session and sends the
// Forward_Open at once.
function openScanner() {
  scanner = new IO.Scanner(2222, "0.0.0.0");
  scanner.socket.on("error", (error) => fail(`UDP 2222: ${error.message}`));
  scanner.socket.on("message", onDatagram);
  const config = {
    configInstance: { assembly: 1, size: 0 },           // docs: configuration point 1, size 0
    outputInstance: { assembly: P.output, size: P.size },
    inputInstance: { assembly: P.input, size: P.size },
  };
  conn = scanner.addConnection(config, RPI_MS, cardIp);
  conn.outputData = H(P.idle.out);
  conn._checkStatus = checkStatus;
  connected = new Promise((resolve) => conn.once("connected", resolve));
  conn.on("disconnected", () => {
    if (!closing) fail(`st-ethernet-ip declared the connection lost (no T->O datagram for ${CONNECTION_TIMEOUT_MS} ms) ${lastGap()}`);
  });
  // net.Socket.connect() puts Socket.prototype.write back on the instance, so the hook goes in once the
  // TCP connection is up (before the session is registered, long before the Forward_Open).
  conn.tcpController.once("connect", () => {
    const socket = conn.tcpController;
    const originalWrite = socket.write;
    socket.write = function (data, ...rest) {
      tcpWrites.push(Buffer.from(data));
      return originalWrite.call(this, data, ...rest);
    };
  });
  conn.tcpController.on("Forward Open", (error, data) => { openReply = { error, data }; });
}

const currentInput = () => (inputs.length ? inputs[inputs.length - 1].data : null);
const inputSince = (t) => inputs.filter((entry) => entry.t >= t);

// The input must become `want` (hex) and then stay exactly that for `hold` ms.
async function waitInput(what, want, limit, hold = 500) {
  const expected = H(want);
  await waitFor(what, async () => currentInput(), (data) => data !== null && data.equals(expected), limit, 10);
  const since = Date.now();
  await sleep(hold);
  const other = inputSince(since).find((entry) => !entry.data.equals(expected));
  if (other) fail(`${what}: ${hex(expected)} did not hold: ${hex(other.data)} after it`);
  ok(`${what}: input ${P.input} = ${hex(expected)} (held ${hold} ms)`);
}

function setOutput(text) {
  conn.outputData = H(text);
}

// ---- Checks on st-ethernet-ip's Forward_Open -----------------------------------------------------------

// The CIP request of the first SendRRData whose service is `service`: [request, SendRRData packet].
function findRequest(service) {
  for (const packet of tcpWrites) {
    if (packet.length < 40 || packet.readUInt16LE(0) !== 0x006f) continue;
    // header 24, interface handle 4, timeout 2, item count 2, null address item 4, data item type 2, length 2
    if (packet.readUInt16LE(30) !== 2 || packet.readUInt16LE(36) !== 0x00b2) continue;
    const request = packet.subarray(40, 40 + packet.readUInt16LE(38));
    if (request[0] === service) return request;
  }
  return null;
}

function checkForwardOpen() {
  const request = findRequest(0x54);
  if (!request) fail(`no Forward_Open written by st-ethernet-ip: ${tcpWrites.map(hex).join(" / ")}`);
  console.log(`   Forward_Open request: ${hex(request)}`);
  // 54 02 20 06 24 01, then the 35 fixed bytes (docs/connections.md), path size, path.
  if (!request.subarray(0, 6).equals(H("54 02 20 06 24 01"))) fail(`Forward_Open service/path ${hex(request.subarray(0, 6))}`);
  const d = request.subarray(6);
  const fields = {
    otRpi: d.readUInt32LE(22), otParams: d.readUInt16LE(26), toRpi: d.readUInt32LE(28), toParams: d.readUInt16LE(32),
    transport: d[34], multiplier: d[18], reserved: hex(d.subarray(19, 22)), vendor: d.readUInt16LE(12),
    originatorSerial: d.readUInt32LE(14),
  };
  const pathWords = d[35];
  const path = d.subarray(36);
  const want = {
    otRpi: RPI_MS * 1000, toRpi: RPI_MS * 1000,
    // exclusive, point-to-point (0x4000), scheduled priority (0x0800), fixed, size: header + data
    otParams: 0x4800 | (2 + 4 + P.size), toParams: 0x4800 | (2 + P.size),
    transport: 0x01, multiplier: 3, reserved: "00 00 00", vendor: 0x3333, originatorSerial: 0x1337,
  };
  for (const [key, value] of Object.entries(want)) {
    if (fields[key] !== value) fail(`Forward_Open ${key} = ${JSON.stringify(fields[key])}, expected ${JSON.stringify(value)}`);
  }
  // An all-zero electronic key (format 4), Assembly class, configuration instance 1, then the points.
  const cp = (point) => (point < 256 ? `2C ${point.toString(16).padStart(2, "0")}` : `2D 00 ${hex([point & 0xff, point >> 8])}`);
  const wantPath = H(`34 04 00 00 00 00 00 00 00 00 20 04 24 01 ${cp(P.output)} ${cp(P.input)}`);
  if (!path.equals(wantPath) || pathWords * 2 !== path.length) {
    fail(`Forward_Open path (${pathWords} words) ${hex(path)}, expected ${hex(wantPath)}`);
  }
  ok(`Forward_Open: class 1 cyclic, RPI ${RPI_MS} ms both ways, O->T ${2 + 4 + P.size} / T->O ${2 + P.size} bytes ` +
     `(point-to-point, scheduled), multiplier 3 (timeout ${RPI_MS * 4 * 8} ms), path key 0 / 20 04 24 01 ` +
     `${P.output} -> ${P.input}`);
  return d;
}

function checkForwardOpenReply(request) {
  if (!openReply) fail("no Forward_Open reply");
  if (openReply.error) fail(`Forward_Open refused: ${JSON.stringify(openReply.error)}`);
  const r = openReply.data;
  console.log(`   Forward_Open reply data: ${hex(r)}`);
  if (r.length !== 26) fail(`Forward_Open reply data is ${r.length} bytes, expected 26`);
  if (r.readUInt32LE(4) !== request.readUInt32LE(6)) fail("Forward_Open reply: T->O connection ID not the originator's");
  if (!r.subarray(8, 16).equals(request.subarray(10, 18))) fail("Forward_Open reply: triad not echoed");
  if (r.readUInt32LE(16) !== RPI_MS * 1000 || r.readUInt32LE(20) !== RPI_MS * 1000) {
    fail(`Forward_Open reply: APIs ${r.readUInt32LE(16)} / ${r.readUInt32LE(20)} us`);
  }
  if (r[24] !== 0 || r[25] !== 0) fail("Forward_Open reply: application reply size not 0");
  if (r.readUInt32LE(0) === 0 || r.readUInt32LE(0) !== conn.OTid) fail("Forward_Open reply: O->T connection ID");
  ok(`Forward_Open reply: O->T ID 0x${conn.OTid.toString(16)} (the card's), T->O ID 0x${conn.TOid.toString(16)} ` +
     `(st-ethernet-ip's), APIs ${RPI_MS} ms`);
}

// ---- The phases ------------------------------------------------------------------------------------------

async function connectPhase(before) {
  phase = "connect";
  try {
    await withTimeout(connected, 5000, "st-ethernet-ip 'connected'");
  } catch (error) {
    fail(`${error.message}; Forward_Open reply: ${openReply ? JSON.stringify(openReply.error) : "none"}`);
  }
  const request = checkForwardOpen();
  checkForwardOpenReply(request);
  const s1 = await stats();
  if (num(s1, "cip.connections") !== 1) fail(`cip.connections = ${s1["cip.connections"]}`);
  if (num(s1, "cip.open_requests") !== num(before, "cip.open_requests") + 1) fail("cip.open_requests did not count 1");
  for (const name of ["cip.open_format_rejects", "cip.open_resource_rejects", "cip.open_other_rejects"]) {
    if (s1[name] !== before[name]) fail(`${name} ${before[name]} -> ${s1[name]}`);
  }
  // 0110: a class 1 connection in run mode (docs/connections.md "Identity status")
  if (s1["cip.io_status"] !== "6") fail(`cip.io_status = ${s1["cip.io_status"]}, expected 6 (run)`);
  await sleep(1000);
  const s2 = await stats();
  const received = num(s2, "io.received") - num(s1, "io.received");
  const sent = num(s2, "io.sent") - num(s1, "io.sent");
  const nominal = 1000 / RPI_MS;
  // About one datagram per RPI each way (st-ethernet-ip answers every T->O datagram with an O->T one).
  if (sent < nominal * 0.5 || received < nominal * 0.5) {
    fail(`io.sent +${sent}, io.received +${received} in ~1 s; expected about ${nominal} each`);
  }
  ok(`card stats: cip.connections = 1, io_status 6 (run), io.sent +${sent}, io.received +${received} in ~1 s`);
  ok(`T->O datagrams well formed so far (modeless, ${20 + P.size} bytes, both sequence numbers advancing together)`);
  await waitInput("stopped before any command", P.idle.in, 2000, 300);
}

// Samples the simulated inverter's output frequency until `done(status)`; returns the samples.
async function sampleRamp(what, done, limit) {
  const samples = [];
  await waitFor(what, async () => {
    const s = await status();
    samples.push(s.output_hz);
    return s;
  }, done, limit, 100);
  return samples;
}

function monotonic(values, up) {
  for (let i = 1; i < values.length; ++i) {
    if (up ? values[i] < values[i - 1] : values[i] > values[i - 1]) return false;
  }
  return true;
}

// The status part of the inputs since `t` must pass through `pattern` (a regular expression over the
// merged runs "AA BB,AA BB,..."), the actual speed must move monotonically, and the samples whose status is
// `moving` must show at least 10 different speeds strictly between 0 and the reference.
//
// At the edges the status and the speed may disagree for one drive-link cycle: the card reads FD01, FD00
// and FE02 one after the other over the serial link, and an input produced between two of those reads
// combines the new FD01 with the previous FD00 (e.g. "70 03" with 7 rpm just after the start, or "70 03"
// with the last speed just before the stop). That is in the nature of sequential register reads, so the
// pattern is checked on the status and the monotonic speed on the whole sequence, not on each sample.
function checkRamp(what, since, until, pattern, moving, up) {
  const entries = inputSince(since).filter((entry) => entry.t <= until);
  const runs = [];
  for (const entry of entries) {
    const text = hex(entry.data.subarray(0, 2));
    if (runs.length && runs[runs.length - 1].text === text) ++runs[runs.length - 1].count;
    else runs.push({ text, count: 1 });
  }
  const sequence = runs.map((run) => run.text).join(",");
  const shown = runs.map((run) => `${run.text} x${run.count}`).join(", ");
  if (!pattern.test(sequence)) fail(`${what}: status sequence ${shown}, expected ${pattern}`);
  const decoded = entries.map((entry) => P.decode(entry.data));
  const speeds = decoded.map((v) => v.speed);
  if (!monotonic(speeds, up)) fail(`${what}: actual speed not ${up ? "climbing" : "falling"}: ${speeds.join(" ")}`);
  const during = entries.filter((entry) => hex(entry.data.subarray(0, 2)) === moving).map((entry) => P.decode(entry.data).speed)
    .filter((speed) => speed > 0 && speed < P.target);
  const distinct = [...new Set(during)];
  if (distinct.length < 10) fail(`${what}: only ${distinct.length} speeds between 0 and ${P.target}: ${speeds.join(" ")}`);
  if (decoded.some((v) => v.faulted)) fail(`${what}: a faulted input`);
  ok(`input ${P.input} ${what}: status ${shown}; actual speed ${up ? "climbing" : "falling"} through ` +
     `${distinct.length} values (${distinct.filter((_, i) => i % 15 === 0).join(" ")} ... ${P.unit})`);
}

async function startPhase() {
  phase = "start";
  const since = Date.now();
  setOutput(P.start.out);
  const s = await waitFor("FA06/FA07 reach the inverter", status,
    (st) => st.fa06 === `0x${P.start.fa06.toString(16).toUpperCase()}` && st.fa07 === P.start.fa07, 3000);
  ok(`inverter: FA06 = ${s.fa06}, FA07 = ${s.fa07} (command ${s.command_source}, frequency ${s.frequency_source})`);
  const hz = await sampleRamp("output frequency ramps to 60 Hz", (st) => st.output_hz >= 60 && st.state === "running", 8000);
  const between = hz.filter((value) => value > 0 && value < 60);
  if (!monotonic(hz, true) || between.length < 2) fail(`output frequency samples ${hz.join(", ")}`);
  ok(`inverter output frequency ramps up: ${hz.map((v) => v.toFixed(1)).join(" ")} Hz`);
  await waitInput("at reference", P.start.in, 3000);
  checkRamp("during the ramp up", since, Date.now(), P.start.pattern, P.start.moving, true);
}

async function stopPhase() {
  phase = "stop";
  const since = Date.now();
  setOutput(P.stop.out);
  await waitFor("the stop reaches the inverter", status,
    (st) => st.fa06 === `0x${P.stop.fa06.toString(16).toUpperCase()}`, 3000);
  const hz = await sampleRamp("output frequency ramps down to 0", (st) => st.output_hz === 0 && st.state === "stopped", 8000);
  const between = hz.filter((value) => value > 0 && value < 60);
  if (!monotonic(hz, false) || between.length < 2) fail(`output frequency samples ${hz.join(", ")}`);
  ok(`inverter FA06 = 0x${P.stop.fa06.toString(16).toUpperCase()}: output frequency ramps down: ` +
     `${hz.map((v) => v.toFixed(1)).join(" ")} Hz, stopped`);
  await waitInput("stopped and ready", P.stop.in, 3000);
  checkRamp("during the ramp down", since, Date.now(), P.stop.pattern, P.stop.moving, false);
}

async function tripPhase() {
  phase = "trip";
  await control("trip E");
  const s = await waitFor("the inverter trips", status, (st) => st.state === "tripped" && st.trip === 17, 2000);
  ok(`inverter tripped: trip ${s.trip}, FD01 ${s.fd01}`);
  await waitInput("faulted", P.faulted, 3000);
  const v = P.decode(currentInput());
  if (!v.faulted || v.running) fail(`faulted input ${JSON.stringify(v)}`);
}

async function faultResetPhase() {
  phase = "fault reset";
  setOutput(P.reset.out);
  const s = await waitFor("the trip is cleared", status, (st) => st.trip === 0 && st.state === "stopped", 5000);
  ok(`fault reset through the assembly (${hex(H(P.reset.out))}): inverter trip ${s.trip}, ${s.state}`);
  await waitInput("ready again after the fault reset", P.stop.in, 5000);
  // Release the reset bit; the card writes its command again after the inverter's reset (RAM cleared).
  setOutput(P.stop.out);
  const again = await waitFor("FA06 written again after the reset", status,
    (st) => st.fa06 === `0x${P.stop.fa06.toString(16).toUpperCase()}` && st.trip === 0, 5000);
  ok(`reset bit released: FA06 = ${again.fa06}, no trip`);
  await waitInput("stopped and ready", P.stop.in, 2000);
}

async function closePhase(before) {
  phase = "close";
  const s1 = await stats();
  closing = true;
  conn.run = false;  // st-ethernet-ip: stop sending O->T and never re-open
  const result = await withTimeout(conn.tcpController.disconnect(), 3000, "Forward_Close");
  if (result !== "disconnected") fail(`disconnect() returned ${result}`);
  const request = findRequest(0x4e);
  if (!request) fail("no Forward_Close written");
  console.log(`   Forward_Close request: ${hex(request)}`);
  const s2 = await waitFor("the connection, the session and the TCP connection are gone", stats,
    (st) => num(st, "cip.connections") === 0 && num(st, "eip.sessions") === 0 && num(st, "eip.connections") === 0,
    2000);
  if (num(s2, "cip.close_requests") !== num(s1, "cip.close_requests") + 1) fail("cip.close_requests did not count 1");
  if (num(s2, "cip.loss_owner_closes") !== num(s1, "cip.loss_owner_closes") + 1) fail("the owner close was not counted");
  if (num(s2, "cip.connection_timeouts") !== num(before, "cip.connection_timeouts")) fail("a connection timed out");
  if (num(s2, "cip.dropped_datagrams") !== num(before, "cip.dropped_datagrams")) {
    fail(`the card dropped ${num(s2, "cip.dropped_datagrams") - num(before, "cip.dropped_datagrams")} O->T datagrams`);
  }
  const count = inputs.length;
  await sleep(300);
  if (inputs.length !== count) fail(`${inputs.length - count} T->O datagrams after the Forward_Close`);
  // The card produces on the grid open + k x API, skipping (not bursting) slots it missed: over the whole
  // run the mean period is the RPI.
  const mean = (arrivals[arrivals.length - 1] - arrivals[0]) / (arrivals.length - 1);
  if (Math.abs(mean - RPI_MS) > 1) fail(`mean T->O period ${mean.toFixed(3)} ms over ${arrivals.length} datagrams`);
  // c101 = 1: the loss is reported (cip.lost) but the inverter continues: no err8
  const st = await status();
  if (st.trip !== 0) fail(`inverter tripped (${st.trip}) after the close; c101 must be 1 for this test`);
  ok(`Forward_Close: cip.connections = 0, session and TCP connection closed, close counted, owner close counted ` +
     `as a loss (cip.lost = ${s2["cip.lost"]}, ` +
     `c101 = 1: no trip), no T->O datagram after it, no timeout, no dropped O->T datagram; ` +
     `${inputs.length} T->O datagrams, ${encapGaps} missing, mean period ${mean.toFixed(3)} ms, longest pause ` +
     `${maxGap} ms, the card's missed ` +
     `productions +${num(s2, "cip.missed_productions") - num(before, "cip.missed_productions")}`);
}

(async () => {
  try {
    const before = await stats();
    if (num(before, "cip.connections") !== 0) fail(`cip.connections = ${before["cip.connections"]} before the test`);
    openScanner();
    await connectPhase(before);
    await startPhase();
    await stopPhase();
    await tripPhase();
    await faultResetPhase();
    await closePhase(before);
    process.exit(0);
  } catch (error) {
    fail(error.stack || error.message);
  }
})();
