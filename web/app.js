// ecam designer page: plain JavaScript, no dependencies.
// Talks to `ecam serve`'s JSON endpoints (see docs/modbus.md):
//   GET /api/laws, GET /api/law/NAME?points=N, GET /api/generators,
//   POST /api/keypoints, POST /api/table/gen, GET /api/status.
"use strict";

const $ = (id) => document.getElementById(id);
let generators = [];

async function getJson(url, options) {
  const response = await fetch(url, options);
  const body = await response.json().catch(() => ({ error: response.statusText }));
  if (!response.ok) {
    throw new Error(body.error || response.statusText);
  }
  return body;
}

function mode() {
  return document.querySelector("input[name=mode]:checked").value;
}

// ---------------------------------------------------------------- forms

function fillLaws(laws) {
  const select = $("law-name");
  for (const law of laws) {
    const option = document.createElement("option");
    option.value = law.name;
    option.textContent = law.name;
    option.dataset.info = "Cv " + fmt(law.cv) + "   Ca " + fmt(law.ca) + "   Cj " + fmt(law.cj);
    select.appendChild(option);
  }
  select.value = "cycloid";
  showLawInfo();
}

function showLawInfo() {
  const option = $("law-name").selectedOptions[0];
  $("law-info").textContent = option ? option.dataset.info : "";
}

function fillGenerators(list) {
  generators = list;
  const select = $("gen-name");
  for (const g of list) {
    const option = document.createElement("option");
    option.value = g.name;
    option.textContent = g.title;
    select.appendChild(option);
  }
  buildFields();
}

function buildFields() {
  const g = generators.find((g) => g.name === $("gen-name").value);
  const box = $("gen-fields");
  box.textContent = "";
  if (!g) return;
  for (const f of g.fields) {
    const label = document.createElement("label");
    label.textContent = f.label + " ";
    let input;
    if (f.type === "choice") {
      input = document.createElement("select");
      for (const c of f.choices) {
        const option = document.createElement("option");
        option.value = c;
        option.textContent = c;
        input.appendChild(option);
      }
      input.value = f.default;
    } else if (f.type === "keys") {
      input = document.createElement("textarea");
      input.wrap = "off";
      input.value = f.default;
    } else if (f.type === "bool") {
      input = document.createElement("input");
      input.type = "checkbox";
      input.checked = !!f.default;
    } else {
      input = document.createElement("input");
      input.type = f.type === "int" ? "number" : "text";
      input.value = f.default;
    }
    input.dataset.key = f.key;
    input.dataset.type = f.type;
    label.appendChild(input);
    box.appendChild(label);
  }
}

// Reads the generator form into the `params` object of POST /api/table/gen.
// Key points are read by the server (POST /api/keypoints), which knows
// their line syntax.
async function generatorParams() {
  const params = {};
  for (const input of $("gen-fields").querySelectorAll("[data-key]")) {
    const key = input.dataset.key;
    const type = input.dataset.type;
    if (type === "bool") {
      params[key] = input.checked;
      continue;
    }
    const text = input.value.trim();
    if (text === "") continue;
    if (type === "int") {
      params[key] = Number(text);
    } else if (type === "number") {
      // Arithmetic such as "5/3" is evaluated by the server.
      params[key] = isFinite(Number(text)) ? Number(text) : text;
    } else if (type === "keys") {
      const parsed = await getJson("/api/keypoints", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ lines: text }),
      });
      params[key] = parsed.key;
    } else {
      params[key] = text;
    }
  }
  return params;
}

// ---------------------------------------------------------------- plotting

function fmt(x) {
  if (x === null || x === undefined) return "∞";
  if (typeof x !== "number") return String(x);
  if (x === 0) return "0";
  const a = Math.abs(x);
  if (a >= 1e5 || a < 1e-3) return x.toExponential(3);
  return String(Math.round(x * 1e4) / 1e4);
}

// Tick step of about `target` ticks over `span`: 1, 2 or 5 × 10^k.
function tickStep(span, target) {
  const raw = span / target;
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const unit = raw / power;
  return (unit < 1.5 ? 1 : unit < 3.5 ? 2 : unit < 7.5 ? 5 : 10) * power;
}

