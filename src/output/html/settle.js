// The settle report: one run played in 3-D (play/pause, a time slider, the contact points and the centre of
// mass marked, the contact type shown), its summary, and its angular speed, energies and contact type
// plotted against time. The paper report reuses the player for each of its cases.

const PLAY_SECONDS = { "4 s": 4, "8 s": 8, "16 s": 16, "real time": 0 };

// The player of `run` ({title, shape, summary, frames}) appended to `parent`.
function buildPlayer(THREE, run, contactNames, parent) {
  const f = run.frames;
  const n = f.t.length;
  const canvas = el("canvas", { width: 720, height: 440, class: "view", "data-role": "view" });
  const slider = el("input", { type: "range", min: 0, max: Math.max(0, n - 1), value: 0, step: 1, class: "time-slider", "aria-label": "time" });
  const play = el("button", { type: "button", class: "play" }, "▶ play");
  const clock = el("span", { class: "clock" });
  const badge = el("span", { class: "badge" });
  const duration = el("select", { "aria-label": "playback length" }, ...Object.keys(PLAY_SECONDS).map((k) => el("option", { value: k }, k)));
  duration.value = "8 s";
  parent.append(
    el("div", { class: "player" }, canvas, el("div", { class: "controls" }, play, slider, clock, badge, el("label", {}, "play over ", duration))),
    el("p", { class: "hint" }, "Drag the view to turn it, scroll to zoom. Blue: centre of mass; red: the hull vertices within the contact threshold ε of the wall." + (run.shape.surface === "mesh" ? "" : " The surface drawn is the convex hull (the mesh is too large for a page).")),
  );

  const stage = new Stage(THREE, canvas, run.shape, { wallCentre: n ? [f.com[0], f.com[1]] : [0, 0] });
  const cursor = { time: n ? f.t[0] : null };
  const charts = [];
  let shown = 0;

  function show(i) {
    shown = i;
    stage.setPose(f.q.slice(4 * i, 4 * i + 4), f.com.slice(3 * i, 3 * i + 3), f.contacts[i]);
    stage.render();
    clock.textContent = "t = " + fmt(f.t[i], 5);
    const c = f.contact[i];
    const modes = f.sticking && f.sticking[i] + f.sliding[i] > 0 ? ` · ${f.sticking[i]} sticking, ${f.sliding[i]} sliding` : "";
    badge.textContent = contactNames[c] + (f.contacts[i].length ? ` · ${f.contacts[i].length} within ε` : "") + modes;
    badge.style.background = CONTACT_COLOURS[c];
    cursor.time = f.t[i];
    for (const u of charts) u.redraw(false);
  }

  // Playback follows the clock: the run's time advances at (run length) / (chosen seconds) per second.
  let playing = false;
  let wallStart = 0;
  let runStart = 0;
  const frameAt = (t) => {
    let lo = 0;
    let hi = n - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (f.t[mid] <= t) lo = mid;
      else hi = mid - 1;
    }
    return lo;
  };
  const stop = () => {
    playing = false;
    play.textContent = "▶ play";
  };
  const tick = (now) => {
    if (!playing) return;
    const seconds = PLAY_SECONDS[duration.value];
    const span = f.t[n - 1] - f.t[0];
    const rate = seconds > 0 && span > 0 ? span / seconds : 1;
    const i = frameAt(runStart + ((now - wallStart) / 1000) * rate);
    slider.value = i;
    show(i);
    if (i >= n - 1) stop();
    else requestAnimationFrame(tick);
  };
  play.addEventListener("click", () => {
    if (playing) return stop();
    if (shown >= n - 1) show(0);
    playing = true;
    play.textContent = "❚❚ pause";
    wallStart = performance.now();
    runStart = f.t[shown];
    requestAnimationFrame(tick);
  });
  slider.addEventListener("input", () => {
    stop();
    show(Number(slider.value));
  });

  // The plots, against the same time as the slider.
  const plots = el("div", { class: "plots" });
  parent.append(plots);
  const omega = f.t.map((_, i) => Math.hypot(f.omega[3 * i], f.omega[3 * i + 1], f.omega[3 * i + 2]));
  const total = f.t.map((_, i) => f.kinetic[i] + f.potential[i]);
  const box = () => plots.appendChild(el("div", { class: "plot" }));
  const u = unitsOf(run.summary);
  const tLabel = `t (${u.time})`;
  if (n > 0) {
    charts.push(
      lineChart(box(), { title: "angular speed |ω|", xLabel: tLabel, yLabel: `|ω| (${u.angular_speed})`, x: f.t, series: [{ label: `|ω| (${u.angular_speed})`, values: omega, colour: "#1f77b4" }], cursor }),
      lineChart(box(), {
        title: `energies (${u.energy}; potential m·g·z of the centre of mass)`,
        xLabel: tLabel,
        yLabel: `energy (${u.energy})`,
        x: f.t,
        series: [
          { label: "kinetic", values: f.kinetic, colour: "#d62728" },
          { label: "potential", values: f.potential, colour: "#2ca02c" },
          { label: "total", values: total, colour: "#333333" },
        ],
        cursor,
      }),
    );
    const used = [...new Set(f.contact)].sort();
    const names = (v) => (Number.isInteger(v) && v >= 0 && v < contactNames.length ? contactNames[v] : "");
    names.splits = [0, 1, 2, 3, 4];
    charts.push(
      lineChart(box(), {
        title: "contact type (" + used.map((c) => contactNames[c]).join(", ") + ")",
        xLabel: tLabel,
        yLabel: "",
        x: f.t,
        series: [{ label: "contact", values: f.contact, colour: "#7b3294" }],
        steps: true,
        yValues: names,
        cursor,
      }),
    );
    // With finite friction: the points on the wall by Coulomb's mode (the frictional contact phase).
    if (f.sticking && f.sticking.some((v, i) => v + f.sliding[i] > 0))
      charts.push(
        lineChart(box(), {
          title: "points on the wall by mode (friction after the landing)",
          xLabel: tLabel,
          yLabel: "points",
          x: f.t,
          series: [
            { label: "sticking", values: f.sticking, colour: "#1f77b4" },
            { label: "sliding", values: f.sliding, colour: "#ff7f0e" },
          ],
          steps: true,
          cursor,
        }),
      );
  }
  if (n > 0) show(0);
  return { stage, show, slider };
}

