// The design report (`repose design --html`): target against achieved per outcome (quasi-static, and tossed
// with the checks' 95 % intervals for a tossed design), the design drawn in each of its rest poses, and the
// optimisation's history. DATA.design is design.json; DATA.poses the design's stable faces (persistence 0).

// Bars (SVG): per outcome, the target and what each design achieved, tossed ones with their interval.
function outcomeChart(rows, series) {
  const svg = svgNode;
  const values = rows.flatMap((r) => series.flatMap((s) => [r[s.key], ...(s.ci ? [r[s.ci][1]] : [])]));
  const highest = Math.max(0.01, ...values.filter((v) => typeof v === "number"));
  const { chart, yOf, left, band, H, bottom, plotW } = probabilityBars(highest, rows.length, "target and achieved probability of each outcome");
  const w = (band * 0.8) / series.length;
  rows.forEach((r, i) => {
    series.forEach((s, j) => {
      const v = r[s.key];
      if (typeof v !== "number") return;
      const x = left + i * band + band * 0.1 + j * w;
      chart.append(svg("rect", { x, y: yOf(v), width: Math.max(1, w * 0.9), height: yOf(0) - yOf(v), fill: s.colour }));
      if (s.ci) {
        const cx = x + (w * 0.9) / 2;
        chart.append(svg("line", { x1: cx, x2: cx, y1: yOf(r[s.ci][0]), y2: yOf(r[s.ci][1]), class: "whisker" }));
      }
    });
    chart.append(svg("text", { x: left + i * band + band / 2, y: H - bottom + 14, "text-anchor": "middle" }, r.label));
  });
  chart.append(svg("text", { x: left + plotW / 2, y: H - 6, "text-anchor": "middle" }, "outcome (as in the table)"));
  const legend = el("p", { class: "legend" }, ...series.flatMap((s) => [el("span", { class: "swatch", style: `background:${s.colour}` }), ` ${s.label}  `]));
  return el("div", {}, chart, legend);
}

// The objective against the iteration (log scale), as uPlot draws it.
function historyChart(parent, title, label, values) {
  const x = values.map((_, i) => i + 1);
  const y = values.map((v) => (v > 0 ? Math.log10(v) : null));
  lineChart(parent, {
    title,
    xLabel: "iteration",
    yLabel: `log10 ${label}`,
    x,
    series: [{ label, values: y, colour: "#1f77b4" }],
  });
}

