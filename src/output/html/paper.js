// The paper report: the comparison with the paper's section 3 (table and figures, from
// scripts/plot_paper.py) and a player for each of its six runs.

REPORTS.paper = (THREE, app) => {
  app.append(
    el("h1", {}, DATA.title),
    el("p", { class: "lead" }, "The four cases of section 3 of Daghooghi & Borazjani, PLoS ONE 16(2): e0243716 (2021), in six runs (repose paper)."),
  );

  // One player at a time (a WebGL context each would exceed a browser's limit on small machines).
  const tabs = el("div", { class: "tabs", role: "tablist" });
  const holder = el("section", { class: "case" });
  app.append(el("h2", {}, "The runs"), tabs, holder);
  const open = (i) => {
    for (const [k, b] of [...tabs.children].entries()) b.setAttribute("aria-selected", String(k === i));
    const old = holder.querySelector("canvas");
    if (old) old.dispatchEvent(new Event("repose-dispose"));
    holder.replaceChildren(el("h3", {}, DATA.cases[i].title));
    const player = buildPlayer(THREE, DATA.cases[i], DATA.contact_names, holder);
    holder.append(summaryTable(DATA.cases[i].summary));
    holder.querySelector("canvas").addEventListener("repose-dispose", () => player.stage.renderer.dispose());
  };
  DATA.cases.forEach((c, i) => tabs.append(el("button", { type: "button", role: "tab", onclick: () => open(i) }, c.title)));

  app.append(el("h2", {}, "Comparison with the paper"));
  if (DATA.table.length) {
    const head = ["case", "quantity", "paper", "exact or analytic", "repose"];
    app.append(el("table", { class: "comparison" }, el("thead", {}, el("tr", {}, ...head.map((h) => el("th", {}, h)))), el("tbody", {}, ...DATA.table.map((row) => el("tr", {}, ...row.map((x) => el("td", {}, x)))))));
  } else {
    app.append(el("p", { class: "hint" }, "No comparison table: the figures were not made (repose paper --no-plots)."));
  }
  if (DATA.figures.length) {
    app.append(el("h2", {}, "Figures"), el("div", { class: "figures" }, ...DATA.figures.map((f) => el("figure", {}, el("img", { src: f.src, alt: f.title }), el("figcaption", {}, f.title)))));
  }
  if (DATA.cases.length) open(0);
};
