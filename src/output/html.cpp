#include "repose/output/html.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "html_page.hpp"
#include "near_wall.hpp"
#include "repose/error.hpp"
#include "repose/output/report.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"

namespace repose {

namespace {

using json = nlohmann::json;

// Seven significant digits: far below a pixel, and the page stays small (nlohmann prints the shortest text
// that reads back, so a rounded double prints short).
double rounded(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", x);
  return std::strtod(buf, nullptr);
}

void append(json& flat, const Vec3& v) {
  for (int k = 0; k < 3; ++k) flat.push_back(rounded(v[k]));
}

// The surface drawn (body frame, centre of mass at the origin) and the hull's vertices, which the contact
// markers index.
json shape_json(const Particle& p) {
  json vertices = json::array(), triangles = json::array(), hull = json::array();
  const bool draw_hull = p.mesh.triangles.size() > kReportMaxTriangles;
  if (draw_hull) {
    for (const Vec3& v : p.hull.vertices) append(vertices, v);
    for (const HullFace& f : p.hull.faces)
      for (std::size_t k = 1; k + 1 < f.loop.size(); ++k)
        triangles.insert(triangles.end(), {f.loop[0], f.loop[k], f.loop[k + 1]});
  } else {
    for (const Vec3& v : p.mesh.vertices) append(vertices, v);
    for (const auto& t : p.mesh.triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  }
  for (const Vec3& v : p.hull.vertices) append(hull, v);
  return {{"name", p.name},       {"length", p.length},     {"surface", draw_hull ? "convex hull" : "mesh"},
          {"vertices", vertices}, {"triangles", triangles}, {"hull_vertices", hull}};
}

// The samples the page keeps: every k-th, k as small as keeps at most kReportMaxFrames, and the last.
std::vector<std::size_t> kept_samples(std::size_t n) {
  std::vector<std::size_t> kept;
  if (n == 0) return kept;
  const std::size_t stride = (n - 1 + kReportMaxFrames - 2) / (kReportMaxFrames - 1);  // ceil((n-1)/(max-1))
  for (std::size_t i = 0; i < n - 1; i += std::max<std::size_t>(stride, 1)) kept.push_back(i);
  kept.push_back(n - 1);
  return kept;
}

json run_json(const SettleRecording& run) {
  if (run.particle == nullptr) throw Error("report: a run without its particle");
  const Particle& p = *run.particle;
  std::vector<Sample> samples;
  for (std::size_t i : kept_samples(run.samples.size())) samples.push_back(run.samples[i]);
  // A run that rested after its last sample ends on its rest pose, at rest (no kinetic energy, by the
  // definition of rest).
  const SettleResult& r = run.result;
  if (r.status == Status::rest && (samples.empty() || samples.back().t < r.time)) {
    Sample last;
    last.t = r.time;
    last.orientation = r.orientation;
    last.com = r.com;
    last.contact = r.phases.empty() ? ContactType::surface : r.phases.back().contact;
    last.contact_count = static_cast<int>(r.contact_points.size());
    last.potential_energy = p.mass.mass * run.params.gravity * r.com.z();
    samples.push_back(last);
  }
  json t = json::array(), q = json::array(), com = json::array(), omega = json::array(),
       contact = json::array(), kinetic = json::array(), potential = json::array(), contacts = json::array(),
       sticking = json::array(), sliding = json::array();
  const double eps = run.params.contact_threshold * p.length;
  for (const Sample& s : samples) {
    t.push_back(s.t);
    for (double c : {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()})
      q.push_back(rounded(c));
    append(com, s.com);
    append(omega, s.omega);
    contact.push_back(static_cast<int>(s.contact));
    kinetic.push_back(rounded(s.kinetic_energy));
    potential.push_back(rounded(s.potential_energy));
    contacts.push_back(hull_vertices_near_wall(p, s.orientation, s.com, eps));
    sticking.push_back(s.sticking);  // the frictional contact phase's points by mode (0 elsewhere)
    sliding.push_back(s.sliding);
  }
  return {{"title", run.title.empty() ? p.name : run.title},
          {"shape", shape_json(p)},
          {"summary", json::parse(settle_summary_json(p, run.params, run.initial, r))},
          {"frames",
           {{"t", t},
            {"q", q},
            {"com", com},
            {"omega", omega},
            {"contact", contact},
            {"kinetic", kinetic},
            {"potential", potential},
            {"contacts", contacts},
            {"sticking", sticking},
            {"sliding", sliding}}}};
}

json contact_names() {
  json names = json::array();
  for (ContactType c : {ContactType::free_fall, ContactType::point, ContactType::line, ContactType::surface,
                        ContactType::flight})
    names.push_back(to_string(c));
  return names;
}

}  // namespace

std::string settle_report_html(const SettleRecording& run) {
  json data = run_json(run);
  data["kind"] = "settle";
  data["contact_names"] = contact_names();
  return html_page("repose settle: " + data["title"].get<std::string>(), data);
}

std::string poses_report_html(const Particle& particle, const PosesStudy& study) {
  json data = {{"kind", "poses"},
               {"title", study.source},
               {"shape", shape_json(particle)},
               {"study", json::parse(poses_json(study))}};
  return html_page("repose poses: " + study.source, data);
}

std::string design_report_page(const std::string& title, const Particle& design,
                               const std::vector<int>& face_outcome, const std::string& design_json) {
  if (face_outcome.size() != design.hull.faces.size())
    throw Error("report: the design's outcomes do not match its hull faces");
  const RestLandscape landscape = compute_rest_landscape(design);
  const RestPoseCatalog catalog = catalog_rest_poses(design, landscape, 0);  // every stable face its own pose
  std::vector<const RestPose*> order;
  for (const RestPose& p : catalog.poses) order.push_back(&p);
  // By outcome (those of no outcome last), then the most likely first.
  auto outcome = [&](const RestPose* p) {
    const int o = face_outcome[static_cast<std::size_t>(p->face)];
    return o < 0 ? INT32_MAX : o;
  };
  std::stable_sort(order.begin(), order.end(), [&](const RestPose* a, const RestPose* b) {
    if (outcome(a) != outcome(b)) return outcome(a) < outcome(b);
    return a->quasi_static_probability > b->quasi_static_probability;
  });
  json poses = json::array();
  for (const RestPose* p : order)
    poses.push_back(
        {{"face", p->face},
         {"outcome", face_outcome[static_cast<std::size_t>(p->face)]},
         {"down_normal_body", {p->down_normal_body.x(), p->down_normal_body.y(), p->down_normal_body.z()}},
         {"com_height", p->com_height},
         {"quasi_static_probability", p->quasi_static_probability}});
  const json data = {{"kind", "design"},
                     {"title", title},
                     {"shape", shape_json(design)},
                     {"design", json::parse(design_json)},
                     {"poses", poses}};
  return html_page("repose design: " + title, data);
}

std::string paper_report_html(const std::vector<SettleRecording>& cases,
                              const std::vector<PaperTableRow>& table,
                              const std::vector<PaperFigure>& figures) {
  json runs = json::array(), rows = json::array(), images = json::array();
  for (const SettleRecording& c : cases) runs.push_back(run_json(c));
  for (const PaperTableRow& r : table) rows.push_back({r.case_name, r.quantity, r.paper, r.exact, r.repose});
  for (const PaperFigure& f : figures)
    images.push_back({{"title", f.title}, {"src", "data:image/png;base64," + base64(f.png)}});
  const json data = {{"kind", "paper"},
                     {"title", "Daghooghi & Borazjani (2021), section 3, reproduced"},
                     {"contact_names", contact_names()},
                     {"cases", runs},
                     {"table", rows},
                     {"figures", images}};
  return html_page("repose paper: the cases of section 3", data);
}

}  // namespace repose
