// homebot console: live map, speech, event log and step view; three levels of control.
"use strict";
const TOKEN = new URLSearchParams(location.search).get("token") || "";
// who this page is: a session the server issues (POST /api/session); control is a lease on
// it that the heartbeat renews and pagehide gives back, so a closed or reloaded page never
// keeps the robot
let SESSION = "", OPERATOR = "";
const SVG = "http://www.w3.org/2000/svg";
const svg = document.getElementById("map");
let map = null, state = null, composed = [], scale = 40, layers = {};
let placementLabels = [];  // the boxes the rooms' and furniture's names take: others keep off

function spoken(name) { return name.replaceAll("_", " "); }
// where a centred label of `text` near (x, y) overlaps none of `taken` (tried: on the spot,
// then a line below, above, two lines below ...); the first spot when all are taken. The
// chosen box is added to `taken`.
function label(taken, text, x, y, size) {
  const w = text.length * size * 0.55, h = size;
  const free = (ty) => taken.every(b => x + w / 2 < b[0] || x - w / 2 > b[2] ||
                                        ty < b[1] || ty - h > b[3]);
  const tries = [0, 1, -1, 2, -2].map(k => y + k * (h + 1));
  const ty = tries.find(free) ?? y;
  taken.push([x - w / 2, ty - h, x + w / 2, ty]);
  return [x, ty];
}

function el(name, attrs, parent) {
  const node = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs || {})) node.setAttribute(k, v);
  if (parent) parent.appendChild(node);
  return node;
}
function px(x, y) { return [(x - map.bounds[0]) * scale + 10, (map.bounds[3] - y) * scale + 10]; }
function world(cx, cy) { return [(cx - 10) / scale + map.bounds[0], map.bounds[3] - (cy - 10) / scale]; }

async function api(path, body) {
  const response = await fetch(path, {
    method: body === undefined ? "GET" : "POST",
    headers: {"Content-Type": "application/json", "X-Homebot-Token": TOKEN,
              "X-Homebot-Session": SESSION},
    body: body === undefined ? undefined : JSON.stringify(body)});
  let data = {};
  try { data = await response.json(); } catch (err) { data = {error: String(response.status)}; }
  document.getElementById("error").textContent = response.ok ? "" : (data.error || response.status);
  if (response.status === 403 && path !== "/api/session") startSession();  // session forgotten
  return data;
}

async function startSession() {
  const data = await api("/api/session", {});
  SESSION = data.session || ""; OPERATOR = data.operator || "";
  document.getElementById("whoami").textContent = OPERATOR ? `(you are ${OPERATOR})` : "";
  return data;
}

let heartbeat = null;
async function startHeartbeat() {
  const data = await startSession();
  const period = Math.max(1, (data.lease || 10) / 4) * 1000;
  if (heartbeat) clearInterval(heartbeat);
  heartbeat = setInterval(() => { if (SESSION) api("/api/session/heartbeat", {}); }, period);
}
window.addEventListener("pagehide", () => {
  // closed, reloaded or navigated away: give control back now, not when the lease lapses
  if (SESSION) navigator.sendBeacon(`/api/session/end?token=${encodeURIComponent(TOKEN)}` +
                                    `&session=${encodeURIComponent(SESSION)}`);
  SESSION = "";
});
// back from the browser's back-forward cache: the old session was ended, start a new one
window.addEventListener("pageshow", (event) => { if (event.persisted) startSession(); });

