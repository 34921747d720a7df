#!/usr/bin/env node
// An independent EtherNet/IP peer against the card: the npm package st-ethernet-ip (package.json at the
// repository root).
//
// 1. Discovery: st-ethernet-ip's Browser broadcasts ListIdentity (UDP 255.255.255.255:44818, sender
//    context 0, so the card waits a random 0..2000 ms before it answers) and must list the card with
//    the expected identity.
// 2. Explicit messaging without a Controller: st-ethernet-ip has no generic "CIP message" API on its
//    Controller (that one is Logix-only: it reads controller properties and tags), but its ENIP socket
//    class registers a session and sends any message router request in SendRRData (write_cip), and its
//    CIP module builds the requests (MessageRouter.build, EPATH segments, UnconnectedSend.build with a
//    "backplane port 1 slot 0" route). Those are used for Get_Attribute_Single and Get_Attributes_All of
//    the Identity object, directly and through Unconnected_Send.
//
// usage: node eip_browse.js CARD_IP EXPECTED_JSON
//   EXPECTED_JSON: {"vendorID":377,"deviceType":2,"productCode":32000,"productName":"VF-MB1",
//                   "serialNumber":"0x...","revision":"1.8"}
// Prints "ok: ..." lines; exits 1 with "FAIL: ..." on the first mismatch, 2 on a usage error.
// Every wait is bounded (discovery 8 s, each explicit request 3 s, the whole script 20 s).
"use strict";

const { Browser, EthernetIP } = require("st-ethernet-ip");

const { MessageRouter, EPATH, UnconnectedSend } = EthernetIP.CIP;
const { LOGICAL, PORT } = EPATH.segments;

