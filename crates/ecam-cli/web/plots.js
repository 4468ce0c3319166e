// Charts of the designer page on top of uPlot (vendor/uplot, see README.md):
// one chart per curve, as wide as its box (resized with it), cursors kept
// together, the synchronised zone shaded, impulses marked where the server
// says the curve steps, and draggable markers on the displacement chart.
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

  // Impulses (`chart.impulses`: {quantity, steps: [{master, size, seam}]},
  // the server's steps): an arrow at each master, the largest reaching
  // towards the edge and the others in proportion, labelled with the
  // quantity that steps and its size. A label goes right of its tip, else
  // left, else beyond it; one that would overlap another label, cover
  // another arrow or leave the plot is left out (its arrow stays).
  function impulseMarks(chart) {
    return (u) => {
      const marks = chart.impulses && chart.impulses.steps;
      // What was drawn, for the browser test: arrows and placed labels.
      chart.drawn = { arrows: 0, labels: [], box: null };
      if (!marks || marks.length === 0) return;
      const { ctx, bbox } = u;
      const dpr = window.devicePixelRatio || 1;
      const biggest = Math.max(...marks.map((m) => Math.abs(m.size)));
      const zero = u.valToPos(0, "y", true);
      const room = (up) => (up ? zero - bbox.top : bbox.top + bbox.height - zero) - 18 * dpr;
      const dense = marks.length * 16 * dpr > bbox.width;
      ctx.save();
      ctx.strokeStyle = COLORS.j;
      ctx.fillStyle = COLORS.j;
      ctx.lineWidth = (dense ? 1 : 2) * dpr;
      ctx.font = `${11 * dpr}px system-ui, sans-serif`;
      ctx.textBaseline = "top";
      ctx.textAlign = "left";
      const arrows = [];
      for (const m of marks) {
        const x = u.valToPos(m.master, "x", true);
        if (x < bbox.left - 1 || x > bbox.left + bbox.width + 1) continue;
        const up = m.size > 0;
        const len = Math.max(8 * dpr, (Math.abs(m.size) / biggest) * Math.max(room(up), 8 * dpr));
        const tip = up ? zero - len : zero + len;
        ctx.beginPath();
        ctx.moveTo(x, zero);
        ctx.lineTo(x, tip);
        ctx.stroke();
        const head = 5 * dpr * (up ? 1 : -1);
        ctx.beginPath();
        ctx.moveTo(x, tip);
        ctx.lineTo(x - 4 * dpr, tip + head);
        ctx.lineTo(x + 4 * dpr, tip + head);
        ctx.closePath();
        ctx.fill();
        arrows.push({ x, tip, up, text: `${m.seam ? "seam " : ""}${chart.impulses.quantity} ${fmt(m.size)}` });
      }
      if (!dense) {
        const h = 12 * dpr;
        const placed = [];
        const shafts = arrows.map((a) => ({ x: a.x - 6 * dpr, y: Math.min(a.tip, zero), w: 12 * dpr, h: Math.abs(zero - a.tip) }));
        const overlaps = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
        const inside = (r) => r.x >= bbox.left && r.y >= bbox.top && r.x + r.w <= bbox.left + bbox.width && r.y + r.h <= bbox.top + bbox.height;
        arrows.forEach((a, k) => {
          const w = ctx.measureText(a.text).width;
          const y = a.up ? a.tip : a.tip - h;
          const beyond = a.up ? a.tip - h - 4 * dpr : a.tip + 4 * dpr;
          const candidates = [
            { x: a.x + 8 * dpr, y, w, h }, { x: a.x - 8 * dpr - w, y, w, h },
            { x: a.x - w / 2, y: beyond, w, h }, { x: a.x - w, y: beyond, w, h }, { x: a.x, y: beyond, w, h },
          ];
          const spot = candidates.find((r) => inside(r) && placed.every((p) => !overlaps(p, r)) && shafts.every((s, j) => j === k || !overlaps(s, r)));
          if (spot) {
            placed.push({ ...spot, text: a.text });
            ctx.fillText(a.text, spot.x, spot.y);
          }
        });
        chart.drawn.labels = placed;
      }
      chart.drawn.arrows = arrows.length;
      chart.drawn.box = { x: bbox.left, y: bbox.top, w: bbox.width, h: bbox.height };
      ctx.restore();
    };
  }

  // The y range of a chart: its data, and room on either side of 0 for
  // its impulses' arrows; a flat 0 (a design's jerk between impulses) gets
  // a band around 0 with only 0 labelled (`chart.flat`).
  function yRange(chart) {
    return (_u, min, max) => {
      const steps = (chart.impulses && chart.impulses.steps) || [];
      let lo = min === null ? 0 : min;
      let hi = max === null ? 0 : max;
      if (steps.length) {
        lo = Math.min(lo, 0);
        hi = Math.max(hi, 0);
        if (steps.some((s) => s.size < 0)) lo = Math.min(lo, -0.6 * hi);
        if (steps.some((s) => s.size > 0)) hi = Math.max(hi, -0.6 * lo);
      }
      chart.flat = lo === 0 && hi === 0;
      if (chart.flat) return [-1, 1];
      if (lo === hi) return [lo - Math.abs(lo) * 0.05, hi + Math.abs(hi) * 0.05];
      const pad = (hi - lo) * 0.05;
      return [lo - pad, hi + pad];
    };
  }

  // A chart in `el`: `series` is [{label, color, stepped, points, width}],
  // `axes` {x, y} labels with units.
  function create(el, { title, xLabel, yLabel, series, syncKey, timeX }) {
    const chart = { el, sync: null, impulses: null, u: null, drag: null, flat: false };
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
      scales: { x: { time: false }, y: { range: yRange(chart) } },
      axes: [
        { label: xLabel, values: timeX ? undefined : axisValues, labelSize: 20, size: 36 },
        { label: yLabel, values: (u, ticks) => (chart.flat ? ticks.map((t) => (t === 0 ? "0" : "")) : axisValues(u, ticks)), labelSize: 22, size: 64 },
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

  return { create, set, join, draggable, fmt, COLORS };
})();
