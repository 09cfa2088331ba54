// repose settle MESH|SHAPE --orientation SPEC ...: one settling run, the paper's method end to end.
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "format.hpp"
#include "mesh_options.hpp"
#include "physics_options.hpp"
#include "repose/model/orientation.hpp"
#include "repose/model/particle.hpp"
#include "repose/model/scenario.hpp"
#include "repose/output/files.hpp"
#include "repose/output/html.hpp"
#include "repose/output/report.hpp"
#include "repose/output/vtk.hpp"
#include "repose/sim/settle.hpp"

namespace repose::cli {

namespace {

struct SettleOptions {
  std::string source;
  std::string orientation = "identity";
  PhysicsOptions physics;
  MeshCliOptions mesh;
  std::string scenario;
  std::string out_dir;
  std::string vtk_dir;
  std::string html;
  double frame_dt = 0;
  double sample_dt = 0;
  int frames = 0;
  bool json = false;
};

// Why the particle was treated as smooth or not, for the user to check the automatic decision.
std::string smooth_reason(const Particle& particle, SmoothMode mode, bool smooth) {
  if (mode != SmoothMode::automatic) return std::string(smooth ? "smooth" : "non-smooth") + " (--smooth)";
  const double degrees = particle.max_dihedral_angle * 180 / 3.141592653589793;
  return std::string(smooth ? "smooth" : "non-smooth") +
         " (auto: " + (particle.convex_surface ? "convex" : "concave") +
         ", largest angle between neighbouring faces " + num(std::round(degrees * 10) / 10) +
         " deg; smooth needs " + "convex and < 30)";
}

// The start orientation as the user gave it, or the default said as such.
std::string start_text(const SettleOptions& o, const CLI::App& sub) {
  if (sub.count("--orientation") > 0) return o.orientation;
  if (!o.scenario.empty()) return "the scenario's";
  return "identity (the default: the mesh's axes; --orientation sets it)";
}

void print_summary(const Particle& particle, const SettleParams& params, const SettleResult& r,
                   const std::string& start) {
  const UnitNames& u = unit_names_for_gravity(params.gravity);
  const std::string s = std::string(" ") + u.time, m = std::string(" ") + u.length;
  std::cout << "particle        " << particle.name << " (L = " << num(particle.length) << m << ")\n"
            << "surface         " << smooth_reason(particle, params.smooth, r.smooth) << "\n"
            << "start           " << start << "\n";
  if (r.status == Status::rest)
    std::cout << "at rest         at t = " << num(r.time) << s
              << " (the time to rest: the supporting face flush on the wall, nothing moving)\n";
  else
    std::cout << "not at rest     stopped by "
              << (r.status == Status::max_time ? "--max-time" : "--max-steps") << " at t = " << num(r.time)
              << s << " (raise it; exit code 3)\n";
  if (r.stable_time >= 0)
    std::cout << "stable          at t = " << num(r.stable_time) << s
              << " (the paper's stability test, §2.4, passed: its run would stop here, the face up to "
                 "contact-threshold above the wall)\n";
  std::cout << "steps           " << r.steps
            << (params.integrator == Integrator::adaptive ? " adaptive steps, none longer than "
                                                          : " steps of ")
            << num(r.dt) << s << "\n";
  if (r.status == Status::rest) {
    std::cout << "rests on        " << to_string(r.rest) << " (hull face " << r.rest_face << ", "
              << r.contact_points.size() << " support points)\n"
              << "down normal     " << vec(r.down_normal_body) << " (body frame)\n";
  }
  std::cout << "orientation     "
            << vec(Eigen::Vector4d(r.orientation.w(), r.orientation.x(), r.orientation.y(),
                                   r.orientation.z()))
            << " (w, x, y, z; body to world)\n"
            << "centre of mass  " << vec(r.com) << m << "\n"
            << "penetration     " << num(r.max_penetration) << m << " max ("
            << num(r.max_penetration / particle.length) << " L)\n"
            << "energy          " << num(r.energy_start) << " -> " << num(r.energy_end) << " " << u.energy
            << " (kinetic + potential, from the wall)\n";
  if (!r.impacts.empty())
    std::cout << "impacts         " << r.impacts.size() << " while airborne, " << r.bounces
              << " followed by a flight (--json lists them)\n";
  std::cout << "phases (" << u.time << ")     ";
  for (const Phase& p : r.phases)
    std::cout << " " << to_string(p.contact) << " [" << num(p.t0) << ", " << num(p.t1) << "]";
  std::cout << "\n";
}

// What a run needs, from the scenario file (if any) with the options given on the command line on top.
struct RunSetup {
  std::string source;
  double density = 1.0;
  MeshOptions mesh;
  Quat orientation = Quat::Identity();
  SettleParams params;
};

RunSetup resolve_setup(const SettleOptions& o, const CLI::App& sub) {
  auto given = [&](const char* option) { return sub.count(option) > 0; };
  RunSetup setup;
  std::string units = "si";
  std::optional<Scenario> scenario;
  if (!o.scenario.empty()) {
    const Scenario& s = scenario.emplace(load_scenario(o.scenario));
    setup.source = s.particle;
    setup.density = s.density;
    setup.orientation = s.orientation;
    setup.params = s.params;
    units = s.units == UnitSystem::cgs ? "cgs" : "si";
  }
  if (!o.source.empty()) setup.source = o.source;
  if (setup.source.empty())
    throw Error("settle: give a particle (mesh file or shape spec) or --scenario FILE");
  if (given("--density") || o.scenario.empty()) setup.density = o.physics.density;
  check_positive("--density", setup.density);
  if (given("--orientation") || o.scenario.empty()) setup.orientation = parse_orientation(o.orientation);
  if (given("--units") || o.scenario.empty()) units = o.physics.units;
  setup.mesh = o.mesh.resolve(units == "cgs");
  if (scenario) {  // the scenario's mesh options, each one given on the command line on top
    MeshOptions& m = setup.mesh;
    const MeshOptions& from = scenario->mesh;
    if (!given("--scale") && !given("--mesh-units"))
      m.scale =
          scenario->mesh_units.empty() ? from.scale : mesh_unit_scale(scenario->mesh_units, units == "cgs");
    if (!given("--inertia")) m.inertia = from.inertia;
    m.repair = m.repair || from.repair;
    m.largest_component = m.largest_component || from.largest_component;
    if (!given("--com")) m.center_of_mass = from.center_of_mass;
  }
  SettleParams& p = setup.params;
  p.gravity = standard_gravity(units == "cgs" ? UnitSystem::cgs : UnitSystem::si);
  // Without a scenario these are the defaults; with one, its values. The options given go on top.
  o.physics.apply_given(sub, p);
  validate(p);
  return setup;
}

// Options that would be ignored are refused: they say the user expects something that would not happen.
void check_output_options(const SettleOptions& o, const CLI::App& sub) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  if (given("--frames") && given("--frame-dt"))
    throw Error(
        "settle: give --frames N (N frames spread over the run) or --frame-dt T (a frame every T), not both");
  for (const char* option : {"--frames", "--frame-dt"})
    if (given(option) && o.vtk_dir.empty())
      throw Error(std::string("settle: ") + option +
                  " sets the ParaView frames of --vtk DIR, which is not given");
  if (given("--sample-dt") && o.out_dir.empty() && o.vtk_dir.empty() && o.html.empty())
    throw Error(
        "settle: --sample-dt spaces the samples written by --out, --vtk or --html, and none is given");
}

}  // namespace

