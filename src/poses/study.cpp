#include "repose/poses/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "../model/param_json.hpp"
#include "repose/error.hpp"
#include "repose/sim/settle.hpp"
#include "study_settings.hpp"

namespace repose {

namespace {

using nlohmann::json;

json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
json quat_json(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }

constexpr const char* kStatusNames[] = {"running", "rest", "max_time", "max_steps"};

}  // namespace

std::vector<int> report_order(const PosesStudy& study) {
  std::vector<int> order(study.catalog.poses.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const std::uint64_t ca = study.tally.poses[a].count, cb = study.tally.poses[b].count;
    if (ca != cb) return ca > cb;
    return study.catalog.poses[a].quasi_static_probability > study.catalog.poses[b].quasi_static_probability;
  });
  return order;
}

PosesStudy prepare_study(const Particle& particle, const RestLandscape& landscape,
                         const StudySettings& settings) {
  if (!std::isfinite(settings.damping_ratio) || settings.damping_ratio < 0)
    throw Error("the damping ratio must be a finite number >= 0");
  if (!std::isfinite(settings.persistence)) throw Error("the persistence must be a finite number");
  SettleParams params = settings.params;
  if (!settings.damping_given) params.damping = 0;
  validate(params);
  const TossDistribution& toss = settings.toss;
  validate(toss);
  if (settings.method == PoseMethod::quasi_static && (toss.active() || uses_impacts(params)))
    throw Error("tosses and rebounds need --method dynamic (quasi-static rolling has no momentum)");
  const bool smooth = params.smooth == SmoothMode::on ||
                      (params.smooth == SmoothMode::automatic && is_smooth_surface(particle));
  if (!settings.damping_given)
    params.damping = settings.damping_ratio * particle.mass.mass *
                     std::sqrt(params.gravity * std::pow(particle.length, 3));
  const double persistence = settings.persistence >= 0 ? settings.persistence * particle.length
                                                       : default_persistence(particle, smooth);
  PosesStudy study;
  study.source = particle.name;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(geometry_fingerprint(particle)));
  study.fingerprint = hex;
  study.density = settings.density;
  study.inertia = to_string(particle.options.inertia);
  study.scale = particle.options.scale;
  study.repaired = particle.repair.has_value();
  study.center_of_mass = particle.options.center_of_mass;
  study.length = particle.length;
  study.mass = particle.mass.mass;
  study.hull_faces = static_cast<int>(particle.hull.faces.size());
  study.smooth = smooth;
  study.params = params;
  study.decide_early = settings.decide_early;
  study.toss = settings.toss;
  study.catalog = catalog_rest_poses(particle, landscape, persistence);
  study.tally.seed = settings.seed;
  study.tally.method = settings.method;
  study.tally.poses.resize(study.catalog.poses.size());
  return study;
}

EnsembleOptions ensemble_options(const PosesStudy& study, DropRange drops, int threads) {
  EnsembleOptions options;
  options.seed = study.tally.seed;
  options.drops = drops;
  options.method = study.tally.method;
  options.params = study.params;
  options.decide_early = study.decide_early;
  options.toss = study.toss;
  options.threads = threads;
  return options;
}

std::uint64_t geometry_fingerprint(const Particle& particle) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bit
  const auto add = [&](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ULL;
  };
  for (const Vec3& v : particle.mesh.vertices) add(v.data(), 3 * sizeof(double));
  for (const auto& t : particle.mesh.triangles) add(t.data(), sizeof t);
  return hash;
}