function plot(canvas, xs, ys, options) {
  const ctx = canvas.getContext("2d");
  const W = canvas.width;
  const H = canvas.height;
  const pad = { left: 70, right: 14, top: 22, bottom: 26 };
  ctx.clearRect(0, 0, W, H);
  ctx.font = "12px system-ui, sans-serif";

  const finite = ys.filter((y) => typeof y === "number" && isFinite(y));
  let ymin = finite.length ? Math.min(...finite) : 0;
  let ymax = finite.length ? Math.max(...finite) : 1;
  if (ymax - ymin < 1e-12 * Math.max(1, Math.abs(ymax))) {
    ymin -= 1;
    ymax += 1;
  }
  const margin = (ymax - ymin) * 0.06;
  ymin -= margin;
  ymax += margin;
  const xmin = xs[0];
  const xmax = xs[xs.length - 1] === xmin ? xmin + 1 : xs[xs.length - 1];
  const px = (x) => pad.left + ((x - xmin) / (xmax - xmin)) * (W - pad.left - pad.right);
  const py = (y) => H - pad.bottom - ((y - ymin) / (ymax - ymin)) * (H - pad.top - pad.bottom);

  if (options.sync) {
    ctx.fillStyle = "rgba(46, 160, 67, 0.12)";
    ctx.fillRect(px(options.sync[0]), pad.top, px(options.sync[1]) - px(options.sync[0]), H - pad.top - pad.bottom);
  }

  // Grid and tick labels.
  ctx.strokeStyle = "#e6e9ef";
  ctx.fillStyle = "#555";
  ctx.lineWidth = 1;
  const ys0 = tickStep(ymax - ymin, 4);
  ctx.textAlign = "right";
  ctx.textBaseline = "middle";
  for (let y = Math.ceil(ymin / ys0) * ys0; y <= ymax; y += ys0) {
    ctx.beginPath();
    ctx.moveTo(pad.left, py(y));
    ctx.lineTo(W - pad.right, py(y));
    ctx.stroke();
    ctx.fillText(fmt(Math.abs(y) < ys0 * 1e-9 ? 0 : y), pad.left - 6, py(y));
  }
  const xs0 = tickStep(xmax - xmin, 8);
  ctx.textAlign = "center";
  ctx.textBaseline = "top";
  for (let x = Math.ceil(xmin / xs0) * xs0; x <= xmax + xs0 * 1e-9; x += xs0) {
    ctx.beginPath();
    ctx.moveTo(px(x), pad.top);
    ctx.lineTo(px(x), H - pad.bottom);
    ctx.stroke();
    ctx.fillText(fmt(x), px(x), H - pad.bottom + 4);
  }
  if (ymin < 0 && ymax > 0) {
    ctx.strokeStyle = "#9aa3b2";
    ctx.beginPath();
    ctx.moveTo(pad.left, py(0));
    ctx.lineTo(W - pad.right, py(0));
    ctx.stroke();
  }
  ctx.strokeStyle = "#9aa3b2";
  ctx.strokeRect(pad.left, pad.top, W - pad.left - pad.right, H - pad.top - pad.bottom);

  // The curve; a null (infinite) value breaks the line.
  ctx.strokeStyle = options.color;
  ctx.lineWidth = 2;
  ctx.beginPath();
  let pen = false;
  for (let i = 0; i < xs.length; i++) {
    const y = ys[i];
    if (typeof y !== "number" || !isFinite(y)) {
      pen = false;
      continue;
    }
    if (pen && options.steps) {
      // A section slope holds from its point to the next one.
      ctx.lineTo(px(xs[i]), py(ys[i - 1]));
      ctx.lineTo(px(xs[i]), py(y));
    } else if (pen) {
      ctx.lineTo(px(xs[i]), py(y));
    } else {
      ctx.moveTo(px(xs[i]), py(y));
    }
    pen = true;
  }
  ctx.stroke();

  ctx.fillStyle = "#1d2330";
  ctx.textAlign = "left";
  ctx.textBaseline = "top";
  ctx.font = "600 12px system-ui, sans-serif";
  ctx.fillText(options.title, pad.left + 6, 4);
  ctx.font = "12px system-ui, sans-serif";
  ctx.textAlign = "right";
  ctx.fillText(options.xLabel, W - pad.right, 4);
}

// `steps`: draw v, a, j as steps (slopes of a table's straight sections).
function drawAll(x, curves, xLabel, sync, steps) {
  const showJerk = $("show-jerk").checked;
  $("plot-j").hidden = !showJerk;
  const specs = [
    ["plot-s", curves.s, "displacement", "#2d6cdf"],
    ["plot-v", curves.v, "velocity", "#d9822b"],
    ["plot-a", curves.a, "acceleration", "#c23b7a"],
    ["plot-j", curves.j, "jerk", "#6b4fbb"],
  ];
  for (const [id, ys, title, color] of specs) {
    if (id === "plot-j" && !showJerk) continue;
    plot($(id), x, ys, { title, color, xLabel, sync, steps: steps && id !== "plot-s" });
  }
}

