// ecam designer page. Talks to `ecam serve` (docs/designer.md):
//   GET /api/laws, /api/law/NAME, /api/generators, /api/status, /api/limits,
//   /api/block?name=, POST /api/keypoints, /api/table/gen, /api/table/check,
//   /api/table/read, /api/table/convert, /api/table/load,
//   (segments.js: POST /api/segments/continuous, /api/drive/check),
//   WebSocket /api/live.
// The page keeps no copy of the Rust facts: file formats, table checks,
// impulses, the rounding note, limits and option names come from the server.
// The whole design lives in `state`; the address (#design=…) mirrors it, so
// a link or a reload restores the design. Every edit redraws (debounced);
// an answer to an older edit is dropped, so the plots never show a design
// other than the one in the form.
"use strict";

const $ = (id) => document.getElementById(id);
const fmt = Plots.fmt;

// How the grid's narrow column shows the key-point curves the server names
// (a name without an entry is shown as it is).
const SHORT_CURVE_NAMES = { "constant-acceleration": "const. accel.", "s-type": "S-type", "constant-speed": "const. speed" };
const REDRAW_DELAY_MS = 150;

let generators = [];
let laws = [];
// GET /api/limits: points of a table, key points, key-point curves.
let limits = { table_points: { min: 2, max: 2 }, key_points: 2, key_curves: [] };
let state = null;
// The table of the design last drawn (what downloads and PLC writes send),
// or null when there is none (a law, or an error).
let table = null;
let drawn = 0; // sequence number of the design being drawn
let redrawTimer = 0;
let charts = {};

// ------------------------------------------------------------ helpers

async function api(url, options = {}) {
  const headers = { ...(options.headers || {}) };
  if (options.body !== undefined) headers["Content-Type"] = "application/json";
  const token = $("plc-token").value.trim();
  if (token && options.method === "POST") headers.Authorization = "Bearer " + token;
  const response = await fetch(url, { ...options, headers });
  const body = await response.json().catch(() => ({ error: response.statusText }));
  if (!response.ok) {
    const err = new Error(body.error || response.statusText);
    err.status = response.status;
    throw err;
  }
  return body;
}

function post(url, body) {
  return api(url, { method: "POST", body: JSON.stringify(body) });
}

function el(tag, props = {}, children = []) {
  const node = document.createElement(tag);
  Object.assign(node, props);
  for (const c of children) node.append(c);
  return node;
}

function defaultState() {
  return {
    source: "gen",
    keys: [],
    keyParams: {},
    gen: { name: "rotary-cut", params: {} },
    points: [[0, 0], [1000, 500], [2000, 0]],
    law: { name: "cycloid", points: 1001 },
    block: "D2000",
    jerk: false,
    seg: null, // segments.js: {start, segment, resolution}, the generator's defaults
    drive: Segments.driveDefaults(),
  };
}

// ------------------------------------------------------------ the address

function saveToUrl() {
  history.replaceState(null, "", "#design=" + encodeURIComponent(JSON.stringify(state)));
}

function loadFromUrl() {
  const hash = location.hash.slice(1);
  const base = defaultState();
  if (hash.startsWith("design=")) {
    try {
      const saved = JSON.parse(decodeURIComponent(hash.slice(7)));
      return { ...base, ...saved };
    } catch (err) {
      showError("the address holds no readable design (" + err.message + "); starting afresh");
      return base;
    }
  }
  // Older links: #law=NAME, #gen=NAME.
  const [kind, name] = decodeURIComponent(hash).split("=");
  if (kind === "law" && name) return { ...base, source: "law", law: { ...base.law, name } };
  if (kind === "gen" && name) return { ...base, source: "gen", gen: { name, params: {} } };
  return base;
}

// ------------------------------------------------------------ forms from the schema

// Builds inputs for `fields` (GET /api/generators) into `box`, showing
// `values` (or the defaults); `onInput(key, value)` on every edit.
function renderFields(box, fields, values, onInput) {
  box.textContent = "";
  for (const f of fields) {
    const value = values[f.key] !== undefined ? values[f.key] : f.default;
    let input;
    if (f.type === "choice") {
      input = el("select");
      for (const c of f.choices) input.append(el("option", { value: c, textContent: c }));
      input.value = value;
    } else if (f.type === "bool") {
      input = el("input", { type: "checkbox", checked: !!value });
    } else if (f.type === "keys") {
      input = el("textarea", { wrap: "off", value: value });
    } else {
      input = el("input", { type: "text", value: value === null ? "" : String(value), spellcheck: false });
      if (f.type === "int") {
        input.inputMode = "numeric";
        if (f.min !== undefined) input.placeholder = f.default === "" ? `${f.min} … ${f.max}` : "";
      }
    }
    input.dataset.key = f.key;
    input.name = f.key;
    const read = () => (f.type === "bool" ? input.checked : input.value);
    input.addEventListener(f.type === "bool" || f.type === "choice" ? "change" : "input", () => onInput(f.key, read()));
    const label = el("label", { title: f.help || "" }, [
      el("span", { className: "field-name", textContent: f.label }),
      el("span", { className: "field-input" }, [input, f.unit ? el("span", { className: "unit", textContent: f.unit }) : ""]),
    ]);
    box.append(label);
  }
}

