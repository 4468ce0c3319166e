// The segment editor of the designer page (docs/designer.md, "Segments"):
// interpolation points joined by segments, each with its law and the
// boundary values the task fixes (empty = free), the continuity at every
// point and each segment's Cv/Ca/Cj from the server, "Make continuous",
// and the drive check. app.js owns the page; this module owns the
// segments' part of the design (`state.seg`, `state.drive`) and is called
// from app.js at a few hooks (render, body, markers, report, drag).
//   POST /api/table/gen {"generator": "segments", ...}  (through app.js)
//   POST /api/segments/continuous, POST /api/drive/check
"use strict";

const Segments = (() => {
  // The laws a segment may follow: the solved ones first (GET /api/laws
  // adds the eleven motion laws).
  const SOLVED = [["poly-5", "poly-5"], ["poly-7", "poly-7"], ["vv-cycloid", "vv-cycloid"]];
  const BOUNDARY = ["velocity", "acceleration", "jerk"];
  // The pick-and-place axis of examples/tables/drive-pick-and-place.toml.
  const DRIVE_FIELDS = [
    ["mechanics", "units_per_motor_rev", "pulses per motor rev", 2000, ""],
    ["mechanics", "gear_ratio", "gear ratio (motor : load)", 3, ""],
    ["mechanics", "load_inertia", "load inertia", 0.0045, "kg·m²"],
    ["mechanics", "motor_inertia", "motor inertia", 0.00012, "kg·m²"],
    ["mechanics", "friction_torque", "friction torque (load)", 0.3, "N·m"],
    ["mechanics", "load_torque", "constant load torque", 0, "N·m"],
    ["limits", "max_speed", "max motor speed", 3000, "rpm"],
    ["limits", "peak_torque", "peak torque", 1.3, "N·m"],
    ["limits", "rms_torque", "RMS torque", 0.45, "N·m"],
    ["limits", "max_jerk", "max jerk (empty: none)", "", "pulses/s³"],
    ["run", "master_speed", "master speed", 3600, "counts/s"],
  ];

  let ctx = null; // {state(), changed(now), post(url, body), el, fmt, showError, laws()}
  let checked = 0; // sequence of drive checks, to drop stale answers

  function driveDefaults() {
    const drive = {};
    for (const [, key, , value] of DRIVE_FIELDS) drive[key] = value;
    return drive;
  }

  // The segments generator's defaults from GET /api/generators.
  function defaults(generator) {
    const field = (key) => (generator ? generator.fields.find((f) => f.key === key) : null);
    const start = field("start");
    const segment = field("segment");
    const resolution = field("resolution");
    return {
      start: start && typeof start.default === "object" ? { ...start.default } : { master: 0, slave: 0 },
      segment: segment && Array.isArray(segment.default) ? segment.default.map((s) => ({ ...s })) : [],
      resolution: resolution ? resolution.default : 100,
    };
  }

  function seg() {
    return ctx.state().seg;
  }

  // Point i: 0 is the start, i ≥ 1 the end of segment i.
  function point(i) {
    return i === 0 ? seg().start : seg().segment[i - 1];
  }

  function pointCount() {
    return seg().segment.length + 1;
  }

  // A typed value: a number where it is one, arithmetic text ("2/5") for
  // the server to read, null (free) when empty.
  function valueOf(text) {
    const t = String(text).trim();
    if (t === "") return null;
    return Number.isFinite(Number(t)) ? Number(t) : t;
  }

  function shown(v) {
    return v === null || v === undefined ? "" : String(v);
  }

  function lawSelect(i) {
    const select = ctx.el("select");
    const laws = [...SOLVED, ...ctx.laws().map((l) => [l.name, l.name])];
    for (const [value, text] of laws) select.append(ctx.el("option", { value, textContent: text }));
    select.value = seg().segment[i - 1].law;
    select.dataset.row = i;
    select.dataset.field = "law";
    select.title = "the law of the segment ending at this point";
    select.addEventListener("change", () => { seg().segment[i - 1].law = select.value; ctx.changed(true); });
    return select;
  }

  function cell(i, field, integer) {
    const p = point(i);
    const input = ctx.el("input", { type: "text", value: shown(p[field]), spellcheck: false, inputMode: "decimal" });
    input.dataset.row = i;
    input.dataset.field = field;
    if (!integer) {
      input.placeholder = "free";
      if (p[field] === null || p[field] === undefined) input.classList.add("free");
    }
    input.addEventListener("input", () => {
      const v = valueOf(input.value);
      if (integer) p[field] = v === null ? "" : v;
      else if (v === null) delete p[field];
      else p[field] = v;
      ctx.changed();
    });
    return ctx.el("td", {}, [input]);
  }

  function render() {
    const body = document.getElementById("seg-grid").tBodies[0];
    body.textContent = "";
    for (let i = 0; i < pointCount(); i++) {
      const law = i === 0 ? ctx.el("td", { className: "hint", textContent: "start" }) : ctx.el("td", {}, [lawSelect(i)]);
      const points = i === 0 ? ctx.el("td") : cell(i, "resolution", true);
      const remove = ctx.el("button", { type: "button", className: "icon", textContent: "×", title: "remove this segment" });
      remove.disabled = i === 0 || seg().segment.length <= 1;
      remove.addEventListener("click", () => { seg().segment.splice(i - 1, 1); render(); ctx.changed(true); });
      const joint = ctx.el("td", { className: "joint" });
      joint.dataset.point = i;
      const peaks = ctx.el("td", { className: "peaks" });
      peaks.dataset.segment = i;
      body.append(ctx.el("tr", {}, [
        ctx.el("td", { className: "num", textContent: String(i) }), law,
        cell(i, "master", true), cell(i, "slave", true),
        ...BOUNDARY.map((b) => cell(i, b, false)), points, joint, peaks, ctx.el("td", {}, [remove]),
      ]));
    }
    document.getElementById("seg-resolution").value = shown(seg().resolution);
    document.getElementById("seg-keep").checked = !!seg().continuous;
    renderDriveFields();
  }

  function renderDriveFields() {
    const box = document.getElementById("drive-fields");
    if (box.childElementCount) return;
    const drive = ctx.state().drive;
    for (const [, key, label, , unit] of DRIVE_FIELDS) {
      const input = ctx.el("input", { type: "text", value: shown(drive[key]), name: key, spellcheck: false, inputMode: "decimal" });
      input.addEventListener("input", () => { drive[key] = valueOf(input.value); ctx.changed(); });
      box.append(ctx.el("label", {}, [
        ctx.el("span", { className: "field-name", textContent: label }),
        ctx.el("span", { className: "field-input" }, [input, unit ? ctx.el("span", { className: "unit", textContent: unit }) : ""]),
      ]));
    }
  }

  // The drive fields after a change of design link (they are built once).
  function refreshDriveFields() {
    const drive = ctx.state().drive;
    for (const input of document.querySelectorAll("#drive-fields input")) input.value = shown(drive[input.name]);
  }

  function params() {
    const s = seg();
    const clean = (p) => Object.fromEntries(Object.entries(p).filter(([, v]) => v !== null && v !== ""));
    const out = { start: clean(s.start), segment: s.segment.map(clean) };
    if (s.continuous) out.continuous = true;
    const resolution = valueOf(shown(s.resolution));
    if (resolution !== null) out.resolution = resolution;
    return out;
  }

  function body() {
    return { generator: "segments", params: params() };
  }

  function markers() {
    const out = [];
    for (let i = 0; i < pointCount(); i++) out.push([Number(point(i).master), Number(point(i).slave)]);
    return out;
  }

  const CLASS_TEXT = { C0: "C0 velocity steps", C1: "C1 acceleration steps", C2: "C2", C3: "C3" };

  // The server's answer for the segments drawn: continuity at every point,
  // each segment's Cv/Ca/Cj; then the drive check.
  function report(t) {
    const s = t.segments;
    if (!s) return;
    const c = s.continuity;
    document.getElementById("seg-class").textContent = `cam ${c.cam}, seam ${c.seam}`;
    for (const j of c.joints) {
      const td = document.querySelector(`#seg-grid td.joint[data-point="${j.seam ? 0 : j.point}"]`);
      if (!td) continue;
      const text = (j.seam ? "seam " : "") + CLASS_TEXT[j.class];
      td.textContent = text;
      td.dataset.class = j.class;
      td.title = `velocity step ${ctx.fmt(j.velocity_jump)}, acceleration step ${ctx.fmt(j.acceleration_jump)}, jerk step ${ctx.fmt(j.jerk_jump)}`;
    }
    for (const p of s.peaks) {
      const td = document.querySelector(`#seg-grid td.peaks[data-segment="${p.segment}"]`);
      if (!td) continue;
      const c3 = [p.cv, p.ca, p.cj].map((x) => (x === null ? "–" : ctx.fmt(x))).join(" / ");
      td.textContent = c3;
      td.title = `peaks: velocity ${ctx.fmt(p.peak_velocity)} pulses/count, acceleration ${ctx.fmt(p.peak_acceleration)} pulses/count², jerk ${ctx.fmt(p.peak_jerk)} pulses/count³`;
    }
    const filled = [s.start, ...s.segment];
    // Free cells show the value the cam was solved with (filled in from the
    // neighbours when "keep continuous" is on, else 0 where a law adapts).
    filled.forEach((p, i) => {
      for (const b of BOUNDARY) {
        const input = document.querySelector(`#seg-grid input[data-row="${i}"][data-field="${b}"]`);
        if (input && input.value === "") input.placeholder = p[b] === undefined ? "free" : ctx.fmt(p[b]);
      }
    });
    const free = BOUNDARY.filter((b) => filled.some((p) => p[b] === undefined));
    document.getElementById("seg-note").textContent =
      "joint: how each point joins its two segments (C0 velocity steps … C3 jerk continuous); Cv / Ca / Cj: the segment's characteristic values (– where it does not rise)." +
      (free.length ? ` Free ${free.join(", ")} values are taken as 0 by the laws that adapt to them.` : "");
    checkDrive();
  }

  async function checkDrive() {
    const seq = ++checked;
    const out = document.getElementById("drive-result");
    const note = document.getElementById("drive-note");
    const drive = ctx.state().drive;
    const section = (name) => Object.fromEntries(DRIVE_FIELDS.filter(([s, k]) => s === name && drive[k] !== null && drive[k] !== "")
      .map(([, k]) => [k, drive[k]]));
    try {
      const r = await ctx.post("/api/drive/check", {
        ...body(), drive: { mechanics: section("mechanics"), limits: section("limits") }, master_speed: drive.master_speed,
      });
      if (seq !== checked) return;
      out.textContent = "";
      const tile = (label, value, use) => {
        const div = ctx.el("div", {}, [ctx.el("span", { textContent: label }), ctx.el("b", { textContent: value })]);
        if (use !== undefined && use !== null && use > 1) div.classList.add("over");
        out.append(div);
      };
      const pct = (u) => (u === null ? "∞" : `${Math.round(u * 100)} %`);
      const a = r.at_speed;
      if (a) {
        tile("machine speed", `${ctx.fmt(a.cycles_per_min)} cycles/min`);
        tile("motor speed", `${ctx.fmt(a.motor_speed_rpm)} rpm (${pct(a.speed_use)})`, a.speed_use);
        tile("peak torque", `${a.peak_torque === null ? "∞" : ctx.fmt(a.peak_torque)} N·m (${pct(a.peak_torque_use)})`, a.peak_torque_use);
        tile("RMS torque", `${a.rms_torque === null ? "∞" : ctx.fmt(a.rms_torque)} N·m (${pct(a.rms_torque_use)})`, a.rms_torque_use);
        if (a.jerk_use !== null) tile("peak jerk", `${a.peak_jerk === null ? "∞" : ctx.fmt(a.peak_jerk)} pulses/s³ (${pct(a.jerk_use)})`, a.jerk_use);
      }
      const binds = r.limits.find((l) => l.limit === r.binding);
      tile("fastest", `${ctx.fmt(r.max_cycles_per_min)} cycles/min`);
      note.textContent = `Drive check: the ${r.binding.replace("-", " ")} limit binds first` +
        (binds && binds.reason ? ` (${binds.reason}${binds.at_master !== undefined ? " at master " + ctx.fmt(binds.at_master) : ""})` : "") +
        `; the others allow ${r.limits.filter((l) => l.limit !== r.binding).map((l) => `${l.limit.replace("-", " ")} ${l.max_cycles_per_min === null ? "∞" : ctx.fmt(l.max_cycles_per_min)}`).join(", ")} cycles/min. Inertia at the motor ${ctx.fmt(r.inertia_at_motor)} kg·m².`;
    } catch (err) {
      if (seq !== checked) return;
      out.textContent = "";
      note.textContent = "Drive check: " + err.message;
    }
  }

  // A point dragged on the displacement plot: whole counts and pulses, the
  // master kept strictly between its neighbours'.
  function drag(i, x, y) {
    if (i >= pointCount()) return;
    const lo = i > 0 ? Number(point(i - 1).master) + 1 : -Infinity;
    const hi = i + 1 < pointCount() ? Number(point(i + 1).master) - 1 : Infinity;
    const p = point(i);
    p.master = Math.min(hi, Math.max(lo, Math.round(x)));
    p.slave = Math.round(y);
    for (const field of ["master", "slave"]) {
      const input = document.querySelector(`#seg-grid [data-row="${i}"][data-field="${field}"]`);
      if (input) input.value = String(p[field]);
    }
  }

  async function makeContinuous() {
    try {
      const filled = await ctx.post("/api/segments/continuous", params());
      const s = seg();
      s.start = { ...filled.start };
      s.segment = filled.segment.map((f, i) => ({ ...f, resolution: s.segment[i] ? s.segment[i].resolution : undefined }));
      for (const p of s.segment) if (p.resolution === undefined) delete p.resolution;
      render();
      ctx.changed(true);
    } catch (err) {
      ctx.showError("Make continuous: " + err.message);
    }
  }

  function addSegment() {
    const s = seg();
    const last = s.segment.length ? s.segment[s.segment.length - 1] : s.start;
    s.segment.push({ law: "poly-5", master: Number(last.master) + 500, slave: Number(last.slave) });
    render();
    ctx.changed(true);
  }

  function init(context) {
    ctx = context;
    document.getElementById("seg-add").addEventListener("click", addSegment);
    document.getElementById("seg-continuous").addEventListener("click", makeContinuous);
    document.getElementById("seg-keep").addEventListener("change", (e) => { seg().continuous = e.target.checked; ctx.changed(true); });
    document.getElementById("seg-resolution").addEventListener("input", (e) => { seg().resolution = valueOf(e.target.value); ctx.changed(); });
  }

  function show(visible) {
    document.getElementById("segments-card").hidden = !visible;
    if (visible) render();
  }

  return { init, defaults, driveDefaults, render, refreshDriveFields, show, body, markers, report, drag };
})();
