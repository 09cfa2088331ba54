// The poses report: every rest pose drawn at rest, its probability with the 95 % interval beside the exact
// quasi-static probability, the counts and the run's settings.

// A pose at rest: its down normal (body frame) turned onto −z, its centre of mass at com_height.
function restPlacement(THREE, pose) {
  const down = new THREE.Vector3(...pose.down_normal_body).normalize();
  const q = new THREE.Quaternion().setFromUnitVectors(down, new THREE.Vector3(0, 0, -1));
  return { q: [q.w, q.x, q.y, q.z], com: [0, 0, pose.com_height] };
}

// Hull vertices on the wall at rest (within 1e-9 L, as flush as the engine leaves them).
function restContacts(shape, placement) {
  const [w, x, y, z] = placement.q;
  const ids = [];
  for (let i = 0; i < shape.hull_vertices.length / 3; ++i) {
    const [vx, vy, vz] = shape.hull_vertices.slice(3 * i, 3 * i + 3);
    // z of q·v: the third row of the rotation matrix.
    const height = 2 * (x * z - w * y) * vx + 2 * (y * z + w * x) * vy + (1 - 2 * (x * x + y * y)) * vz;
    if (height + placement.com[2] <= 1e-6 * shape.length) ids.push(i);
  }
  return ids;
}

// Bars (SVG): per pose, the measured probability with its 95 % interval and the quasi-static probability.
function probabilityChart(poses, method) {
  const svg = svgNode;
  const shown = poses.slice(0, 40);
  const highest = Math.max(0.01, ...shown.map((p) => Math.max(p.ci95[1], p.quasi_static_probability)));
  const { chart, yOf, left, band, H, bottom, plotW } = probabilityBars(highest, shown.length, "probability of each rest pose");
  shown.forEach((p, i) => {
    const x0 = left + i * band;
    const w = Math.max(2, band * 0.36);
    chart.append(svg("rect", { x: x0 + band * 0.12, y: yOf(p.probability), width: w, height: yOf(0) - yOf(p.probability), class: "measured" }));
    const cx = x0 + band * 0.12 + w / 2;
    chart.append(svg("line", { x1: cx, x2: cx, y1: yOf(p.ci95[0]), y2: yOf(p.ci95[1]), class: "whisker" }));
    for (const end of p.ci95) chart.append(svg("line", { x1: cx - w / 4, x2: cx + w / 4, y1: yOf(end), y2: yOf(end), class: "whisker" }));
    chart.append(svg("rect", { x: x0 + band * 0.52, y: yOf(p.quasi_static_probability), width: w, height: yOf(0) - yOf(p.quasi_static_probability), class: "quasi" }));
    chart.append(svg("text", { x: x0 + band / 2, y: H - bottom + 14, "text-anchor": "middle" }, String(p.pose)));
  });
  chart.append(svg("text", { x: left + plotW / 2, y: H - 6, "text-anchor": "middle" }, "rest pose number (as in the table, JSON and CSV), most frequent first"));
  const legend = el(
    "p",
    { class: "legend" },
    el("span", { class: "swatch measured" }),
    ` ${method} probability with its 95 % interval (Wilson)  `,
    el("span", { class: "swatch quasi" }),
    " exact quasi-static probability (basin area / 4π)",
  );
  const note = poses.length > shown.length ? el("p", { class: "hint" }, `The ${shown.length} most frequent of ${poses.length} poses are drawn; the table lists all.`) : null;
  return el("div", {}, chart, legend, note);
}

// A view of the particle at rest in each pose of `poses` (each with down_normal_body and com_height): a large
// canvas with a slider through them, `describe(pose, i)` as its caption; `thumbnail(i)` renders pose i once
// by the same view and returns its picture (the view is left on pose i: call select afterwards).
function restPoseViewer(THREE, shape, poses, describe) {
  const canvas = el("canvas", { width: 720, height: 400, class: "view", "data-role": "view" });
  const slider = el("input", { type: "range", min: 0, max: Math.max(0, poses.length - 1), value: 0, step: 1, class: "pose-slider", "aria-label": "pose" });
  const caption = el("span", { class: "clock" });
  const element = el("div", { class: "player" }, canvas, el("div", { class: "controls" }, el("span", {}, "pose "), slider, caption));
  const stage = new Stage(THREE, canvas, shape);
  stage.view.elevation = 0.3;
  stage.view.distance = 3.2 * shape.length;
  const place = (p) => {
    const at = restPlacement(THREE, p);
    stage.setPose(at.q, at.com, restContacts(shape, at));
    stage.render();
  };
  const select = (i) => {
    slider.value = i;
    place(poses[i]);
    caption.textContent = describe(poses[i], i);
  };
  const thumbnail = (i, alt) => {
    place(poses[i]);
    return el("img", { src: canvas.toDataURL("image/png"), alt, class: "thumb" });
  };
  // A table row's click shows its pose in the large view.
  const show = (i) => () => { select(i); canvas.scrollIntoView({ behavior: "smooth" }); };
  slider.addEventListener("input", () => select(Number(slider.value)));
  return { element, select, thumbnail, show };
}