function summaryTable(summary) {
  const rest = summary.rest || {};
  const u = unitsOf(summary);
  const rows = [
    ["particle", `${summary.particle.source} (L = ${fmt(summary.particle.characteristic_length)} ${u.length}, mass ${fmt(summary.particle.mass)} ${u.mass})`],
    [summary.status === "rest" ? "at rest" : "not at rest", `${summary.status === "rest" ? "at" : `stopped (${summary.status}) at`} t = ${fmt(summary.time, 6)} ${u.time} (${summary.steps} steps)`],
  ];
  if (summary.status === "rest") {
    rows.push(["rests on", `${rest.contact}, hull face ${rest.face}, ${rest.contact_points.length} support points`]);
    rows.push(["centre of mass at rest", `(${rest.com.map((x) => fmt(x, 6)).join(", ")}) ${u.length}; face plane ${fmt(rest.face_com_height, 6)} ${u.length} below it`]);
  }
  if (summary.stable_time !== null) rows.push(["the paper's stability test", `passes at t = ${fmt(summary.stable_time, 6)} ${u.time} (where the paper's run would stop)`]);
  rows.push(["largest penetration", `${fmt(summary.max_penetration)} ${u.length}`]);
  rows.push(["energy", `${fmt(summary.energy.start, 6)} → ${fmt(summary.energy.end, 6)} ${u.energy}`]);
  if (summary.impacts.length) rows.push(["impacts", `${summary.impacts.length}, ${summary.bounces} followed by a flight`]);
  if (summary.energy.friction_work !== undefined && summary.parameters.friction !== null)
    rows.push(["friction after the landing", `work ${fmt(summary.energy.friction_work, 6)} ${u.energy}, damping's ${fmt(summary.energy.damping_work, 6)} ${u.energy}, impacts' losses ${fmt(summary.energy.impact_losses, 6)} ${u.energy}; slid ${fmt(summary.sliding_distance, 6)} ${u.length}; ${summary.painleve} Painlevé impacts`]);
  rows.push([`phases (${u.time})`, summary.phases.map((p) => `${p.contact} [${fmt(p.t0)}, ${fmt(p.t1)}]`).join(" · ")]);
  const p = summary.parameters;
  rows.push(["parameters", `g = ${fmt(p.gravity)} ${u.length}/${u.time}², damping C = ${fmt(p.damping)} ${u.damping}, ${p.integrator} integrator, restitution ${fmt(p.restitution)}, friction ${p.friction === null ? "no slip" : fmt(p.friction)}`]);
  return keyValueTable(rows);
}

REPORTS.settle = (THREE, app) => {
  app.append(el("h1", {}, DATA.title), el("p", { class: "lead" }, "One settling run (repose settle)."));
  const player = el("section", {});
  app.append(player, el("h2", {}, "Summary"), summaryTable(DATA.summary));
  buildPlayer(THREE, DATA, DATA.contact_names, player);
};
