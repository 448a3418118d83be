#!/usr/bin/env node
// Foxglove's own WebSocket client (@foxglove/ws-protocol over the `ws` package) against uampc's
// live viewer: connects as Foxglove does, subscribes, and decodes every message with
// @foxglove/rosmsg2-serialization from the schema the server advertised.
//
//   node watch.mjs URL --topics /a,/b|all [--seconds S] [--until-closed] [--lazy-client]
//                      [--bad-requests N] [--huge-frame] [--duplicate-subscription] [--churn N]
//                      [--subscriptions-per-topic N] [--stop-reading]
//                      [--hold-clients N [--held-subscribe [--held-reading]]]
//                      [--late-client]
//
// --topics      what to subscribe to (all: every channel advertised, also those advertised later)
// --seconds     how long to watch (default 10); --until-closed: until the server closes instead
// --lazy-client a second client that subscribes to the same and never reads its socket
// --bad-requests N first send N malformed or unsupported requests (a cycle of six kinds)
// --huge-frame  send a 2 MiB text message (more than the server takes)
// --duplicate-subscription  subscribe to the first wanted channel twice under id 77 in one request
// --churn N     first connect and drop N clients (every other one mid-subscription, abruptly)
// --subscriptions-per-topic N  subscribe to each wanted channel N times, under N ids, in one request
// --stop-reading  stop reading the socket 200 ms after subscribing (a client that never reads)
// --hold-clients N  first connect N clients that stay until the end; with --held-subscribe each
//               subscribes to the wanted topics and stops reading (N slow clients); with
//               --held-reading it reads on, without decoding
// --late-client a second client that subscribes to the wanted topics once the first has received
//               a message of each: what it receives is in "late_client"
//
// Prints one JSON object: per topic the messages received and decoded and a digest of the first
// one; the status messages; time messages; decode errors (each names topic and error); what held
// and late clients saw. Exits 1 on a connection that fails or any message that does not decode.
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;

function options(argv) {
  const o = { url: argv[0], topics: "all", seconds: 10, untilClosed: false, lazy: false, bad: 0, huge: false, duplicate: false, churn: 0,
              perTopic: 1, stopReading: false, hold: 0, heldSubscribe: false, heldReading: false, late: false };
  for (let i = 1; i < argv.length; ++i) {
    const a = argv[i];
    if (a === "--topics") o.topics = argv[++i];
    else if (a === "--seconds") o.seconds = Number(argv[++i]);
    else if (a === "--until-closed") o.untilClosed = true;
    else if (a === "--lazy-client") o.lazy = true;
    else if (a === "--bad-requests") o.bad = Number(argv[++i]);
    else if (a === "--huge-frame") o.huge = true;
    else if (a === "--duplicate-subscription") o.duplicate = true;
    else if (a === "--churn") o.churn = Number(argv[++i]);
    else if (a === "--subscriptions-per-topic") o.perTopic = Number(argv[++i]);
    else if (a === "--stop-reading") o.stopReading = true;
    else if (a === "--hold-clients") o.hold = Number(argv[++i]);
    else if (a === "--held-subscribe") o.heldSubscribe = true;
    else if (a === "--held-reading") o.heldReading = true;
    else if (a === "--late-client") o.late = true;
    else throw new Error(`unknown argument ${a}`);
  }
  return o;
}

const opts = options(process.argv.slice(2));
const wanted = opts.topics === "all" ? null : new Set(opts.topics.split(","));