// The `params` of POST /api/table/gen from values typed in a form: whole
// numbers as numbers, other numbers as numbers or as arithmetic ("5/3",
// read by the server), empty fields left to the generator's default.
function paramsOf(fields, values) {
  const params = {};
  for (const f of fields) {
    const raw = values[f.key];
    if (raw === undefined) continue;
    if (f.type === "bool") { params[f.key] = !!raw; continue; }
    const text = String(raw).trim();
    if (text === "" || f.type === "keys") continue;
    if (f.type === "int") params[f.key] = /^[-+]?\d+$/.test(text) ? Number(text) : text;
    else if (f.type === "number") params[f.key] = Number.isFinite(Number(text)) ? Number(text) : text;
    else params[f.key] = text;
  }
  return params;
}

function generator(name) {
  return generators.find((g) => g.name === name);
}

// ------------------------------------------------------------ key point grid

function renderKeysGrid() {
  const body = $("keys-grid").tBodies[0];
  body.textContent = "";
  state.keys.forEach((k, i) => {
    const cell = (field, attrs = {}) => {
      const input = el("input", { type: "text", value: String(k[field]), inputMode: "numeric", spellcheck: false, ...attrs });
      input.dataset.row = i;
      input.dataset.field = field;
      input.addEventListener("input", () => {
        k[field] = input.value.trim() === "" ? "" : Number(input.value);
        if (Number.isNaN(k[field])) k[field] = input.value;
        changed();
      });
      return el("td", {}, [input]);
    };
    const law = el("select");
    for (const c of limits.key_curves) law.append(el("option", { value: c, textContent: SHORT_CURVE_NAMES[c] || c, title: c }));
    law.value = k.curve;
    law.dataset.row = i;
    law.dataset.field = "curve";
    law.disabled = i === 0;
    law.title = i === 0 ? "the first key point starts the table" : "law of the segment ending here";
    law.addEventListener("change", () => { k.curve = law.value; changed(); });
    const remove = el("button", { type: "button", className: "icon", textContent: "×", title: "remove this key point" });
    remove.disabled = state.keys.length <= 2;
    remove.addEventListener("click", () => { state.keys.splice(i, 1); renderKeysGrid(); changed(); });
    body.append(el("tr", {}, [
      el("td", { className: "num", textContent: String(i + 1) }),
      cell("master"), cell("slave"), el("td", {}, [law]), cell("resolution", { className: "narrow" }),
      el("td", {}, [remove]),
    ]));
  });
  $("keys-add").disabled = state.keys.length >= limits.key_points;
}

function renderPointsGrid() {
  const body = $("points-grid").tBodies[0];
  body.textContent = "";
  state.points.forEach((p, i) => {
    const cell = (j) => {
      const input = el("input", { type: "text", value: String(p[j]), inputMode: "numeric", spellcheck: false });
      input.dataset.row = i;
      input.dataset.field = j === 0 ? "master" : "slave";
      input.addEventListener("input", () => { p[j] = Number(input.value); changed(); });
      return el("td", {}, [input]);
    };
    const remove = el("button", { type: "button", className: "icon", textContent: "×", title: "remove this point" });
    remove.disabled = state.points.length <= 2;
    remove.addEventListener("click", () => { state.points.splice(i, 1); renderPointsGrid(); changed(); });
    body.append(el("tr", {}, [el("td", { className: "num", textContent: String(i + 1) }), cell(0), cell(1), el("td", {}, [remove])]));
  });
  $("points-add").disabled = state.points.length >= limits.table_points.max;
}

// Writes a dragged value into the grid's input without rebuilding it (the
// user may be typing in another cell).
function showInGrid(gridId, row, field, value) {
  const input = $(gridId).querySelector(`[data-row="${row}"][data-field="${field}"]`);
  if (input) input.value = String(value);
}

// ------------------------------------------------------------ the panes