function settingsTable(study) {
  const rows = [];
  const show = (v) => (v === null ? "—" : typeof v === "object" ? JSON.stringify(v) : typeof v === "number" ? fmt(v, 6) : String(v));
  const part = study.particle;
  const u = unitsOf(study);
  rows.push(["particle", `${part.source}: L = ${fmt(part.characteristic_length)} ${u.length}, mass ${fmt(part.mass)} ${u.mass}, density ${fmt(part.density)} ${u.mass}/${u.length}${part.inertia_model === "shell" ? "²" : "³"}, ${part.hull_faces} hull faces, ${part.smooth ? "smooth" : "non-smooth"}, inertia ${part.inertia_model}`]);
  rows.push(["drops", `${study.n} (ranges ${study.drop_ranges.map((r) => r.join("–")).join(", ")}), seed ${study.seed}, method ${study.method}`]);
  rows.push(["how they ended", Object.entries(study.status_counts).map(([k, v]) => `${k} ${v}`).join(", ") + `; decided early ${study.decided_early}`]);
  for (const [k, v] of Object.entries(study.settings)) rows.push([k.replaceAll("_", " "), show(v)]);
  rows.push(["timing", `${fmt(study.timing.seconds)} s on ${study.timing.threads} threads (${fmt(study.timing.settles_per_second)} settles/s)`]);
  return keyValueTable(rows);
}

REPORTS.poses = (THREE, app) => {
  const study = DATA.study;
  const poses = study.poses;
  app.append(
    el("h1", {}, "Rest poses of " + DATA.title),
    el("p", { class: "lead" }, `${study.n} drops, ${study.method} method, seed ${study.seed}: ${poses.length} rest poses.`),
  );

  // The selected pose, large, with a slider through all of them.
  const viewer = restPoseViewer(THREE, DATA.shape, poses, (p, i) =>
    `${p.pose} (${i + 1} of ${poses.length} by frequency): hull face ${p.face}, probability ${percent(p.probability)} [${percent(p.ci95[0])}, ${percent(p.ci95[1])}], quasi-static ${percent(p.quasi_static_probability)}`);
  app.append(viewer.element);

  app.append(el("h2", {}, "Probabilities"), probabilityChart(poses, study.method));

  // The table, with a picture of each pose (rendered once by the same view).
  const rows = poses.map((p, i) => {
    const picture = i < 48 ? viewer.thumbnail(i, `pose ${p.pose} at rest`) : "—";
    return el(
      "tr",
      { onclick: viewer.show(i) },
      el("td", {}, p.pose),
      el("td", {}, picture),
      el("td", {}, p.faces.join(", ")),
      el("td", {}, p.count),
      el("td", {}, percent(p.probability)),
      el("td", {}, `${percent(p.ci95[0])} – ${percent(p.ci95[1])}`),
      el("td", {}, percent(p.quasi_static_probability)),
      el("td", {}, fmt(p.com_height, 6)),
      el("td", {}, p.barrier === null ? "—" : fmt(p.barrier, 4)),
    );
  });
  const u = unitsOf(study);
  const head = ["pose", "at rest", "hull faces", "count", "probability", "95 % interval", "quasi-static", `COM height (${u.length})`, `barrier (${u.length})`];
  app.append(
    el("h2", {}, "Poses"),
    el("table", { class: "poses" }, el("thead", {}, el("tr", {}, ...head.map((h) => el("th", {}, h)))), el("tbody", {}, ...rows)),
    el("h2", {}, "Settings and counts"),
    settingsTable(study),
  );
  if (poses.length) viewer.select(0);
};