function connect() {
  return new WebSocket(opts.url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
}

function sleep(ms) {
  return new Promise((resolve) => setTimeout(resolve, ms));
}

// What a test wants to see of a decoded message, kept small.
function digest(topic, m) {
  if (m.header && m.header.frame_id !== undefined) {
    const d = { frame_id: m.header.frame_id, stamp_sec: m.header.stamp.sec };
    if (m.width !== undefined) Object.assign(d, { width: m.width, height: m.height });
    if (m.data !== undefined) d.data_bytes = m.data.length;
    if (m.encoding !== undefined) d.encoding = m.encoding;
    if (m.poses !== undefined) d.poses = m.poses.length;
    if (m.pose !== undefined && m.pose.pose !== undefined) d.position = m.pose.pose.position;
    return d;
  }
  if (m.transforms !== undefined) return { frames: m.transforms.map((t) => `${t.header.frame_id}->${t.child_frame_id}`) };
  return { fields: Object.keys(m) };
}

// Connects N clients one after another and drops them: half cleanly after subscribing to
// everything, half by destroying the socket right after sending a subscribe.
async function churn(n) {
  for (let i = 0; i < n; ++i) {
    await new Promise((resolve) => {
      const ws = connect();
      const client = new FoxgloveClient({ ws });
      client.on("advertise", (channels) => {
        for (const c of channels) client.subscribe(c.id);
        if (i % 2 === 0) ws.terminate();
        else client.close();
      });
      client.on("close", resolve);
      client.on("error", () => {});
    });
  }
}

// N clients connected one after another that stay: each has its serverInfo before the next
// connects, so that the server counts them in order. With subscribe, each subscribes to the wanted
// topics and stops reading its socket.
async function holdClients(n, subscribe, reading) {
  const held = { clients: [], closed_by_server: 0, statuses: [] };
  for (let i = 0; i < n; ++i) {
    await new Promise((resolve) => {
      const ws = connect();
      const client = new FoxgloveClient({ ws });
      const entry = { ws, closed: false };
      held.clients.push(entry);
      client.on("error", () => {});
      client.on("status", (s) => held.statuses.push({ level: s.level, message: s.message }));
      client.on("close", () => { entry.closed = true; resolve(); });
      client.on("serverInfo", () => { if (!subscribe) resolve(); });
      // Whenever the wanted topics are advertised (a run may not have started yet).
      client.on("advertise", (channels) => {
        if (!subscribe) return;
        const mine = channels.filter((c) => !wanted || wanted.has(c.topic));
        for (const c of mine) client.subscribe(c.id);
        if (mine.length > 0) setTimeout(() => { if (!reading) ws._socket.pause(); resolve(); }, 200);
      });
    });
  }
  return held;
}

// A client that subscribes to the wanted topics when asked, and counts what it receives by topic.
function lateClient() {
  const late = { topics: {}, statuses: [] };
  const ws = connect();
  const client = new FoxgloveClient({ ws });
  const topicOf = new Map();
  client.on("error", () => {});
  client.on("status", (s) => late.statuses.push({ level: s.level, message: s.message }));
  client.on("advertise", (channels) => {
    for (const c of channels) if (!wanted || wanted.has(c.topic)) topicOf.set(client.subscribe(c.id), c.topic);
  });
  client.on("message", ({ subscriptionId }) => {
    const topic = topicOf.get(subscriptionId);
    late.topics[topic] = (late.topics[topic] ?? 0) + 1;
  });
  return { late, ws };
}

function badRequests(ws, n) {
  const sends = [
    "{not json",
    JSON.stringify({ op: "subscribe", subscriptions: [{ id: 1, channelId: 999999 }] }),
    JSON.stringify({ op: "fly" }),
    JSON.stringify({ op: "unsubscribe", subscriptionIds: [4242] }),
    JSON.stringify({ op: "subscribe", subscriptions: [{ id: -3, channelId: 1 }] }),
  ];
  sends.push(new Uint8Array([1, 0, 0, 0, 0, 7]));  // client message data: not served
  for (let i = 0; i < n; ++i) ws.send(sends[i % sends.length]);
}

async function main() {
  if (opts.churn > 0) await churn(opts.churn);
  const held = opts.hold > 0 ? await holdClients(opts.hold, opts.heldSubscribe, opts.heldReading) : null;

  const result = { server: null, channels: 0, topics: {}, statuses: [], time_messages: 0, last_time_ns: null,
                   decode_errors: [], closed_by_server: false, lazy_client: null };
  const readers = new Map();  // channel id -> {topic, reader}
  const bySubscription = new Map();
  const ws = connect();
  const client = new FoxgloveClient({ ws });
  let closed = false;
  let failed = null;
  let duplicated = false;
  let nextId = 1000000;  // ids of --subscriptions-per-topic, apart from the client library's

  client.on("error", (e) => { failed = failed ?? String(e?.message ?? e); });
  client.on("close", () => { closed = true; result.closed_by_server = true; });
  client.on("serverInfo", (info) => { result.server = { name: info.name, capabilities: info.capabilities }; });
  client.on("status", (s) => result.statuses.push({ level: s.level, message: s.message }));
  client.on("time", (t) => { result.time_messages += 1; result.last_time_ns = t.timestamp.toString(); });
  client.on("advertise", (channels) => {
    for (const c of channels) {
      result.channels += 1;
      if (wanted && !wanted.has(c.topic)) continue;
      try {
        readers.set(c.id, { topic: c.topic, reader: new MessageReader(parse(c.schema, { ros2: true })) });
      } catch (e) {
        result.decode_errors.push({ topic: c.topic, error: `schema: ${e.message}` });
        continue;
      }
      if (opts.perTopic > 1) {
        // One request with every id, as a client that means harm sends it.
        const subscriptions = [];
        for (let k = 0; k < opts.perTopic; ++k) {
          const id = nextId++;
          subscriptions.push({ id, channelId: c.id });
          bySubscription.set(id, c.id);
        }
        ws.send(JSON.stringify({ op: "subscribe", subscriptions }));
      } else {
        bySubscription.set(client.subscribe(c.id), c.id);
      }
      if (opts.stopReading) setTimeout(() => ws._socket.pause(), 200);
      if (opts.duplicate && !duplicated) {
        // The first of the two is taken, the second refused: its id is in use.
        duplicated = true;
        ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 77, channelId: c.id }, { id: 77, channelId: c.id }] }));
        bySubscription.set(77, c.id);
      }
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const channel = readers.get(bySubscription.get(subscriptionId));
    if (!channel) {
      result.decode_errors.push({ topic: "?", error: `message for unknown subscription ${subscriptionId}` });
      return;
    }
    const t = (result.topics[channel.topic] ??= { received: 0, decoded: 0, first: null, first_time_ns: null });
    t.received += 1;
    try {
      const m = channel.reader.readMessage(data);
      t.decoded += 1;
      if (t.first === null) {
        t.first = digest(channel.topic, m);
        t.first_time_ns = timestamp.toString();
      }
    } catch (e) {
      result.decode_errors.push({ topic: channel.topic, error: e.message });
    }
  });

  await new Promise((resolve, reject) => {
    ws.once("open", resolve);
    ws.once("error", reject);
  });
  if (opts.bad > 0) badRequests(ws, opts.bad);
  if (opts.huge) ws.send(JSON.stringify({ op: "subscribe", subscriptions: [], padding: "x".repeat(2 << 20) }));

  let lazy = null;
  if (opts.lazy) {
    // Subscribes like the first, then stops reading its socket for good.
    lazy = connect();
    const lazyClient = new FoxgloveClient({ ws: lazy });
    lazyClient.on("error", () => {});
    lazyClient.on("advertise", (channels) => {
      for (const c of channels) if (!wanted || wanted.has(c.topic)) lazyClient.subscribe(c.id);
      setTimeout(() => lazy._socket.pause(), 200);
    });
  }

  const deadline = Date.now() + opts.seconds * 1000;
  let late = null;
  while (!closed && (opts.untilClosed || Date.now() < deadline)) {
    await sleep(50);
    // Late: once every wanted topic has reached the first client, which stays subscribed.
    if (opts.late && !late && wanted && [...wanted].every((t) => result.topics[t]?.received > 0)) late = lateClient();
  }
  if (lazy) {
    result.lazy_client = { still_open: lazy.readyState === WebSocket.OPEN };
    lazy.terminate();
  }
  if (!closed) client.close();
  if (late) {
    result.late_client = late.late;
    late.ws.terminate();
  }
  if (held) {
    result.held_clients = { closed_by_server: held.clients.filter((c) => c.closed).length, statuses: held.statuses };
    for (const c of held.clients) c.ws.terminate();
  }
  if (failed && !result.closed_by_server) result.error = failed;
  process.stdout.write(`${JSON.stringify(result)}\n`);
  process.exit(result.decode_errors.length > 0 || result.error ? 1 : 0);
}

main().catch((e) => {
  process.stdout.write(`${JSON.stringify({ error: String(e?.message ?? e) })}\n`);
  process.exit(1);
});