Command add_settle_command(CLI::App& app) {
  auto o = std::make_shared<SettleOptions>();
  CLI::App* sub = app.add_subcommand("settle", "Settle one particle on the wall z = 0 (the paper's method)");
  sub->add_option("particle", o->source, "Mesh file (STL, OBJ, PLY, OFF) or shape spec");
  sub->add_option(
      "--scenario", o->scenario,
      "Scenario file (JSON, e.g. scenarios/paper/cylinder-1106.json); options given here override it");
  sub->add_option("--orientation", o->orientation,
                  "Initial orientation, body to world: quat:w,x,y,z | axis-angle:x,y,z,radians | identity "
                  "(default identity: the mesh's axes as in the file)");
  add_physics_options(*sub, o->physics);
  add_mesh_options(*sub, o->mesh);
  add_param_options(*sub, o->physics, CliGroup::toss);  // --velocity, --spin
  add_impact_options(*sub, o->physics);
  sub->add_option("--out", o->out_dir, "Write timeseries.csv and summary.json into this directory");
  sub->add_option("--vtk", o->vtk_dir, "Write ParaView frames (.vtp) and settling.pvd into this directory");
  sub->add_option(
      "--html", o->html,
      "Write a self-contained HTML report: the run played in 3-D, with its plots (docs/reports.md)");
  sub->add_option(
         "--sample-dt", o->sample_dt,
         "Time between the samples of timeseries.csv and the ParaView frames' candidates (0 or unset: "
         "every step with --integrator paper, 1e-3*sqrt(L/g) with adaptive)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--frame-dt", o->frame_dt, "Time between ParaView frames (default: every step)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--frames", o->frames, "At most this many ParaView frames, evenly spread over the run")
      ->check(CLI::Range(2, 10000000));
  sub->add_flag("--json", o->json, "Print the JSON summary instead of text");
  sub->footer(
      "Exit codes: 0 at rest; 2 bad input; 3 stopped by --max-time or --max-steps before coming to rest (the "
      "outputs are written all the same).");
  return {sub, [o, sub]() {
            check_output_options(*o, *sub);
            const RunSetup setup = resolve_setup(*o, *sub);
            if (!o->out_dir.empty()) ensure_output_directory(o->out_dir);
            if (!o->vtk_dir.empty()) ensure_output_directory(o->vtk_dir);
            if (!o->html.empty()) ensure_output_file(o->html);
            const Particle particle = load_particle(setup.source, setup.density, setup.mesh);
            warn_implausible_size(particle, setup.params.gravity == standard_gravity(UnitSystem::cgs)
                                                ? UnitSystem::cgs
                                                : UnitSystem::si);

            // Samples are kept when frames must be spread over a run whose length is known only at its end.
            const bool keep_samples = !o->out_dir.empty() || !o->vtk_dir.empty() || !o->html.empty();
            std::vector<Sample> samples;
            // Without outputs no sample is kept, and the adaptive run is the same whatever the interval.
            const double sample_dt = !keep_samples      ? 0.0
                                     : o->sample_dt > 0 ? o->sample_dt
                                                        : default_sample_dt(particle, setup.params);
            const SettleResult r = settle(
                particle, setup.params, setup.orientation,
                [&](const Sample& s) {
                  if (keep_samples) samples.push_back(s);
                },
                sample_dt);
            std::string csv = time_series_header();
            for (const Sample& s : samples) csv += time_series_row(s);
            if (!o->vtk_dir.empty()) {
              double frame_dt = o->frame_dt;
              if (o->frames > 1 && frame_dt == 0) frame_dt = r.time / (o->frames - 1);
              VtkRecorder vtk(particle, o->vtk_dir, frame_dt, o->frames, setup.params.contact_threshold);
              for (const Sample& s : samples) vtk(s);
              vtk.finish(r);
            }
            const std::string summary = settle_summary_json(particle, setup.params, setup.orientation, r);
            if (!o->html.empty())
              write_file_atomically(o->html, settle_report_html({.title = particle.name,
                                                                 .particle = &particle,
                                                                 .params = setup.params,
                                                                 .initial = setup.orientation,
                                                                 .result = r,
                                                                 .samples = std::move(samples)}));
            if (!o->out_dir.empty()) {
              write_file_atomically(o->out_dir + "/timeseries.csv", csv);
              write_file_atomically(o->out_dir + "/summary.json", summary);
            }
            if (o->json)
              std::cout << summary;
            else
              print_summary(particle, setup.params, r, start_text(*o, *sub));
            return r.status == Status::rest ? 0 : 3;
          }};
}

}  // namespace repose::cli