std::string poses_json(const PosesStudy& s) {
  const std::uint64_t n = s.tally.drops();
  json j;
  j["command"] = "poses";
  j["units"] = units_json(unit_names_for_gravity(s.params.gravity));
  j["particle"] = {{"source", s.source}, {"density", s.density},       {"characteristic_length", s.length},
                   {"mass", s.mass},     {"hull_faces", s.hull_faces}, {"smooth", s.smooth}};
  if (!s.fingerprint.empty()) j["particle"]["fingerprint"] = s.fingerprint;
  j["particle"]["inertia_model"] = s.inertia;
  j["particle"]["scale"] = s.scale;
  j["particle"]["repaired"] = s.repaired;
  if (s.center_of_mass) j["particle"]["center_of_mass"] = vec_json(*s.center_of_mass);
  j["method"] = to_string(s.tally.method);
  j["seed"] = s.tally.seed;
  j["n"] = n;
  json ranges = json::array();
  for (const DropRange& r : s.tally.ranges) ranges.push_back({r.begin, r.end});
  j["drop_ranges"] = ranges;
  j["settings"] = settings_json(s);
  json poses = json::array();
  for (int p : report_order(s)) {
    const RestPose& pose = s.catalog.poses[p];
    const PoseTally& t = s.tally.poses[p];
    const auto ci = wilson_interval(t.count, n);
    poses.push_back({{"pose", p},
                     {"face", pose.face},
                     {"faces", pose.faces},
                     {"count", t.count},
                     {"probability", n ? static_cast<double>(t.count) / static_cast<double>(n) : 0.0},
                     {"ci95", {ci[0], ci[1]}},
                     {"quasi_static_probability", pose.quasi_static_probability},
                     {"down_normal_body", vec_json(pose.down_normal_body)},
                     {"com_height", pose.com_height},
                     {"barrier", std::isfinite(pose.barrier) ? json(pose.barrier) : json(nullptr)},
                     {"orientation", t.count ? quat_json(t.orientation) : json(nullptr)},
                     {"first_drop", t.count ? json(t.first_drop) : json(nullptr)}});
    if (t.count && !t.settled) poses.back()["settled"] = false;  // only in the pieces of a larger job
  }
  j["poses"] = poses;
  json status;
  for (int k = 1; k < 4; ++k) status[kStatusNames[k]] = s.tally.status_counts[k];
  j["status_counts"] = status;
  j["decided_early"] = s.tally.decided_early;
  j["steps"] = s.tally.steps;
  j["timing"] = {{"seconds", s.tally.seconds},
                 {"settles_per_second", s.tally.seconds > 0 ? static_cast<double>(n) / s.tally.seconds : 0.0},
                 {"threads", s.threads}};
  return j.dump(2) + "\n";
}

PosesStudy parse_poses_json(const std::string& text, const std::string& name) {
  // Integers are checked to be integers first: nlohmann converts a floating-point value with a plain cast,
  // undefined behaviour when it does not fit (found by fuzz_poses_result: 1e300 as a count).
  const auto whole = [&](const json& v) -> const json& {
    if (!v.is_number_integer()) throw Error(name + ": malformed poses result file (expected an integer)");
    return v;
  };
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object())
    throw Error(name +
                ": not a repose poses result file: " + (j.is_discarded() ? "not JSON" : "not a JSON object") +
                " (give the poses.json that repose poses --out writes; the CSV cannot be read back)");
  try {
    if (j.value("command", "") != "poses") throw Error(name + ": not a repose poses result file");
    PosesStudy s;
    const json& particle = j.at("particle");
    s.source = particle.at("source").get<std::string>();
    if (particle.contains("fingerprint")) s.fingerprint = particle.at("fingerprint").get<std::string>();
    s.density = particle.at("density").get<double>();
    // Files that predate these fields were all exact, unscaled and unrepaired.
    s.inertia = particle.value("inertia_model", std::string("exact"));
    if (s.inertia != "exact" && s.inertia != "convex" && s.inertia != "shell")
      throw Error(name + ": unknown inertia model '" + s.inertia + "'");
    s.scale = particle.value("scale", 1.0);
    s.repaired = particle.value("repaired", false);
    if (particle.contains("center_of_mass")) {
      const auto c = particle.at("center_of_mass").get<std::vector<double>>();
      if (c.size() != 3) throw Error(name + ": malformed poses result file (center_of_mass)");
      s.center_of_mass = Vec3(c[0], c[1], c[2]);
    }
    s.length = particle.at("characteristic_length").get<double>();
    s.mass = particle.at("mass").get<double>();
    s.hull_faces = whole(particle.at("hull_faces")).get<int>();
    s.smooth = particle.at("smooth").get<bool>();
    s.tally.method = parse_pose_method(j.at("method").get<std::string>());
    s.tally.seed = whole(j.at("seed")).get<std::uint64_t>();
    for (const json& r : j.at("drop_ranges")) {
      const DropRange range{whole(r.at(0)).get<std::uint64_t>(), whole(r.at(1)).get<std::uint64_t>()};
      // A drop range [begin, end) holds at least one drop (a run of no drops writes no range).
      if (range.begin >= range.end)
        throw Error(name + ": drop range [" + std::to_string(range.begin) + ", " + std::to_string(range.end) +
                    ") is empty or reversed");
      s.tally.ranges.push_back(range);
    }
    read_settings(j.at("settings"), s, name);

    const json& poses = j.at("poses");
    s.catalog.poses.resize(poses.size());
    s.tally.poses.resize(poses.size());
    for (const json& e : poses) {
      const auto index = whole(e.at("pose")).get<std::size_t>();
      if (index >= poses.size())
        throw Error(name + ": pose index " + std::to_string(index) + " out of range");
      RestPose& pose = s.catalog.poses[index];
      pose.face = whole(e.at("face")).get<int>();
      pose.faces.clear();
      for (const json& f : e.at("faces")) pose.faces.push_back(whole(f).get<int>());
      pose.quasi_static_probability = e.at("quasi_static_probability").get<double>();
      const auto down = e.at("down_normal_body").get<std::vector<double>>();
      if (down.size() != 3) throw Error(name + ": down_normal_body needs 3 numbers");
      pose.down_normal_body = Vec3(down[0], down[1], down[2]);
      pose.com_height = e.at("com_height").get<double>();
      pose.barrier =
          e.at("barrier").is_null() ? std::numeric_limits<double>::infinity() : e.at("barrier").get<double>();
      PoseTally& t = s.tally.poses[index];
      t.count = whole(e.at("count")).get<std::uint64_t>();
      if (t.count) {
        const auto q = e.at("orientation").get<std::vector<double>>();
        if (q.size() != 4) throw Error(name + ": orientation needs 4 numbers");
        t.orientation = Quat(q[0], q[1], q[2], q[3]);
        t.first_drop = whole(e.at("first_drop")).get<std::uint64_t>();
        t.settled = e.value("settled", true);
      }
    }
    const json& status = j.at("status_counts");
    for (int k = 1; k < 4; ++k)
      s.tally.status_counts[k] = whole(status.at(kStatusNames[k])).get<std::uint64_t>();
    s.tally.decided_early = whole(j.at("decided_early")).get<std::uint64_t>();
    s.tally.steps = whole(j.at("steps")).get<std::uint64_t>();
    s.tally.seconds = j.at("timing").at("seconds").get<double>();
    s.threads = whole(j.at("timing").at("threads")).get<int>();
    if (s.tally.drops() != whole(j.at("n")).get<std::uint64_t>())
      throw Error(name + ": n does not match drop_ranges");
    return s;
  } catch (const json::exception& e) {
    // nlohmann's "[json.exception.out_of_range.403] key 'n' not found" without its bracketed id.
    std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
      what = what.substr(what.find("] ") + 2);
    throw Error(name + ": malformed poses result file (" + what + ")");
  }
}