function showSource() {
  Segments.show(state.source === "segments");
  for (const source of ["keys", "gen", "points", "law", "segments"]) {
    $("pane-" + source).hidden = state.source !== source;
    const tab = $("tab-" + source);
    tab.setAttribute("aria-selected", String(state.source === source));
  }
  if (state.source === "keys") renderKeysGrid();
  if (state.source === "points") renderPointsGrid();
  if (state.source === "gen") showGeneratorSummary();
  if (state.source === "law") {
    $("law-name").value = state.law.name;
    $("law-points").value = state.law.points;
    showLawInfo();
  }
  const tableless = state.source === "law";
  for (const id of ["download-csv", "download-json", "plc-write", "to-points"]) {
    $(id).disabled = tableless;
    $(id).title = tableless ? "a motion law is a normalised curve, not a table" : "";
  }
}

function showGeneratorSummary() {
  const g = generator(state.gen.name);
  if (!g) { $("gen-summary").textContent = "unknown generator " + state.gen.name; return; }
  const set = Object.entries(state.gen.params).filter(([, v]) => String(v).trim() !== "");
  $("gen-summary").textContent = g.title + (set.length ? " — " + set.map(([k, v]) => `${k} ${v}`).join(", ") : " — defaults");
}

function showLawInfo() {
  const law = laws.find((l) => l.name === $("law-name").value);
  $("law-info").textContent = law ? `Cv ${fmt(law.cv)}   Ca ${fmt(law.ca)}   Cj ${fmt(law.cj)}` : "";
}

// ------------------------------------------------------------ generator dialog

let dialogValues = {};

function openGeneratorDialog() {
  const select = $("gen-name");
  select.value = generator(state.gen.name) ? state.gen.name : "rotary-cut";
  dialogValues = select.value === state.gen.name ? { ...state.gen.params } : {};
  renderDialogFields();
  $("gen-error").textContent = "";
  $("gen-dialog").showModal();
}

function renderDialogFields() {
  const g = generator($("gen-name").value);
  $("gen-about").textContent = g ? g.about || "" : "";
  renderFields($("gen-fields"), g ? g.fields : [], dialogValues, (key, value) => { dialogValues[key] = value; });
}

// Applies the dialog: the generator is tried first, so a refused set of
// parameters keeps the dialog open with the generator's message.
async function applyGeneratorDialog(event) {
  event.preventDefault();
  const name = $("gen-name").value;
  const g = generator(name);
  try {
    await post("/api/table/gen", { generator: name, params: paramsOf(g.fields, dialogValues) });
  } catch (err) {
    $("gen-error").textContent = err.message;
    return;
  }
  state.source = "gen";
  state.gen = { name, params: { ...dialogValues } };
  $("gen-dialog").close();
  showSource();
  changed(true);
}

// ------------------------------------------------------------ drawing

function changed(now = false) {
  saveToUrl();
  markStale();
  clearTimeout(redrawTimer);
  if (now) redraw();
  else redrawTimer = setTimeout(redraw, REDRAW_DELAY_MS);
}

function markStale() {
  $("plots").classList.add("updating");
  $("plots-state").textContent = "updating…";
}

function showError(message) {
  $("error").textContent = message;
}

async function redraw() {
  const seq = ++drawn;
  const current = () => seq === drawn;
  showError("");
  try {
    let result;
    if (state.source === "law") result = await computeLaw();
    else if (state.source === "points") result = await computePoints();
    else result = await computeTable();
    if (!current()) return;
    table = result.table;
    draw(result);
    if (result.segments) Segments.report(result);
    $("plots").classList.remove("updating", "failed");
    $("plots-state").textContent = "";
  } catch (err) {
    if (!current()) return;
    // No plot of an older design stays on screen beside an error.
    table = null;
    clearPlots();
    showError(err.message);
    $("plots").classList.remove("updating");
    $("plots").classList.add("failed");
    $("plots-state").textContent = "no valid design";
  }
}

async function computeLaw() {
  const points = Number(state.law.points) || 1001;
  const law = await api(`/api/law/${encodeURIComponent(state.law.name)}?points=${points}`);
  const info = laws.find((l) => l.name === law.law) || {};
  return {
    kind: "law",
    title: "Motion law " + law.law + " (normalised rise)",
    x: law.u, s: law.s, v: law.v, a: law.a, j: law.j,
    units: { x: "u (master / segment)", s: "s (stroke)", v: "ds/du", a: "d²s/du²", j: "d³s/du³" },
    summary: [["law", law.law], ["samples", law.u.length], ["Cv", fmt(info.cv)], ["Ca", fmt(info.ca)], ["Cj", fmt(info.cj)]],
    table: null,
  };
}