REPORTS.design = (THREE, app) => {
  const d = DATA.design;
  const tossed = d.model === "tossed" ? d.tossed : null;
  const reached = tossed ? tossed.reached : d.reached;
  app.append(
    el("h1", {}, "Design of " + DATA.title),
    el(
      "p",
      { class: "lead" },
      `Target ${d.target_file}, ${d.model} model, varying ${d.options.vary}: ` +
        (reached ? "reached" : `NOT reached (${tossed ? tossed.stop : d.stop}; the best achievable from this start)`) +
        (tossed ? `; ${tossed.settles} tossed settles.` : `; max |achieved − target| ${fmt(d.max_error)}.`),
    ),
  );

  // The outcomes' table and chart.
  const rows = d.outcomes.map((o, k) => ({ label: String(k + 1), normal: o.normal, target: o.target, start: o.start, achieved: o.achieved }));
  rows.push({ label: "other", normal: null, target: 0, start: d.unassigned.start, achieved: d.unassigned.achieved });
  if (tossed) {
    rows.forEach((r, k) => {
      r.tossedDesign = tossed.check.probability[k];
      r.tossedDesignCi = tossed.check.ci95[k];
      r.tossedQuasi = tossed.check_quasi_static_design.probability[k];
      r.tossedQuasiCi = tossed.check_quasi_static_design.ci95[k];
      r.quasiDesign = d.quasi_static_design.outcomes[k] ? d.quasi_static_design.outcomes[k].achieved : d.quasi_static_design.unassigned.achieved;
    });
  }
  const series = tossed
    ? [
        { key: "target", label: "target", colour: "#444" },
        { key: "tossedQuasi", ci: "tossedQuasiCi", label: "quasi-static design, tossed (check drops, 95 % interval)", colour: "#ff9f40" },
        { key: "tossedDesign", ci: "tossedDesignCi", label: "tossed design, tossed (check drops, 95 % interval)", colour: "#1f77b4" },
      ]
    : [
        { key: "target", label: "target", colour: "#444" },
        { key: "start", label: "start", colour: "#bbb" },
        { key: "achieved", label: "design (exact quasi-static)", colour: "#1f77b4" },
      ];
  const interval = (ci) => `${percent(ci[0])} – ${percent(ci[1])}`;
  const head = tossed
    ? ["outcome", "normal", "target", "quasi-static design: quasi-static", "tossed", "95 % interval", "tossed design: quasi-static", "tossed", "95 % interval"]
    : ["outcome", "normal", "target", "start", "achieved"];
  const body = rows.map((r) =>
    el(
      "tr",
      {},
      el("td", {}, r.label),
      el("td", {}, r.normal ? `[${r.normal.map((c) => fmt(c, 3)).join(", ")}]` : "(faces of no outcome)"),
      el("td", {}, percent(r.target)),
      ...(tossed
        ? [el("td", {}, percent(r.quasiDesign)), el("td", {}, percent(r.tossedQuasi)), el("td", {}, interval(r.tossedQuasiCi)), el("td", {}, percent(r.achieved)), el("td", {}, percent(r.tossedDesign)), el("td", {}, interval(r.tossedDesignCi))]
        : [el("td", {}, percent(r.start)), el("td", {}, percent(r.achieved))]),
    ),
  );
  app.append(el("h2", {}, "Target and achieved"), outcomeChart(rows, series), el("table", {}, el("thead", {}, el("tr", {}, ...head.map((h) => el("th", {}, h)))), el("tbody", {}, ...body)));
  if (tossed) {
    const c = tossed.check, q = tossed.check_quasi_static_design;
    app.append(
      el(
        "p",
        { class: "hint" },
        `Checked on drops ${c.drops[0]}–${c.drops[1] - 1}, which the optimiser never saw. χ² against the target (${c.degrees_of_freedom} degrees of freedom): ` +
          `quasi-static design p = ${fmt(q.p_value, 3)}, tossed design p = ${fmt(c.p_value, 3)}; every target inside its 95 % interval: ${c.all_within_ci95 ? "yes" : "no"}; inside its simultaneous interval (Bonferroni over the ${d.outcomes.length} outcomes): ${c.all_within_simultaneous_ci95 ? "yes" : "no"}; within the fit's noise and the check's (fitted on ${c.fit_drops} drops): ${c.all_within_fit_and_check ? "yes" : "no"}, simultaneous: ${c.all_within_fit_and_check_simultaneous ? "yes" : "no"}.`,
      ),
    );
  }

  // The design in each rest pose.
  const poses = DATA.poses;
  const outcomeName = (p) => (p.outcome >= 0 ? `outcome ${p.outcome + 1}` : "no outcome");
  const viewer = restPoseViewer(THREE, DATA.shape, poses, (p) => `${outcomeName(p)}: hull face ${p.face}, quasi-static probability ${percent(p.quasi_static_probability)}`);
  app.append(el("h2", {}, "The design at rest"), viewer.element);
  const poseRows = poses.map((p, i) =>
    el(
      "tr",
      { onclick: viewer.show(i) },
      el("td", {}, outcomeName(p)),
      el("td", {}, i < 48 ? viewer.thumbnail(i, `the design resting on face ${p.face}`) : "—"),
      el("td", {}, p.face),
      el("td", {}, percent(p.quasi_static_probability)),
      el("td", {}, fmt(p.com_height, 6)),
    ),
  );
  app.append(
    el("table", { class: "poses" }, el("thead", {}, el("tr", {}, ...["outcome", "at rest", "hull face", "quasi-static", "COM height"].map((h) => el("th", {}, h)))), el("tbody", {}, ...poseRows)),
    el(
      "p",
      { class: "hint" },
      `Centre of mass [${d.center_of_mass.map((c) => fmt(c, 5)).join(", ")}]; a uniform solid's [${d.centroid.map((c) => fmt(c, 5)).join(", ")}]: ` +
        `an insert or cavity must move it by [${d.center_of_mass_offset.map((c) => fmt(c, 5)).join(", ")}]. Hull: ${d.hull.vertices} vertices, L = ${fmt(d.characteristic_length)}.`,
    ),
  );
  if (poses.length) viewer.select(0);

  // The history.
  app.append(el("h2", {}, "Optimisation"));
  const plots = el("div", { class: "plots" });
  app.append(plots);
  const qs = tossed ? d.quasi_static_design : d;
  if (qs.history.length) historyChart(plots, "quasi-static design: Σ (achieved − target)² per iteration", "objective", qs.history.map((h) => h.objective));
  if (tossed) {
    historyChart(plots, "tossed design: Σ (tossed − target)², less its sampling variance, per tossed estimate", "objective", tossed.history.map((h) => h.objective));
    const t = tossed.history.map((h, i) =>
      el(
        "tr",
        {},
        el("td", {}, i + 1),
        el("td", {}, h.kind),
        el("td", {}, h.tossed.drops[1]),
        el("td", {}, h.surrogate_target.map((v) => fmt(v, 3)).join(", ")),
        el("td", {}, h.tossed.probability.slice(0, d.outcomes.length).map((v) => fmt(v, 3)).join(", ")),
        el("td", {}, fmt(h.objective, 3)),
        el("td", {}, h.accepted ? "yes" : "no"),
      ),
    );
    app.append(
      el("table", {}, el("thead", {}, el("tr", {}, ...["estimate", "kind", "drops", "quasi-static target", "tossed", "objective", "accepted"].map((h) => el("th", {}, h)))), el("tbody", {}, ...t)),
      el("h2", {}, "The toss"),
      keyValueTable(Object.entries(tossed.toss).map(([k, v]) => [k.replaceAll("_", " "), v === null ? "—" : String(v)])),
    );
  }
  app.append(el("h2", {}, "Options"), keyValueTable(Object.entries(d.options).map(([k, v]) => [k.replaceAll("_", " "), String(v)])));
};