function drawMap() {
  svg.innerHTML = "";
  const w = map.bounds[2] - map.bounds[0], h = map.bounds[3] - map.bounds[1];
  const box = svg.getBoundingClientRect();
  scale = Math.max(10, Math.min((box.width - 20) / w, (box.height - 20) / h));
  svg.setAttribute("viewBox", `0 0 ${w * scale + 20} ${h * scale + 20}`);
  const base = el("g", {}, svg);
  for (const poly of Object.values(map.rooms))
    el("polygon", {points: poly.map(p => px(...p).join(",")).join(" "), fill: "#fff",
                   stroke: "#333", "stroke-width": 2}, base);
  placementLabels = [];
  for (const [name, p] of Object.entries(map.placements)) {
    const [x0, y0] = px(p.box[0], p.box[3]), [x1, y1] = px(p.box[2], p.box[1]);
    el("rect", {x: x0, y: y0, width: x1 - x0, height: y1 - y0,
                fill: p.kind === "furniture" ? "#dcb" : "#eef", stroke: "#765"}, base)
      .appendChild(document.createElementNS(SVG, "title")).textContent = name;
  }
  // the rooms' names above the furniture, then the furniture's at their footprints'
  // centres, each nudged off the names already drawn; a white halo keeps them readable
  const names = el("g", {id: "layer-placement-labels"}, base);
  for (const [name, poly] of Object.entries(map.rooms)) {
    const cx = poly.reduce((a, p) => a + p[0], 0) / poly.length;
    const cy = poly.reduce((a, p) => a + p[1], 0) / poly.length;
    const spot = label(placementLabels, spoken(name), px(cx, cy)[0], px(cx, cy)[1], 12);
    el("text", {x: spot[0], y: spot[1], "font-size": 12, fill: "#888", "text-anchor": "middle",
                class: "room-label halo"}, names).textContent = spoken(name);
  }
  for (const [name, p] of Object.entries(map.placements)) {
    const [cx, cy] = px((p.box[0] + p.box[2]) / 2, (p.box[1] + p.box[3]) / 2);
    const spot = label(placementLabels, spoken(name), cx, cy + 3, 10);
    el("text", {x: spot[0], y: spot[1], "font-size": 10, fill: "#543", "text-anchor": "middle",
                class: "placement-label halo", "data-placement": name}, names)
      .textContent = spoken(name);
  }
  document.getElementById("command").placeholder = map.example || "";
  for (const name of ["doors", "trail", "scan", "particles", "objects", "people", "robot"])
    layers[name] = el("g", {id: "layer-" + name}, svg);
}

function drawState() {
  if (!map || !state) return;
  for (const g of Object.values(layers)) g.innerHTML = "";
  for (const [name, d] of Object.entries(map.doors)) {
    const [cx, cy] = px(d.x, d.y);
    const s = state.doors[name] || "open";
    el("circle", {cx, cy, r: 5, fill: s === "open" ? "#6c6" : s === "locked" ? "#a00" : "#e80"},
       layers.doors);
  }
  if (state.path && state.path.length > 1)
    el("polyline", {points: state.path.map(p => px(...p).join(",")).join(" "), fill: "none",
                    stroke: "#0a0", "stroke-width": 2, "stroke-dasharray": "6 4", id: "plan"},
       layers.trail);
  if (state.trail.length > 1)
    el("polyline", {points: state.trail.map(p => px(...p).join(",")).join(" "), fill: "none",
                    stroke: "#39f", "stroke-width": 2}, layers.trail);
  for (const p of state.scan || []) el("circle", {cx: px(...p)[0], cy: px(...p)[1], r: 1.5,
                                                   fill: "#e22"}, layers.scan);
  for (const p of state.particles || []) el("circle", {cx: px(...p)[0], cy: px(...p)[1], r: 1,
                                                        fill: "#a3a"}, layers.particles);
  const taken = placementLabels.slice();
  for (const [name, o] of Object.entries(state.objects)) {
    const [cx, cy] = px(...o.xy);
    const c = el("circle", {cx, cy, r: 3, fill: "#08a", "data-object": name, class: "object"},
                 layers.objects);
    el("title", {}, c).textContent = `${name} (on ${o.at})`;
    const spot = label(taken, spoken(name), cx, cy - 4, 9);
    el("text", {x: spot[0], y: spot[1], "font-size": 9, fill: "#057", "text-anchor": "middle",
                class: "object-label halo", "data-object": name}, layers.objects)
      .textContent = spoken(name);
  }
  for (const [name, p] of Object.entries(state.people)) {
    const [cx, cy] = px(...p);
    el("circle", {cx, cy, r: 7, fill: "#f90"}, layers.people);
    const spot = label(taken, name, cx + 9 + name.length * 3, cy + 4, 11);
    el("text", {x: spot[0], y: spot[1], "font-size": 11, "text-anchor": "middle",
                class: "halo"}, layers.people).textContent = name;
  }
  const [x, y, th] = state.robot, [cx, cy] = px(x, y), r = Math.max(6, map.radius * scale);
  el("circle", {cx, cy, r, fill: "none", stroke: "#06c", "stroke-width": 3, id: "robot",
                "data-x": x, "data-y": y}, layers.robot);
  el("line", {x1: cx, y1: cy, x2: cx + 1.8 * r * Math.cos(th), y2: cy - 1.8 * r * Math.sin(th),
              stroke: "#06c", "stroke-width": 3}, layers.robot);
}

