// Charts of the designer page on top of uPlot (vendor/uplot, see README.md):
// one chart per curve, as wide as its box (resized with it), cursors kept
// together, the synchronised zone shaded, jerk impulses marked where the
// acceleration steps, and draggable markers on the displacement chart.
"use strict";

const Plots = (() => {
  const COLORS = {
    s: "#2563eb", v: "#d97706", a: "#c026d3", j: "#7c3aed",
    points: "#0f172a", master: "#0891b2", slave: "#2563eb",
    vmaster: "#0891b2", vslave: "#d97706", sync: "rgba(22, 163, 74, 0.13)",
  };
  const HEIGHT = 190;

  function fmt(x) {
    if (x === null || x === undefined || Number.isNaN(x)) return "–";
    if (!Number.isFinite(x)) return x > 0 ? "∞" : "−∞";
    if (x === 0) return "0";
    const a = Math.abs(x);
    if (a >= 1e6 || a < 1e-3) return x.toExponential(3);
    return String(Math.round(x * 1e4) / 1e4);
  }

  function axisValues(_u, ticks) {
    return ticks.map(fmt);
  }

  // Shades [lo, hi] (or several such zones) of the x scale behind the curves.
  function syncShade(chart) {
    return (u) => {
      const zone = chart.sync;
      if (!zone || zone.length === 0) return;
      const zones = Array.isArray(zone[0]) ? zone : [zone];
      const { ctx, bbox } = u;
      ctx.save();
      ctx.fillStyle = COLORS.sync;
      for (const [lo, hi] of zones) {
        const x0 = Math.max(bbox.left, u.valToPos(lo, "x", true));
        const x1 = Math.min(bbox.left + bbox.width, u.valToPos(hi, "x", true));
        if (x1 > x0) ctx.fillRect(x0, bbox.top, x1 - x0, bbox.height);
      }
      ctx.restore();
    };
  }

  // Jerk impulses: an arrow at each master where the acceleration steps,
  // its length in proportion to the step, labelled with its size.
  function impulseMarks(chart) {
    return (u) => {
      const marks = chart.impulses;
      if (!marks || marks.length === 0) return;
      const { ctx, bbox } = u;
      const biggest = Math.max(...marks.map((m) => Math.abs(m.step)));
      const zero = u.valToPos(0, "y", true);
      const room = Math.min(bbox.height * 0.45, Math.max(zero - bbox.top, bbox.top + bbox.height - zero) - 4);
      const dpr = window.devicePixelRatio || 1;
      ctx.save();
      ctx.strokeStyle = COLORS.j;
      ctx.fillStyle = COLORS.j;
      ctx.lineWidth = 2 * dpr;
      ctx.font = `${11 * dpr}px system-ui, sans-serif`;
      ctx.textAlign = "center";
      for (const m of marks) {
        const x = u.valToPos(m.master, "x", true);
        if (x < bbox.left || x > bbox.left + bbox.width) continue;
        const len = Math.max(8 * dpr, (Math.abs(m.step) / biggest) * room);
        const tip = m.step > 0 ? zero - len : zero + len;
        ctx.beginPath();
        ctx.moveTo(x, zero);
        ctx.lineTo(x, tip);
        ctx.stroke();
        const head = 5 * dpr * Math.sign(m.step || 1);
        ctx.beginPath();
        ctx.moveTo(x, tip);
        ctx.lineTo(x - 4 * dpr, tip + head);
        ctx.lineTo(x + 4 * dpr, tip + head);
        ctx.closePath();
        ctx.fill();
        ctx.fillText("Δa " + fmt(m.step), x, m.step > 0 ? tip - 4 * dpr : tip + 12 * dpr);
      }
      ctx.restore();
    };
  }

  // A chart in `el`: `series` is [{label, color, stepped, points, width}],
  // `axes` {x, y} labels with units.
  function create(el, { title, xLabel, yLabel, series, syncKey, timeX }) {
    const chart = { el, sync: null, impulses: null, u: null, drag: null };
    const opts = {
      title,
      width: Math.max(200, el.clientWidth),
      height: HEIGHT,
      cursor: {
        sync: syncKey ? { key: syncKey } : undefined,
        drag: { x: false, y: false },
        points: { size: 6 },
      },
      legend: { live: true },
      scales: { x: { time: false } },
      axes: [
        { label: xLabel, values: timeX ? undefined : axisValues, labelSize: 20, size: 36 },
        { label: yLabel, values: axisValues, labelSize: 22, size: 64 },
      ],
      series: [
        { label: xLabel, value: (_u, v) => fmt(v) },
        ...series.map((s) => ({
          label: s.label,
          stroke: s.color,
          width: s.width === undefined ? 2 : s.width,
          paths: s.points ? () => null : s.stepped ? uPlot.paths.stepped({ align: 1 }) : undefined,
          points: s.points
            ? { show: true, size: s.size || 9, stroke: s.color, fill: "#fff", width: 2 }
            : { show: false },
          spanGaps: !!s.spanGaps,
          value: (_u, v) => fmt(v),
        })),
      ],
      hooks: {
        drawClear: [syncShade(chart)],
        draw: [impulseMarks(chart)],
      },
    };
    const empty = [[], ...series.map(() => [])];
    chart.u = new uPlot(opts, empty, el);
    new ResizeObserver(() => {
      const width = Math.max(200, el.clientWidth);
      if (chart.u && Math.abs(chart.u.width - width) > 1) chart.u.setSize({ width, height: HEIGHT });
    }).observe(el);
    return chart;
  }

  // Aligns series sampled at different x (the design curve and the table's
  // points) on one x array, null where a series has no sample.
  function join(parts) {
    const xs = [...new Set(parts.flatMap((p) => p.x))].sort((a, b) => a - b);
    const index = new Map(xs.map((x, i) => [x, i]));
    const out = [xs];
    for (const p of parts) {
      const ys = new Array(xs.length).fill(null);
      // Several samples at one x (a step): the last one wins here; steps
      // are drawn from series that keep their own x (see setCurve).
      p.x.forEach((x, i) => { ys[index.get(x)] = p.y[i]; });
      out.push(ys);
    }
    return out;
  }

  // Sets a chart's data: `x` and one y array per series (same length).
  function set(chart, data, { sync = null, impulses = null } = {}) {
    chart.sync = sync;
    chart.impulses = impulses;
    chart.u.setData(data, true);
  }

  // Where the acceleration steps: consecutive design samples at the same
  // master with different acceleration (a joint of two pieces).
  function impulsesOf(master, a) {
    const marks = [];
    for (let i = 1; i < master.length; i++) {
      if (master[i] === master[i - 1] && a[i] !== null && a[i - 1] !== null) {
        const step = a[i] - a[i - 1];
        const scale = Math.max(Math.abs(a[i]), Math.abs(a[i - 1]), 1e-300);
        if (Math.abs(step) > 1e-9 * scale) marks.push({ master: master[i], step });
      }
    }
    return marks;
  }

  // Makes the markers of series `seriesIndex` draggable: `onDrag(i, x, y)`
  // while a marker moves (values in the chart's units), `onDrop()` at the end.
  function draggable(chart, seriesIndex, onDrag, onDrop) {
    const u = chart.u;
    const over = u.over;
    let dragging = -1;
    const nearest = (event) => {
      const rect = over.getBoundingClientRect();
      const px = event.clientX - rect.left;
      const py = event.clientY - rect.top;
      const xs = u.data[0];
      const ys = u.data[seriesIndex];
      let best = -1;
      let bestDist = 12;
      for (let i = 0; i < xs.length; i++) {
        if (ys[i] === null || ys[i] === undefined) continue;
        const dx = u.valToPos(xs[i], "x") - px;
        const dy = u.valToPos(ys[i], "y") - py;
        const d = Math.hypot(dx, dy);
        if (d < bestDist) { bestDist = d; best = i; }
      }
      return { best, px, py };
    };
    over.addEventListener("pointerdown", (event) => {
      const { best } = nearest(event);
      if (best < 0) return;
      // The marker's index among the series' own (non-null) samples.
      const ys = u.data[seriesIndex];
      let k = -1;
      for (let i = 0; i <= best; i++) if (ys[i] !== null && ys[i] !== undefined) k++;
      dragging = k;
      over.setPointerCapture(event.pointerId);
      over.classList.add("dragging");
      event.preventDefault();
    });
    over.addEventListener("pointermove", (event) => {
      if (dragging < 0) {
        over.classList.toggle("grab", nearest(event).best >= 0);
        return;
      }
      const rect = over.getBoundingClientRect();
      const x = u.posToVal(event.clientX - rect.left, "x");
      const y = u.posToVal(event.clientY - rect.top, "y");
      onDrag(dragging, x, y);
    });
    const end = () => {
      if (dragging < 0) return;
      dragging = -1;
      over.classList.remove("dragging");
      onDrop();
    };
    over.addEventListener("pointerup", end);
    over.addEventListener("pointercancel", end);
  }

  return { create, set, join, impulsesOf, draggable, fmt, COLORS };
})();
