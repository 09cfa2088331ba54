// The parts every report shares: its data, three.js (embedded in the page as text and imported from a blob,
// so the page needs no file and no network), DOM helpers, number formats and uPlot charts. The page's
// scripts are concatenated in the order common, stage, settle, poses, paper into one module (html_page.cpp).

const DATA = JSON.parse(document.getElementById("repose-data").textContent);

async function loadThree() {
  const source = document.getElementById("three-source").textContent;
  const url = URL.createObjectURL(new Blob([source], { type: "text/javascript" }));
  try {
    return await import(url);
  } finally {
    URL.revokeObjectURL(url);
  }
}

// el("div", {class: "x"}, child, "text", ...): an element with attributes and children.
function el(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (key.startsWith("on")) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value);
  }
  for (const child of children) {
    if (child === null || child === undefined) continue;
    node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

// A number for people: `digits` significant digits, no exponent for everyday magnitudes.
function fmt(x, digits = 4) {
  if (x === null || x === undefined) return "—";
  if (typeof x !== "number") return String(x);
  if (x === 0) return "0";
  const a = Math.abs(x);
  if (a >= 1e-3 && a < 1e6) return String(Number(x.toPrecision(digits)));
  return x.toExponential(digits - 1);
}

function percent(p, digits = 3) {
  return fmt(100 * p, digits) + " %";
}

// A two-column table of [label, value] rows.
// The units a result's numbers are in (its "units" field; generic names for a file that predates it).
const GENERIC_UNITS = { system: "consistent", length: "length", mass: "mass", time: "time", energy: "mass·length²/time²", speed: "length/time", angular_speed: "rad/time", inertia: "mass·length²", damping: "mass·length²/time" };
function unitsOf(result) {
  return (result && result.units) || GENERIC_UNITS;
}

function keyValueTable(rows) {
  return el("table", { class: "kv" }, ...rows.map(([k, v]) => el("tr", {}, el("th", {}, k), el("td", {}, v))));
}

const CONTACT_COLOURS = ["#9e9e9e", "#d62728", "#ff7f0e", "#2ca02c", "#1f77b4"];

// A uPlot line chart of `series` [{label, values, colour}] against `x`, with a vertical line at the time
// cursor.time (set by the player; redraw to move it). `steps`: draw as a staircase (the contact type).
function lineChart(parent, { title, xLabel, yLabel, x, series, steps = false, yValues = null, cursor = null }) {
  const width = Math.min(760, Math.max(320, parent.clientWidth || 760));
  const options = {
    title,
    width,
    height: 220,
    scales: { x: { time: false } },
    axes: [
      { label: xLabel },
      yValues ? { label: yLabel, values: (u, ticks) => ticks.map(yValues), splits: () => yValues.splits } : { label: yLabel },
    ],
    series: [
      { label: xLabel },
      ...series.map((s) => ({
        label: s.label,
        stroke: s.colour,
        width: 1.5,
        paths: steps ? uPlot.paths.stepped({ align: 1 }) : undefined,
        points: { show: false },
      })),
    ],
    hooks: {
      draw: [
        (u) => {
          if (!cursor || cursor.time === null) return;
          const left = u.valToPos(cursor.time, "x", true);
          const ctx = u.ctx;
          ctx.save();
          ctx.strokeStyle = "#444";
          ctx.setLineDash([4, 3]);
          ctx.beginPath();
          ctx.moveTo(left, u.bbox.top);
          ctx.lineTo(left, u.bbox.top + u.bbox.height);
          ctx.stroke();
          ctx.restore();
        },
      ],
    },
  };
  return new uPlot(options, [x, ...series.map((s) => s.values)], parent);
}

// An SVG element with attributes (and text).
function svgNode(tag, attributes, text) {
  const node = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const [k, v] of Object.entries(attributes)) node.setAttribute(k, v);
  if (text !== undefined) node.textContent = text;
  return node;
}

// The frame of a bar chart of probabilities up to `highest` over `bands` categories: the SVG with its grid
// and percent ticks, the y of a probability, and the geometry the bars are placed by.
function probabilityBars(highest, bands, label) {
  const step = [0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.25].find((s) => highest / s <= 5) || 0.25;
  const ticks = Math.ceil(highest / step);
  const top = ticks * step;
  const W = 760, H = 260, left = 48, bottom = 36;
  const plotW = W - left - 10, plotH = H - bottom - 26;
  const yOf = (p) => 10 + plotH * (1 - p / top);
  const chart = svgNode("svg", { viewBox: `0 0 ${W} ${H}`, class: "bars", role: "img", "aria-label": label });
  for (let k = 0; k <= ticks; ++k) {
    const p = k * step;
    chart.append(svgNode("line", { x1: left, x2: W - 10, y1: yOf(p), y2: yOf(p), class: "gridline" }));
    chart.append(svgNode("text", { x: left - 6, y: yOf(p) + 4, "text-anchor": "end" }, (100 * p).toFixed(step < 0.01 ? 1 : 0) + " %"));
  }
  return { chart, yOf, left, band: plotW / Math.max(1, bands), W, H, bottom, plotW };
}

// A status line for errors of the page itself (the test reads the console; a person reads this).
function reportProblem(error) {
  console.error(error);
  document.getElementById("app").prepend(el("p", { class: "problem" }, "This report could not be drawn: " + error));
}

// The report builders by DATA.kind ("settle", "poses", "paper"), each (THREE, app element) → draws the page.
const REPORTS = {};