function drawPanels() {
  const s = state;
  document.getElementById("status").textContent =
    `t=${s.time.toFixed(1)} s · ${s.fidelity} · speed ${s.speed || "max"}× · ` +
    `robot (${s.robot[0].toFixed(2)}, ${s.robot[1].toFixed(2)}) · ` +
    (s.busy ? "busy" : "idle") + (s.estop ? " · STOPPED" : "") +
    (s.velocity ? ` · v=${s.velocity[0]} m/s · ahead ${s.nearest_ahead} m · ` +
     `slowing ×${s.teleop_scale}` : "");
  document.getElementById("estop").className = s.estop ? "engaged" : "";
  document.getElementById("control").textContent = s.controller === OPERATOR ?
    "you have control" : s.controller ? "someone else has control" : "nobody has control";
  document.getElementById("speech").innerHTML = "";
  for (const line of s.speech) {
    const d = document.createElement("div"); d.textContent = "robot: " + line;
    document.getElementById("speech").appendChild(d);
  }
  const task = document.getElementById("task");
  task.innerHTML = "";
  const head = document.createElement("div");
  head.textContent = s.task.description + (s.task.ended === null ? "" :
    s.task.ended ? " — done" : ` — ${s.task.outcome || "ended"}: ` + s.task.reason);
  head.dataset.outcome = s.task.outcome || "";
  head.id = "task-head";
  task.appendChild(head);
  for (const step of s.task.steps) {
    const d = document.createElement("div");
    d.className = "step " + step.status;
    d.dataset.status = step.status;
    const args = Object.entries(step).filter(([k]) => !["skill", "status", "error",
      "recovery"].includes(k)).map(([k, v]) => `${k}=${JSON.stringify(v)}`).join(", ");
    d.textContent = `${step.recovery ? "↳ " : ""}${step.skill}(${args}) — ${step.status}` +
      (step.error ? ` (${step.error})` : "");
    task.appendChild(d);
  }
  const help = document.getElementById("help");
  if (s.help && !s.busy) {
    help.style.display = "block";
    help.innerHTML = "";
    if (s.help.stopped)
      help.append(`Stopped at step ${s.help.step + 1} (${s.help.skill}): ${s.help.reason}. ` +
        (s.estop ? "Release the stop, then " : "You may help first, then "));
    else
      help.append(`Step ${s.help.step + 1} (${s.help.skill}) failed: ${s.help.reason}. ` +
        `Help on the ${s.help.levels.join(" or ")} level below (map clicks, composer` +
        (s.help.levels.includes("body") ? ", arrow keys" : "") + "), then ");
    const b = document.createElement("button");
    b.textContent = "go on with the task"; b.id = "resume";
    b.onclick = () => api("/api/resume", {});
    help.appendChild(b);
  } else help.style.display = "none";
}

// the head camera, live: what it sees now, drawn for this page (the robot's run is the same
// watched or not). One image at a time, a new one once the home's clock has moved on by a
// quarter of a simulated second and a quarter of a wall second has passed; none while the
// page is hidden (a background tab watches nothing).
const CAMERA_PERIOD = 0.25;
let cameraStamp = -Infinity, cameraAsked = 0, cameraBusy = false;
function drawCamera() {
  const image = document.getElementById("camera"), note = document.getElementById("camera-note");
  if (state.fidelity !== "embodied") {
    image.style.display = "none";
    note.textContent = "no camera: this home is served symbolic (serve with --fidelity " +
      "embodied to see through the robot's head camera)";
    return;
  }
  if (cameraBusy || document.hidden || Math.abs(state.time - cameraStamp) < CAMERA_PERIOD ||
      performance.now() - cameraAsked < CAMERA_PERIOD * 1000) return;
  cameraBusy = true; cameraAsked = performance.now();
  fetchCamera(image, note).finally(() => { cameraBusy = false; });
}
async function fetchCamera(image, note) {
  const response = await fetch("/api/camera.jpg", {headers: {"X-Homebot-Token": TOKEN}});
  if (!response.ok) {
    let data = {};
    try { data = await response.json(); } catch (err) { data = {error: String(response.status)}; }
    note.textContent = data.error || String(response.status);
    return;
  }
  const stamp = parseFloat(response.headers.get("X-Homebot-Stamp"));
  const url = URL.createObjectURL(await response.blob());
  await new Promise((done) => { image.onload = image.onerror = done; image.src = url; });
  if (image.dataset.url) URL.revokeObjectURL(image.dataset.url);
  image.dataset.url = url; image.dataset.stamp = stamp;
  image.style.display = "block";
  cameraStamp = stamp;
  note.textContent = `seen at t=${stamp.toFixed(1)} s (simulated)` + (state.camera == null ?
    "" : ` · the robot itself last looked at t=${state.camera.toFixed(1)} s`);
}