function keysBody() {
  const g = generator("keypoints");
  const params = paramsOf(g ? g.fields : [], state.keyParams);
  params.key = state.keys.map((k) => ({ master: k.master, slave: k.slave, curve: k.curve, resolution: k.resolution === "" ? 0 : k.resolution }));
  return { generator: "keypoints", params };
}

async function computeTable() {
  let body;
  if (state.source === "keys") {
    body = keysBody();
  } else if (state.source === "segments") {
    body = Segments.body();
  } else {
    const g = generator(state.gen.name);
    if (!g) throw new Error(`unknown generator \`${state.gen.name}\``);
    body = { generator: state.gen.name, params: paramsOf(g.fields, state.gen.params) };
  }
  const t = await post("/api/table/gen", body);
  const g = generator(t.generator);
  const result = {
    kind: "table",
    title: (g ? g.title : t.generator) + ` — ${t.points} points`,
    units: UNITS_COUNTS,
    sync: t.sync,
    tableX: t.master, tableS: t.slave,
    summary: summaryOf(t),
    steps: t.steps,
    table: {
      name: t.generator,
      master: t.master, slave: t.slave,
      velocity: t.velocity, acceleration: t.acceleration, jerk: t.jerk,
      sync: t.sync,
      // A segment cam travels with its table (JSON downloads keep it).
      segments: t.segments ? { start: t.segments.start, segments: t.segments.segment } : null,
    },
    segments: t.segments,
  };
  if (t.design) {
    Object.assign(result, { x: t.design.master, s: t.design.s, v: t.design.v, a: t.design.a, j: t.design.j, exact: true, design: true });
    result.note = "Curves: the generator's exact curve before rounding to the table (dots: the table's points); arrows: its steps as impulses (Δv in acceleration, Δa in jerk).";
  } else {
    Object.assign(result, { x: t.master, s: t.slave, v: t.velocity, a: t.acceleration, j: t.jerk, exact: t.exact_kinematics });
    result.note = t.exact_kinematics
      ? "Velocity, acceleration and jerk of the exact curve at the table's points (dots; between points the table is straight); arrows: its steps as impulses."
      : "Velocity, acceleration and jerk are the slopes of the table's straight sections, each held to the next point.";
  }
  if (state.source === "segments") result.keyMarkers = Segments.markers();
  if (state.source === "keys") result.keyMarkers = state.keys.map((k) => [Number(k.master), Number(k.slave) + Number(state.keyParams.initial_slave || 0)]);
  return result;
}

const UNITS_COUNTS = { x: "master (counts)", s: "slave (pulses)", v: "pulses/count", a: "pulses/count²", j: "pulses/count³" };

// A point table: straight sections, so velocity steps at each point and
// acceleration is an impulse there (arrows). The server checks the table
// and says where its velocity steps.
async function computePoints() {
  const t = await post("/api/table/check", { points: state.points });
  const stroke = t.summary.stroke;
  return {
    kind: "points",
    title: `Point table — ${t.points} points`,
    units: UNITS_COUNTS,
    x: t.master, s: t.slave, v: t.velocity, a: null, j: null, stepped: true,
    steps: t.steps,
    note: "Straight sections: velocity holds from each point to the next; the acceleration is an impulse at each point (arrows: the velocity step Δv). A point table has no jerk to draw.",
    keyMarkers: t.master.map((m, i) => [m, t.slave[i]]),
    summary: [["points", t.points], ["master span", t.summary.master_span], ["stroke", stroke],
      ["peak velocity", fmt(t.summary.peak_velocity)], ["continuity", t.summary.continuity]],
    table: { name: "table", master: t.master, slave: t.slave, sync: null },
  };
}

const SUMMARY_LABELS = {
  sections: "sections", master_span: "master span", stroke: "stroke", slave_min: "slave min",
  slave_max: "slave max", peak_velocity: "peak velocity (table)", peak_acceleration: "peak acceleration (table)",
  design_peak_velocity: "peak velocity (design)", design_peak_acceleration: "peak acceleration (design)",
  continuity: "continuity (table)", seam: "seam (table)", design_continuity: "continuity (design)", note: "note",
};

// The server's summary, in its order; its `note` (the rounding ripple) last.
function summaryOf(t) {
  const rows = [["points", t.points]];
  for (const [k, v] of Object.entries(t.summary || {})) {
    if (v === null || v === undefined || k === "note") continue;
    rows.push([SUMMARY_LABELS[k] || k.replace(/_/g, " "), typeof v === "number" ? fmt(v) : v]);
  }
  if (t.summary && t.summary.note) rows.push(["note", t.summary.note]);
  const outputs = Object.entries(t.outputs || {});
  if (t.sync && !outputs.some(([k]) => k === "sync zone")) rows.push(["sync zone", `${t.sync[0]} … ${t.sync[1]}`]);
  for (const [k, v] of outputs) rows.push([k, v]);
  return rows;
}