void require_same_study(const PosesStudy& a, const PosesStudy& b) {
  const auto require_same = [](bool same, const std::string& what) {
    if (!same) throw Error("cannot merge results for different " + what);
  };
  require_same(a.source == b.source && a.density == b.density && a.inertia == b.inertia &&
                   a.scale == b.scale && a.repaired == b.repaired && a.center_of_mass == b.center_of_mass &&
                   a.length == b.length && a.mass == b.mass && a.hull_faces == b.hull_faces &&
                   a.smooth == b.smooth &&
                   (a.fingerprint.empty() || b.fingerprint.empty() || a.fingerprint == b.fingerprint),
               "particles ('" + a.source + "' and '" + b.source + "')");
  if (a.tally.seed != b.tally.seed)
    throw Error("cannot merge results of different seeds (" + std::to_string(a.tally.seed) + " and " +
                std::to_string(b.tally.seed) + ")");
  if (a.tally.method != b.tally.method)
    throw Error(std::string("cannot merge results of different methods (") + to_string(a.tally.method) +
                " and " + to_string(b.tally.method) + ")");
  // The settings must agree exactly: the files round-trip doubles, so any difference is a different setting.
  require_same(json(settings_json(a)) == json(settings_json(b)), "settings (damping, dt, thresholds, ...)");
  require_same(a.catalog.poses.size() == b.catalog.poses.size(), "rest-pose catalogues");
  for (std::size_t p = 0; p < a.catalog.poses.size(); ++p)
    require_same(a.catalog.poses[p].faces == b.catalog.poses[p].faces, "rest-pose catalogues");
}

PosesStudy merge_studies(const PosesStudy& a, const PosesStudy& b) {
  require_same_study(a, b);
  PosesStudy m = a;
  m.tally = merge_tallies(a.tally, b.tally);
  m.threads = std::max(a.threads, b.threads);
  return m;
}