function logEvents(events, lost) {
  const log = document.getElementById("log");
  if (lost) { const d = document.createElement("div"); d.textContent = `(${lost} events skipped)`;
              log.appendChild(d); }
  // one narrated line per event; its raw JSON one click away. An event without a line is the
  // second record of the words the line before says: its JSON joins that line's.
  for (const e of events) {
    const {line, ...raw} = e;
    const last = log.lastElementChild;
    if (line === null && last && last.tagName === "DETAILS") {
      last.querySelector("pre").textContent += "\n" + JSON.stringify(raw, null, 1);
      continue;
    }
    const d = document.createElement("details");
    d.className = "event"; d.dataset.kind = e.kind;
    const summary = document.createElement("summary");
    summary.textContent = `${e.time.toFixed(1)} s  ${line || e.kind}`;
    const json = document.createElement("pre");
    json.textContent = JSON.stringify(raw, null, 1);
    d.append(summary, json);
    log.appendChild(d);
  }
  while (log.childNodes.length > 300) log.removeChild(log.firstChild);
  log.scrollTop = log.scrollHeight;
}

function connect() {
  const proto = location.protocol === "https:" ? "wss" : "ws";
  const ws = new WebSocket(`${proto}://${location.host}/ws?token=${encodeURIComponent(TOKEN)}`);
  ws.onmessage = (message) => {
    const data = JSON.parse(message.data);
    if (data.type === "map") { map = data; drawMap(); }
    else if (data.type === "events") logEvents(data.events, data.lost);
    else if (data.type === "state") { state = data; drawState(); drawPanels(); drawCamera(); }
  };
  ws.onclose = () => { document.getElementById("status").textContent = "disconnected; retrying";
                       setTimeout(connect, 1000); };
}

svg.addEventListener("click", (event) => {
  if (!map) return;
  const point = svg.createSVGPoint(); point.x = event.clientX; point.y = event.clientY;
  const local = point.matrixTransform(svg.getScreenCTM().inverse());
  const [x, y] = world(local.x, local.y);
  const mode = document.querySelector("input[name=click]:checked").value;
  if (mode === "navigate") {
    api("/api/steps", {steps: [{skill: "navigate", to: [+x.toFixed(2), +y.toFixed(2)]}]});
  } else if (state) {
    let best = null, dist = 1e9;
    for (const [name, o] of Object.entries(state.objects)) {
      const d = Math.hypot(o.xy[0] - x, o.xy[1] - y);
      if (d < dist && !o.at.startsWith("hand")) { best = name; dist = d; }
    }
    if (best) api("/api/steps", {steps: [{skill: "pick", object: best}],
                                 description: "pick " + best});
  }
});

const keys = new Set();
document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT") return;
  if (e.key.startsWith("Arrow")) { keys.add(e.key); e.preventDefault(); }
});
document.addEventListener("keyup", (e) => keys.delete(e.key));
setInterval(() => {
  if (!keys.size) return;
  const f = keys.has("ArrowUp") ? 1 : keys.has("ArrowDown") ? -1 : 0;
  const t = keys.has("ArrowLeft") ? 1 : keys.has("ArrowRight") ? -1 : 0;
  api("/api/drive", {vx: f * 10, wz: t * 10});  // the server caps the speeds
}, 100);

document.getElementById("estop").onclick = () => api("/api/estop", {});
document.getElementById("release-estop").onclick = () => api("/api/estop/release", {});
document.getElementById("take").onclick = () => api("/api/control", {action: "take"});
document.getElementById("give-up").onclick = () => api("/api/control", {action: "release"});
document.getElementById("command-form").onsubmit = (e) => {
  e.preventDefault();
  const box = document.getElementById("command");
  api("/api/command", {text: box.value}); box.value = "";
};
document.getElementById("add-step").onclick = () => {
  let args = {};
  try { args = JSON.parse(document.getElementById("args").value || "{}"); }
  catch (err) { document.getElementById("error").textContent = "arguments: " + err; return; }
  composed.push({skill: document.getElementById("skill").value, ...args});
  const li = document.createElement("li"); li.textContent = JSON.stringify(composed.at(-1));
  document.getElementById("composed").appendChild(li);
};
document.getElementById("clear-composed").onclick = () => {
  composed = []; document.getElementById("composed").innerHTML = ""; };
document.getElementById("run-composed").onclick = () => api("/api/steps", {steps: composed});
window.addEventListener("resize", () => { if (map) { drawMap(); drawState(); } });
startHeartbeat().then(connect);
