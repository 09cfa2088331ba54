// The entry point: load three.js, then draw the report DATA.kind names.
(async () => {
  const app = document.getElementById("app");
  try {
    const THREE = await loadThree();
    const build = REPORTS[DATA.kind];
    if (!build) throw new Error(`unknown report kind "${DATA.kind}"`);
    build(THREE, app);
    const licences = el("details", { class: "licences" }, el("summary", {}, "Made with repose, three.js and uPlot (licences)"));
    licences.append(document.getElementById("licences").content.cloneNode(true));
    app.append(licences);
    document.body.dataset.ready = "true";
  } catch (error) {
    reportProblem(error);
  }
})();