function showSummary(entries) {
  const dl = $("summary");
  dl.textContent = "";
  for (const [k, v] of entries) {
    const dt = document.createElement("dt");
    dt.textContent = k;
    const dd = document.createElement("dd");
    dd.textContent = typeof v === "number" ? fmt(v) : String(v);
    dl.append(dt, dd);
  }
}

// ---------------------------------------------------------------- actions

async function draw() {
  $("error").textContent = "";
  updateHash();
  try {
    if (mode() === "law") {
      const name = $("law-name").value;
      const points = $("law-points").value || "201";
      const law = await getJson("/api/law/" + encodeURIComponent(name) + "?points=" + encodeURIComponent(points));
      drawAll(law.u, law, "u (normalised master)", null, false);
      const option = $("law-name").selectedOptions[0];
      showSummary([["law", law.law], ["points", law.u.length], ["characteristics", option ? option.dataset.info : ""]]);
    } else {
      const body = { generator: $("gen-name").value, params: await generatorParams() };
      const table = await getJson("/api/table/gen", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify(body),
      });
      // Prefer the generator's exact design curve (dense samples); a plain
      // table only has its points.
      if (table.design) {
        drawAll(table.design.master, table.design, "master (counts)", table.sync, false);
      } else {
        drawAll(
          table.master,
          { s: table.slave, v: table.velocity, a: table.acceleration, j: table.jerk },
          "master (counts)",
          table.sync,
          !table.exact_kinematics,
        );
      }
      const entries = [["points", table.points]];
      for (const [k, v] of Object.entries(table.summary)) entries.push([k.replace(/_/g, " "), v]);
      if (table.sync) entries.push(["sync zone", table.sync[0] + " .. " + table.sync[1]]);
      for (const [k, v] of Object.entries(table.outputs)) entries.push([k, v]);
      showSummary(entries);
    }
  } catch (err) {
    $("error").textContent = err.message;
  }
}

function switchMode() {
  const law = mode() === "law";
  $("law-form").hidden = !law;
  $("gen-form").hidden = law;
  draw();
}

async function pollStatus() {
  try {
    const s = await getJson("/api/status");
    $("plc-status").textContent =
      "PLC " + (s.program || "(no program)") + " · scans " + s.scans +
      " · t " + (s.sim_time_us / 1e6).toFixed(1) + " s · Modbus " + s.modbus.address;
  } catch (err) {
    $("plc-status").textContent = "PLC: not reachable";
  }
}

// `#law=poly-345` or `#gen=rotary-cut` opens the page on that design
// (links can be shared); the hash follows the selection.
function applyHash() {
  const [kind, name] = decodeURIComponent(location.hash.slice(1)).split("=");
  if (kind === "law" && [...$("law-name").options].some((o) => o.value === name)) {
    $("law-name").value = name;
    showLawInfo();
  } else if (kind === "gen" && generators.some((g) => g.name === name)) {
    document.querySelector("input[name=mode][value=generator]").checked = true;
    $("gen-name").value = name;
    buildFields();
    $("law-form").hidden = true;
    $("gen-form").hidden = false;
  }
}

function updateHash() {
  const hash = mode() === "law" ? "law=" + $("law-name").value : "gen=" + $("gen-name").value;
  history.replaceState(null, "", "#" + hash);
}

async function start() {
  for (const radio of document.querySelectorAll("input[name=mode]")) {
    radio.addEventListener("change", switchMode);
  }
  $("law-name").addEventListener("change", () => { showLawInfo(); draw(); });
  $("law-points").addEventListener("change", draw);
  $("gen-name").addEventListener("change", () => { buildFields(); draw(); });
  $("draw").addEventListener("click", draw);
  $("show-jerk").addEventListener("change", draw);
  for (const form of [$("law-form"), $("gen-form")]) {
    form.addEventListener("submit", (e) => { e.preventDefault(); draw(); });
  }
  try {
    const [laws, gens] = await Promise.all([getJson("/api/laws"), getJson("/api/generators")]);
    fillLaws(laws);
    fillGenerators(gens);
    applyHash();
    await draw();
  } catch (err) {
    $("error").textContent = err.message;
  }
  pollStatus();
  setInterval(pollStatus, 1000);
}

start();