std::string poses_csv(const PosesStudy& s) {
  const std::uint64_t n = s.tally.drops();
  std::ostringstream out;
  out.precision(17);
  out << "pose,face,count,probability,ci95_lo,ci95_hi,quasi_static_probability,down_x,down_y,down_z,"
         "com_height,barrier,qw,qx,qy,qz\n";
  for (int p : report_order(s)) {
    const RestPose& pose = s.catalog.poses[p];
    const PoseTally& t = s.tally.poses[p];
    const auto ci = wilson_interval(t.count, n);
    out << p << ',' << pose.face << ',' << t.count << ','
        << (n ? static_cast<double>(t.count) / static_cast<double>(n) : 0.0) << ',' << ci[0] << ',' << ci[1]
        << ',' << pose.quasi_static_probability << ',' << pose.down_normal_body.x() << ','
        << pose.down_normal_body.y() << ',' << pose.down_normal_body.z() << ',' << pose.com_height << ',';
    if (std::isfinite(pose.barrier)) out << pose.barrier;
    out << ',';
    if (t.count)
      out << t.orientation.w() << ',' << t.orientation.x() << ',' << t.orientation.y() << ','
          << t.orientation.z();
    else
      out << ",,,";
    out << '\n';
  }
  return out.str();
}

std::string poses_table(const PosesStudy& s) {
  const std::uint64_t n = s.tally.drops();
  char line[256];
  std::string out;
  const UnitNames& units = unit_names_for_gravity(s.params.gravity);
  std::snprintf(line, sizeof line, "particle   %s (L = %.6g %s, %d hull faces%s)\n", s.source.c_str(),
                s.length, units.length, s.hull_faces, s.smooth ? ", smooth" : "");
  out += line;
  std::snprintf(line, sizeof line, "drops      %llu (%s, seed %llu)\n", static_cast<unsigned long long>(n),
                to_string(s.tally.method), static_cast<unsigned long long>(s.tally.seed));
  out += line;
  // The COM height's column is as wide as its heading with the unit (UTF-8 units are ASCII here).
  const std::string height = std::string("COM height (") + units.length + ")";
  const int width = static_cast<int>(height.size());
  out += "  pose   face    count  probability  95% interval       quasi-static  " + height +
         "  down normal (body)\n";
  const std::vector<int> order = report_order(s);
  int shown = 0;
  for (int p : order) {
    const RestPose& pose = s.catalog.poses[p];
    const PoseTally& t = s.tally.poses[p];
    if (t.count == 0 && pose.quasi_static_probability < 1e-4) continue;
    const auto ci = wilson_interval(t.count, n);
    std::snprintf(line, sizeof line,
                  "  %4d  %5d  %7llu  %11.5f  [%.5f, %.5f]  %12.5f  %*.5g  [%.4f, %.4f, %.4f]\n", p,
                  pose.face, static_cast<unsigned long long>(t.count),
                  n ? static_cast<double>(t.count) / static_cast<double>(n) : 0.0, ci[0], ci[1],
                  pose.quasi_static_probability, width, pose.com_height, pose.down_normal_body.x(),
                  pose.down_normal_body.y(), pose.down_normal_body.z());
    out += line;
    ++shown;
  }
  out +=
      "  (pose: its number in the catalogue, lowest centre of mass first, the same in the JSON, the CSV and\n"
      "   the HTML report; face: the hull face it rests on)\n";
  if (shown < static_cast<int>(order.size())) {
    std::snprintf(line, sizeof line,
                  "  (%d rarer poses with no drops and quasi-static probability < 1e-4: see --json)\n",
                  static_cast<int>(order.size()) - shown);
    out += line;
  }
  std::snprintf(line, sizeof line, "status     rest %llu, max_time %llu, max_steps %llu",
                static_cast<unsigned long long>(s.tally.status_counts[1]),
                static_cast<unsigned long long>(s.tally.status_counts[2]),
                static_cast<unsigned long long>(s.tally.status_counts[3]));
  out += line;
  if (s.tally.method == PoseMethod::dynamic) {
    std::snprintf(line, sizeof line, " (%llu decided early)",
                  static_cast<unsigned long long>(s.tally.decided_early));
    out += line;
  }
  std::snprintf(line, sizeof line, "\ntime       %.3f s, %.1f drops/s on %d threads\n", s.tally.seconds,
                s.tally.seconds > 0 ? static_cast<double>(n) / s.tally.seconds : 0.0, s.threads);
  out += line;
  return out;
}

}  // namespace repose