function makeDesignCharts() {
  const sync = "design";
  charts.s = Plots.create($("plot-s"), {
    title: "Displacement", xLabel: "master (counts)", yLabel: "slave (pulses)", syncKey: sync,
    series: [
      { label: "slave", color: Plots.COLORS.s },
      { label: "table points", color: Plots.COLORS.points, points: true, size: 3, width: 1 },
      { label: "key points", color: Plots.COLORS.s, points: true, size: 11 },
    ],
  });
  // Each derivative twice: as a curve, and as values at the table's points
  // only (a table without its design curve: nothing is known between points).
  const derivative = (id, title, unit, label, color) => Plots.create($(id), {
    title, xLabel: "master (counts)", yLabel: unit, syncKey: sync,
    series: [{ label, color }, { label: label + " at the points", color, points: true, size: 5 }],
  });
  charts.v = derivative("plot-v", "Velocity", "pulses/count", "velocity", Plots.COLORS.v);
  charts.a = derivative("plot-a", "Acceleration", "pulses/count²", "acceleration", Plots.COLORS.a);
  charts.j = derivative("plot-j", "Jerk", "pulses/count³", "jerk", Plots.COLORS.j);
  Plots.draggable(charts.s, 3, onDragMarker, () => changed(true));
}

// A key point (or table point) dragged on the displacement chart: whole
// counts, kept strictly between its neighbours' masters.
function onDragMarker(i, x, y) {
  if (state.source === "segments") {
    Segments.drag(i, x, y);
    moveMarkers(Segments.markers());
    changed();
    return;
  }
  const list = state.source === "keys" ? state.keys : state.source === "points" ? state.points : null;
  if (!list || i >= list.length) return;
  const masterOf = (p) => Number(state.source === "keys" ? p.master : p[0]);
  const lo = i > 0 ? masterOf(list[i - 1]) + 1 : -Infinity;
  const hi = i + 1 < list.length ? masterOf(list[i + 1]) - 1 : Infinity;
  const master = Math.min(hi, Math.max(lo, Math.round(x)));
  const offset = state.source === "keys" ? Number(state.keyParams.initial_slave || 0) : 0;
  const slave = Math.round(y) - offset;
  if (state.source === "keys") {
    Object.assign(list[i], { master, slave });
    showInGrid("keys-grid", i, "master", master);
    showInGrid("keys-grid", i, "slave", slave);
  } else {
    list[i] = [master, slave];
    showInGrid("points-grid", i, "master", master);
    showInGrid("points-grid", i, "slave", slave);
  }
  moveMarkers(list.map((p) => [masterOf(p), (state.source === "keys" ? Number(p.slave) : p[1]) + offset]));
  changed();
}

// Moves the markers at once; the curve follows when the server answers.
function moveMarkers(markers) {
  const u = charts.s.u;
  const data = Plots.join([
    { x: u.data[0].filter((_, k) => u.data[1][k] !== null), y: u.data[1].filter((v) => v !== null) },
    { x: u.data[0].filter((_, k) => u.data[2][k] !== null), y: u.data[2].filter((v) => v !== null) },
    { x: markers.map((m) => m[0]), y: markers.map((m) => m[1]) },
  ]);
  u.setData(data, false);
  u.redraw();
}

function draw(r) {
  $("plots-title").textContent = r.title;
  $("plot-note").textContent = r.note || "";
  const units = r.units;
  for (const [key, axis] of [["s", units.s], ["v", units.v], ["a", units.a], ["j", units.j]]) {
    charts[key].u.axes[0].label = units.x;
    charts[key].u.axes[1].label = axis;
    charts[key].u.series[0].label = units.x;
  }
  const markers = r.keyMarkers || [];
  const parts = [{ x: r.x, y: r.s }, { x: r.tableX || [], y: r.tableS || [] }, { x: markers.map((m) => m[0]), y: markers.map((m) => m[1]) }];
  Plots.set(charts.s, Plots.join(parts), { sync: r.sync });
  showSeries(charts.s, 2, !!r.tableX);
  showSeries(charts.s, 3, markers.length > 0);
  // Section slopes hold from a point to the next (steps); values of the
  // exact curve known only at the points are dots; dense curves are lines.
  const dots = r.kind === "table" && !r.design && r.exact;
  const stepped = r.stepped || (r.kind === "table" && !r.exact);
  const none = r.x.map(() => null);
  const setDerivative = (key, ys, extra) => {
    const chart = charts[key];
    chart.u.series[1].paths = stepped ? uPlot.paths.stepped({ align: 1 }) : uPlot.paths.linear();
    Plots.set(chart, [r.x, dots ? none : ys, dots ? ys : none], { sync: r.sync, ...extra });
    showSeries(chart, 1, !dots);
    showSeries(chart, 2, dots);
  };
  setDerivative("v", r.v);
  const hasA = r.a !== null;
  // Impulses where the server's steps are: a velocity step is an
  // acceleration impulse (Δv), an acceleration step a jerk impulse (Δa).
  const steps = r.steps || { velocity: [], acceleration: [] };
  setDerivative("a", hasA ? r.a : r.x.map(() => 0), { impulses: { quantity: "Δv", steps: steps.velocity } });
  // A point table's acceleration is impulses only: it has no jerk to draw.
  $("show-jerk").disabled = !hasA;
  $("show-jerk").parentElement.title = hasA ? "" : "a point table's acceleration is impulses only: it has no jerk to draw";
  $("plot-j").hidden = !state.jerk || !hasA;
  if (state.jerk && hasA) {
    setDerivative("j", r.j, { impulses: { quantity: "Δa", steps: steps.acceleration } });
  }
  showSummary(r.summary);
}