const [cardIp, expectedJson] = process.argv.slice(2);
if (!cardIp || !expectedJson) {
  console.error("usage: node eip_browse.js CARD_IP EXPECTED_JSON");
  process.exit(2);
}
const expected = JSON.parse(expectedJson);

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exit(1);
}
// A last resort: nothing here may hang the test.
setTimeout(() => fail("eip_browse.js did not finish within 20 s"), 20000).unref();

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: no answer within ${ms} ms`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

// ---- 1. Browser (broadcast ListIdentity) --------------------------------------------------------

function discover() {
  return new Promise((resolve, reject) => {
    // Port 0: any free local port; a request every 1000 ms (the first after 1 s).
    const browser = new Browser(0, "0.0.0.0", true, 1000);
    const timer = setTimeout(() => {
      browser.stop();
      browser.socket.close();
      reject(new Error("the Browser did not find the card within 8 s"));
    }, 8000);
    browser.on("New Device", (device) => {
      if (device.socketAddress.sin_addr !== cardIp) return;  // only the card is on this network
      clearTimeout(timer);
      browser.stop();
      browser.socket.close();
      resolve(device);
    });
    browser.socket.on("error", (error) => {
      clearTimeout(timer);
      reject(error);
    });
  });
}

function checkDevice(device) {
  const fields = {
    vendorID: device.vendorID,
    deviceType: device.deviceType,
    productCode: device.productCode,
    productName: device.productName,
    serialNumber: device.serialNumber,
    revision: device.revision,
  };
  for (const [key, want] of Object.entries(expected)) {
    if (fields[key] !== want) fail(`Browser: ${key} = ${JSON.stringify(fields[key])}, expected ${JSON.stringify(want)}`);
  }
  if (device.EncapsulationVersion !== 1) fail(`Browser: encapsulation version ${device.EncapsulationVersion}`);
  if (device.socketAddress.sin_family !== 2 || device.socketAddress.sin_port !== 44818) {
    fail(`Browser: socket address ${JSON.stringify(device.socketAddress)}`);
  }
  if (device.state !== 0xff) fail(`Browser: state ${device.state}`);
  console.log(`ok: Browser found ${device.productName} at ${device.socketAddress.sin_addr}: vendor ${device.vendorID}, ` +
              `type ${device.deviceType}, product ${device.productCode}, revision ${device.revision}, ` +
              `serial ${device.serialNumber}, status 0x${device.status.toString(16)}`);
}

// ---- 2. Explicit messages over an ENIP session ---------------------------------------------------

function identityPath() {
  return Buffer.concat([
    LOGICAL.build(LOGICAL.types.ClassID, 0x01),
    LOGICAL.build(LOGICAL.types.InstanceID, 1),
  ]);
}

function ask(enip, request, what) {
  const reply = new Promise((resolve) => {
    enip.once("SendRRData Received", (items) => resolve(items));
  });
  enip.write_cip(request);
  return withTimeout(reply, 3000, what).then((items) => {
    const ucmm = items.find((item) => item.TypeID === 0xb2);
    if (!ucmm) fail(`${what}: no unconnected data item in ${JSON.stringify(items)}`);
    return MessageRouter.parse(ucmm.data);
  });
}

async function explicit() {
  const enip = new EthernetIP.ENIP();
  const session = await enip.connect(cardIp, 3000);
  if (!session) fail(`RegisterSession refused: ${JSON.stringify(enip.error)}`);
  console.log(`ok: ENIP session registered, handle 0x${session.toString(16)}`);
  try {
    // Get_Attribute_Single Identity attribute 1 (vendor ID) and 7 (product name).
    const attribute = (id) => Buffer.concat([identityPath(), LOGICAL.build(LOGICAL.types.AttributeID, id)]);
    let reply = await ask(enip, MessageRouter.build(0x0e, attribute(1), []), "Get vendor ID");
    if (reply.service !== 0x8e || reply.generalStatusCode !== 0 || reply.data.readUInt16LE(0) !== expected.vendorID) {
      fail(`Get vendor ID: ${JSON.stringify(reply)}`);
    }
    reply = await ask(enip, MessageRouter.build(0x0e, attribute(7), []), "Get product name");
    const name = reply.data.subarray(1, 1 + reply.data[0]).toString("latin1");
    if (reply.generalStatusCode !== 0 || name !== expected.productName) fail(`Get product name: ${name}`);
    console.log(`ok: Get_Attribute_Single Identity 1 = ${expected.vendorID}, 7 = "${name}"`);

    // Get_Attributes_All of Identity instance 1, inside Unconnected_Send over "port 1, slot 0".
    const all = MessageRouter.build(0x01, identityPath(), []);
    reply = await ask(enip, UnconnectedSend.build(all, PORT.build(1, 0), 2000), "Unconnected_Send");
    if (reply.service !== 0x81 || reply.generalStatusCode !== 0) fail(`Unconnected_Send: ${JSON.stringify(reply)}`);
    const d = reply.data;
    const got = {
      vendorID: d.readUInt16LE(0),
      deviceType: d.readUInt16LE(2),
      productCode: d.readUInt16LE(4),
      revision: `${d[6]}.${d[7]}`,
      serialNumber: "0x" + d.readUInt32LE(10).toString(16),
      productName: d.subarray(15, 15 + d[14]).toString("latin1"),
    };
    for (const [key, want] of Object.entries(expected)) {
      if (got[key] !== want) fail(`Unconnected_Send Get_Attributes_All: ${key} = ${got[key]}, expected ${want}`);
    }
    if (d.length !== 15 + d[14]) fail(`Get_Attributes_All: ${d.length} bytes`);
    console.log("ok: Unconnected_Send (route port 1 slot 0) carrying Get_Attributes_All Identity: same identity");

    // An error comes back as a CIP status, not as a broken session: attribute 8 does not exist.
    reply = await ask(enip, MessageRouter.build(0x0e, attribute(8), []), "Get attribute 8");
    if (reply.generalStatusCode !== 0x14) fail(`Get Identity attribute 8: status 0x${reply.generalStatusCode.toString(16)}`);
    console.log("ok: Identity attribute 8 answered 0x14");
  } finally {
    // destroy() sends UnRegisterSession; the card closes the connection.
    enip.destroy(new Error("done"));
  }
}

(async () => {
  try {
    checkDevice(await discover());
    await explicit();
    process.exit(0);
  } catch (error) {
    fail(error.message);
  }
})();
