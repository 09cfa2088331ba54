// repose design MESH|SHAPE --target FILE: the centre of mass and/or the convex hull that give a target
// probability per outcome under quasi-static rolling, or under the toss (--model tossed; design_toss_cli.hpp)
// (docs/inverse-design.md).
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "commands.hpp"
#include "design_toss_cli.hpp"
#include "format.hpp"
#include "mesh_options.hpp"
#include "repose/design/design.hpp"
#include "repose/design/design_json.hpp"
#include "repose/design/design_report.hpp"
#include "repose/design/target.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"

namespace repose::cli {

namespace {

struct DesignCliOptions {
  std::string source;
  std::string target;
  std::string vary = "vertices+center-of-mass";
  std::string mass = "follows";
  double outcome_angle = 30;  // degrees
  std::string outcome_normals = "fixed";
  DesignOptions design;
  std::string model = "quasi-static";
  TossCliOptions toss;
  MeshCliOptions mesh;
  std::string out_dir;
  std::string html;
  bool json = false;
  bool fold_faces = false;
};

void print_design(const DesignCliOptions& o, const DesignTarget& target, const DesignResult& r) {
  std::cout << "design of " << o.source << " for " << o.target << " (vary " << o.vary << ")\n";
  // With --outcome-normals follow the normals shown are where the outcomes' faces turned to.
  std::cout << (o.design.follow_outcome_normals ? "outcome  normal (followed)              "
                                                : "outcome  normal                         ")
            << "target    start     achieved\n";
  char line[160];
  // The normals the outcomes are assigned by at the design (the target's unless --outcome-normals follow).
  for (std::size_t k = 0; k < target.outcomes.size(); ++k) {
    const Vec3& n = r.outcome_normals[k];
    std::snprintf(line, sizeof line, "%-8zu [%7.4f, %7.4f, %7.4f]   %.5f   %.5f   %.5f\n", k + 1, n[0], n[1],
                  n[2], r.target[k], r.start[k], r.achieved[k]);
    std::cout << line;
  }
  std::snprintf(line, sizeof line, "%-8s %-30s %.5f   %.5f   %.5f\n", "other", "(faces of no outcome)", 0.0,
                r.start.back(), r.achieved.back());
  std::cout << line;
  std::cout
      << (r.reached() ? "reached" : "NOT reached") << ": max |achieved - target| " << num(r.max_error())
      << " after " << r.history.size() << " iterations ("
      << (r.stop == "converged" ? "within --tolerance"
          : r.stop == "stalled"
              ? "stalled: no step within the bounds lowers the error; the best achievable from this start"
              : "--iterations reached")
      << ")\n";
  std::cout << "centre of mass " << vec(r.center_of_mass) << "; a uniform solid's " << vec(r.centroid)
            << " (offset " << num((r.center_of_mass - r.centroid).norm()) << ")\n";
}

// design.obj, design.stl and design.json into `dir` (if one was given).
void write_design(const std::string& dir, const DesignResult& r, const std::string& json) {
  if (dir.empty()) return;
  write_obj(r.mesh, dir + "/design.obj");
  write_stl(r.mesh, dir + "/design.stl");
  write_file_atomically(dir + "/design.json", json);
}

}  // namespace

Command add_design_command(CLI::App& app) {
  auto opts = std::make_shared<DesignCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "design",
      "Design the centre of mass and/or the convex hull for target rest probabilities (quasi-static)");
  sub->add_option("particle", opts->source, "Mesh file or shape spec to start from, e.g. box:x=1,y=1,z=1")
      ->required();
  sub->add_option(
         "--target", opts->target,
         "JSON target: [[normal, p], ...] (convex_dice's pairs), {\"outcomes\": [{\"normal\": [...], "
         "\"probability\": p}, ...]} or {\"fair\": [normals]}; normals in the mesh's frame")
      ->required();
  sub->add_option(
      "--vary", opts->vary,
      "What may change: center-of-mass, vertices, faces (planes: faces stay flat), or a shape and "
      "center-of-mass joined by '+' (default vertices+center-of-mass)");
  sub->add_option("--mass", opts->mass,
                  "As the shape changes the centre of mass follows it (follows: a uniform part, or an insert "
                  "moving with it; default) or stays fixed in the body (fixed)")
      ->check(CLI::IsMember({"follows", "fixed"}));
  sub->add_option("--outcome-angle", opts->outcome_angle,
                  "Degrees: a hull face belongs to the nearest target normal within this (default 30)");
  sub->add_option("--outcome-normals", opts->outcome_normals,
                  "fixed: the target's normals stay put in the body (default); follow: after every step each "
                  "outcome's normal moves to its most probable face's (convex_dice's rule: an outcome is the "
                  "face the die shows, however the design turns it)")
      ->check(CLI::IsMember({"fixed", "follow"}));
  sub->add_option("--com-margin", opts->design.com_margin,
                  "x L: the centre of mass stays this far inside every face (default 0.05)");
  sub->add_option("--max-move", opts->design.max_vertex_move,
                  "x L: no vertex (faces: no face plane) moves further from where it started (default 0.15)");
  sub->add_option("--min-edge", opts->design.min_edge,
                  "x L: no hull edge gets shorter, unless it started shorter (default 0.02)");
  sub->add_option("--min-face", opts->design.min_face_area,
                  "x L^2: no hull face gets smaller, unless it started smaller (default 0.001)");
  sub->add_option(
      "--min-margin", opts->design.min_margin,
      "x L: draw every outcome toward a stable face with its centre of mass's projection at least "
      "this far inside (a robust face, and no stall at the edge of stability; default 0: only "
      "outcomes with no stable face)");
  sub->add_flag("--fold-faces", opts->fold_faces,
                "Vertices: let faces of four or more vertices fold (by default they stay flat: a flat face "
                "is a kink of the probabilities, and a die's faces are flat)");
  sub->add_option("--max-step", opts->design.max_step,
                  "x L: the most any vertex or face plane moves in one iteration (default 0.05)");
  sub->add_option("--smoothing", opts->design.smoothing,
                  "x L: shape steps are smooth over about this distance (0: each vertex or face on its own; "
                  "default 0.1)");
  sub->add_option("--tolerance", opts->design.tolerance,
                  "Done when every outcome is within this of its target (default 1e-4)");
  sub->add_option("--iterations", opts->design.max_iterations, "At most this many iterations (default 200)");
  sub->add_option(
         "--model", opts->model,
         "quasi-static (exact rolling probabilities; default) or tossed (the dynamic model's landings "
         "under the toss given by the options below, from the quasi-static design)")
      ->check(CLI::IsMember({"quasi-static", "tossed"}));
  add_toss_options(*sub, opts->toss);
  sub->add_option("--out", opts->out_dir,
                  "Write design.obj, design.stl (the design's hull, the mesh's frame) and design.json here");
  sub->add_option(
      "--html", opts->html,
      "Write a self-contained HTML report: target against achieved, the design in each rest pose, "
      "the history (docs/reports.md)");
  sub->add_flag("--json", opts->json, "Print design.json on stdout instead of the summary");
  add_mesh_options(*sub, opts->mesh);
  return {sub, [opts, sub]() {
            DesignCliOptions& o = *opts;
            o.design.freedom = parse_design_freedom(o.vary);
            o.design.mass = o.mass == "fixed" ? MassModel::fixed : MassModel::follows_shape;
            o.design.keep_faces_flat = !o.fold_faces;
            o.design.follow_outcome_normals = o.outcome_normals == "follow";
            if (!(o.outcome_angle > 0 && o.outcome_angle <= 180))
              throw Error("--outcome-angle " + num(o.outcome_angle) + ": must be in (0, 180] degrees");
            o.design.outcome_angle = o.outcome_angle * std::numbers::pi / 180;
            const bool tossed = o.model == "tossed";
            TossDesignOptions toss;
            if (tossed)
              toss = toss_design_options(o.toss, *sub, o.design);
            else
              reject_toss_options(*sub);
            const std::string text = read_text_file(o.target, std::size_t{1} << 24);
            const DesignTarget target = parse_design_target(text, o.target);
            if (!o.out_dir.empty()) ensure_output_directory(o.out_dir);
            const Particle start =
                load_particle(o.source, 1.0, o.mesh.resolve(o.toss.physics.unit_system() == UnitSystem::cgs));
            if (tossed) {
              const TossDesignResult r = design_for_toss(start, target, toss);
              const std::string j = toss_design_json(o.source, target, toss, r) + "\n";
              write_design(o.out_dir, r.design, j);
              if (!o.html.empty())
                write_file_atomically(o.html, design_report_html(o.source, target, o.design, r.design, j));
              if (o.json) {
                std::cout << j;
              } else {
                print_design(o, target, r.quasi_static_design);
                print_toss_design(target, toss, r);
                std::cout << "tossed design: centre of mass " << vec(r.design.center_of_mass)
                          << "; a uniform solid's " << vec(r.design.centroid) << "\n";
                if (!o.out_dir.empty()) std::cout << "wrote " << o.out_dir << "/design.{obj,stl,json}\n";
              }
              return 0;
            }
            const DesignResult r = design_quasi_static(start, target, o.design);
            const std::string j = design_json(o.source, target, o.design, r) + "\n";
            write_design(o.out_dir, r, j);
            if (!o.html.empty())
              write_file_atomically(o.html, design_report_html(o.source, target, o.design, r, j));
            if (o.json) {
              std::cout << j;
            } else {
              print_design(o, target, r);
              if (!o.out_dir.empty()) std::cout << "wrote " << o.out_dir << "/design.{obj,stl,json}\n";
            }
            return 0;
          }};
}

}  // namespace repose::cli