function showSeries(chart, index, show) {
  if (chart.u.series[index].show !== show) chart.u.setSeries(index, { show });
}

function clearPlots() {
  for (const key of Object.keys(charts)) {
    if (!key.startsWith("live")) Plots.set(charts[key], charts[key].u.data.map(() => []));
  }
  showSummary([]);
}

function showSummary(rows) {
  const dl = $("summary");
  dl.textContent = "";
  for (const [k, v] of rows) dl.append(el("dt", { textContent: k }), el("dd", { textContent: String(v) }));
}

// ------------------------------------------------------------ files

function download(name, type, text) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = el("a", { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// The same formats as `ecam table gen -o` (docs/cli.md, "File formats"),
// written by the server.
async function downloadTable(format) {
  if (!table) return;
  const body = { format, points: table.master.map((m, i) => [m, table.slave[i]]), sync: table.sync };
  if (table.name !== "table") body.generator = table.name;
  if (table.velocity) Object.assign(body, { velocity: table.velocity, acceleration: table.acceleration, jerk: table.jerk });
  if (table.segments) body.segments = table.segments;
  try {
    const file = await post("/api/table/convert", body);
    download(fileStem() + "." + format, format === "csv" ? "text/csv" : "application/json", file.text);
  } catch (err) {
    showError(err.message);
  }
}

function fileStem() {
  return table ? table.name : "table";
}

async function upload(event) {
  const file = event.target.files[0];
  event.target.value = "";
  if (!file) return;
  try {
    // Read by the server as `ecam table show` reads it.
    const read = await post("/api/table/read", { name: file.name, text: await file.text() });
    state.source = "points";
    state.points = read.points;
    showSource();
    changed(true);
  } catch (err) {
    showError(err.message);
  }
}

function toPoints() {
  if (!table) return;
  state.points = table.master.map((m, i) => [m, table.slave[i]]);
  state.source = "points";
  showSource();
  changed(true);
}

// ------------------------------------------------------------ write to the PLC

// Where the DECAM block starts, as the server reads the typed name (its
// message names the device's kind when it is not one).
async function blockNumber() {
  return (await api("/api/block?name=" + encodeURIComponent($("plc-block").value.trim()))).block;
}

async function writeToPlc(whileRunning) {
  $("plc-conflict").hidden = true;
  const out = $("plc-result");
  out.className = "hint";
  if (!table) { out.textContent = "nothing to write: the design has no valid table"; out.className = "error"; return; }
  let block;
  try { block = await blockNumber(); } catch (err) { out.textContent = err.message; out.className = "error"; return; }
  const body = { block, points: table.master.map((m, i) => [m, table.slave[i]]) };
  if (whileRunning) body.while_running = "at-seam";
  out.textContent = "writing…";
  try {
    const answer = await post("/api/table/load", body);
    const when = answer.switch === "at-seam" ? "the running cam takes it at its next seam" : "taken now";
    out.textContent = `Written to D${answer.block}: ${answer.points} points, one journalled record; ${when}. (${new Date().toLocaleTimeString()})`;
    out.className = "ok";
  } catch (err) {
    if (err.status === 409) {
      $("plc-conflict-text").textContent = err.message.replace(/: send .*/, ".") + " Switch tables at the end of its current cycle, or cancel?";
      $("plc-conflict").hidden = false;
      out.textContent = "";
    } else if (err.status === 401) {
      $("plc-token-row").hidden = false;
      out.textContent = "the server wants a token for writes: type it above and write again";
      out.className = "error";
    } else {
      out.textContent = "not written: " + err.message;
      out.className = "error";
    }
  }
}

// ------------------------------------------------------------ live view

const LIVE_WINDOW_US = 20e6;
let live = { socket: null, block: null, retry: 0, t: [], master: [], slave: [], vm: [], vs: [], zones: [] };

function makeLiveCharts() {
  charts.livePos = Plots.create($("live-pos"), {
    title: "Position", xLabel: "PLC time (s)", yLabel: "counts / pulses", syncKey: "live",
    series: [{ label: "master in cycle (counts)", color: Plots.COLORS.master }, { label: "slave (pulses)", color: Plots.COLORS.slave }],
  });
  charts.liveVel = Plots.create($("live-vel"), {
    title: "Speed (shaded: sync output on)", xLabel: "PLC time (s)", yLabel: "per second", syncKey: "live",
    // A sample with no PLC time since the last has no speed: bridge it.
    series: [{ label: "master (counts/s)", color: Plots.COLORS.vmaster, spanGaps: true }, { label: "slave (pulses/s)", color: Plots.COLORS.vslave, spanGaps: true }],
  });
}

async function liveConnect() {
  liveClose();
  if (!$("live-on").checked) { $("live-state").textContent = "off"; return; }
  let block;
  try { block = await blockNumber(); } catch (err) { $("live-state").textContent = err.message; return; }
  if (live.socket) return; // a later connect finished first
  const scheme = location.protocol === "https:" ? "wss:" : "ws:";
  const socket = new WebSocket(`${scheme}//${location.host}/api/live?block=${block}&rate=20`);
  live = { socket, block, retry: live.retry, t: [], mic: [], slave: [], vm: [], vs: [], zones: [], syncFrom: null };
  $("live-block").textContent = "D" + block;
  $("live-state").textContent = "connecting…";
  socket.onopen = () => { live.retry = 0; $("live-state").textContent = "connected"; };
  socket.onmessage = (event) => onLiveSample(JSON.parse(event.data));
  socket.onclose = () => {
    if (live.socket !== socket) return;
    $("live-state").textContent = "disconnected — retrying";
    live.retry = Math.min(live.retry + 1, 5);
    setTimeout(() => { if (live.socket === socket) liveConnect(); }, 1000 * live.retry);
  };
}

function liveClose() {
  if (live.socket) {
    const s = live.socket;
    live.socket = null;
    s.close();
  }
}

function onLiveSample(s) {
  const t = s.time_us / 1e6;
  live.t.push(t);
  live.mic.push(s.master_in_cycle);
  live.slave.push(s.slave);
  live.vm.push(s.master_velocity);
  live.vs.push(s.slave_velocity);
  const syncOn = s.sync_output.enabled ? s.sync_output.on === true : s.in_sync;
  if (syncOn && live.syncFrom === null) live.syncFrom = t;
  if (!syncOn && live.syncFrom !== null) { live.zones.push([live.syncFrom, t]); live.syncFrom = null; }
  while (live.t.length && live.t[0] < t - LIVE_WINDOW_US / 1e6) {
    for (const k of ["t", "mic", "slave", "vm", "vs"]) live[k].shift();
  }
  live.zones = live.zones.filter((z) => z[1] >= live.t[0]);
  const zones = live.syncFrom !== null ? [...live.zones, [live.syncFrom, t]] : live.zones;
  Plots.set(charts.livePos, [live.t, live.mic, live.slave]);
  Plots.set(charts.liveVel, [live.t, live.vm, live.vs], { sync: zones });
  $("live-state").textContent = s.running ? "cam running" : "cam stopped";
  $("live-state").dataset.state = s.running ? "running" : "stopped";
  $("ro-mode").textContent = s.mode + (s.error ? ` (error ${s.error})` : "");
  // Offsets 27/28 and 25/26: the same place in the cycle, before and after the master zoom.
  $("ro-master").textContent = s.master === s.master_in_cycle ? String(s.master) : `${s.master} (zoomed ${s.master_in_cycle})`;
  $("ro-slave").textContent = String(s.slave);
  $("ro-speed").textContent = s.slave_velocity === null ? "–" : `${fmt(Math.round(s.slave_velocity))} pulses/s`;
  $("ro-sync").textContent = `${s.sync_output.device} ${s.sync_output.enabled ? (s.sync_output.on ? "on" : "off") : "not driven"}${s.in_sync ? " · in sync area" : ""}`;
}

// ------------------------------------------------------------ status

async function pollStatus() {
  const badge = $("plc-status");
  try {
    const s = await api("/api/status");
    badge.textContent = `${s.program || "no program"} · ${s.scans} scans · ${(s.sim_time_us / 1e6).toFixed(1)} s · Modbus ${s.modbus.address}`;
    badge.dataset.state = s.running ? "running" : "stopped";
  } catch (err) {
    badge.textContent = "PLC not reachable";
    badge.dataset.state = "down";
  }
}

// ------------------------------------------------------------ start

// The keypoints generator's default key points, read by the server.
async function defaultKeys() {
  const field = generator("keypoints").fields.find((f) => f.type === "keys");
  return (await post("/api/keypoints", { lines: field.default })).key;
}

// The keypoints generator's other parameters (total points, initial slave), under the grid.
function renderKeyParams() {
  const keyFields = generator("keypoints").fields.filter((f) => f.type !== "keys");
  renderFields($("keys-params"), keyFields, state.keyParams, (key, value) => { state.keyParams[key] = value; changed(); });
}

async function start() {
  state = loadFromUrl();
  makeDesignCharts();
  makeLiveCharts();
  try {
    [laws, generators, limits] = await Promise.all([api("/api/laws"), api("/api/generators"), api("/api/limits")]);
  } catch (err) {
    showError("the server's design API did not answer: " + err.message);
    return;
  }
  for (const l of laws) $("law-name").append(el("option", { value: l.name, textContent: l.name }));
  // The Key points tab is the keypoints generator's grid; the dialog offers the others.
  // Segments have their own tab too.
  for (const g of generators.filter((g) => g.name !== "keypoints" && g.name !== "segments")) $("gen-name").append(el("option", { value: g.name, textContent: g.title }));
  if (state.keys.length === 0) state.keys = await defaultKeys();
  if (!state.seg) state.seg = Segments.defaults(generator("segments"));
  Segments.init({
    state: () => state, changed, post, el, fmt, showError, laws: () => laws,
  });
  renderKeyParams();

  for (const tab of document.querySelectorAll("[data-source]")) {
    tab.addEventListener("click", () => { state.source = tab.dataset.source; showSource(); changed(true); });
  }
  $("keys-add").addEventListener("click", () => {
    const last = state.keys[state.keys.length - 1];
    state.keys.push({ master: Number(last.master) + 500, slave: Number(last.slave), curve: "cycloid", resolution: 0 });
    renderKeysGrid();
    changed(true);
  });
  $("points-add").addEventListener("click", () => {
    const last = state.points[state.points.length - 1];
    state.points.push([last[0] + 100, last[1]]);
    renderPointsGrid();
    changed(true);
  });
  $("law-name").addEventListener("change", () => { state.law.name = $("law-name").value; showLawInfo(); changed(true); });
  $("law-points").addEventListener("input", () => { state.law.points = Number($("law-points").value); changed(); });
  $("gen-open").addEventListener("click", openGeneratorDialog);
  $("gen-name").addEventListener("change", () => { dialogValues = {}; renderDialogFields(); $("gen-error").textContent = ""; });
  $("gen-form").addEventListener("submit", applyGeneratorDialog);
  $("gen-cancel").addEventListener("click", () => $("gen-dialog").close());
  $("show-jerk").checked = !!state.jerk;
  $("show-jerk").addEventListener("change", () => { state.jerk = $("show-jerk").checked; changed(true); });
  $("download-csv").addEventListener("click", () => downloadTable("csv"));
  $("download-json").addEventListener("click", () => downloadTable("json"));
  $("upload").addEventListener("change", upload);
  $("to-points").addEventListener("click", toPoints);
  $("plc-block").value = state.block;
  $("plc-block").addEventListener("change", () => { state.block = $("plc-block").value.trim(); saveToUrl(); liveConnect(); });
  $("plc-write").addEventListener("click", () => writeToPlc(false));
  $("plc-at-seam").addEventListener("click", () => writeToPlc(true));
  $("plc-cancel").addEventListener("click", () => { $("plc-conflict").hidden = true; $("plc-result").textContent = "not written"; });
  $("live-on").addEventListener("change", liveConnect);

  // A design link pasted into this tab (only the address' hash changes).
  window.addEventListener("hashchange", async () => {
    if (location.hash === "#design=" + encodeURIComponent(JSON.stringify(state))) return;
    state = loadFromUrl();
    if (state.keys.length === 0) state.keys = await defaultKeys();
    if (!state.seg) state.seg = Segments.defaults(generator("segments"));
    Segments.refreshDriveFields();
    renderKeyParams();
    $("show-jerk").checked = !!state.jerk;
    $("plc-block").value = state.block;
    showSource();
    changed(true);
    liveConnect();
  });

  showSource();
  changed(true);
  liveConnect();
  pollStatus();
  setInterval(pollStatus, 2000);
}

start();
