#include "repose/campaign/summary.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "repose/error.hpp"

namespace repose {

namespace {

// What a row shows about one particle.
struct Row {
  std::uint64_t n = 0;
  int poses_seen = 0;  // poses at least one drop ended in
  int top = -1;        // most frequent pose (report order); −1 if no drop rested
  double probability = 0;
  std::array<double, 2> ci{0, 0};
  Vec3 down = Vec3::Zero();
  std::uint64_t not_at_rest = 0;
};

Row row_of(const PosesStudy& s) {
  Row r;
  r.n = s.tally.drops();
  for (const PoseTally& t : s.tally.poses) r.poses_seen += t.count > 0;
  const std::vector<int> order = report_order(s);
  if (!order.empty() && s.tally.poses[order[0]].count > 0) {
    r.top = order[0];
    const std::uint64_t count = s.tally.poses[r.top].count;
    r.probability = static_cast<double>(count) / static_cast<double>(r.n);
    r.ci = wilson_interval(count, r.n);
    r.down = s.catalog.poses[r.top].down_normal_body;
  }
  r.not_at_rest = s.tally.status_counts[2] + s.tally.status_counts[3];
  return r;
}

// A CSV field in quotes, quotes inside doubled (RFC 4180): sources may hold commas (shape specs) or quotes.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + '"';
}

void check(const CampaignSummary& s) {
  if (s.studies.size() != s.particles.size() || s.result_files.size() != s.particles.size())
    throw Error("campaign summary: one study and one result file per particle needed");
}

}  // namespace

std::string summary_csv(const CampaignSummary& summary) {
  check(summary);
  std::ostringstream out;
  out.precision(17);
  out << "particle,source,result_file,hull_faces,smooth,drops,poses_seen,top_pose,top_probability,"
         "top_ci95_lo,top_ci95_hi,top_down_x,top_down_y,top_down_z,not_at_rest\n";
  for (std::size_t i = 0; i < summary.particles.size(); ++i) {
    const PosesStudy& s = summary.studies[i];
    const Row r = row_of(s);
    out << summary.particles[i].name << ',' << quoted(summary.particles[i].source) << ','
        << summary.result_files[i] << ',' << s.hull_faces << ',' << (s.smooth ? 1 : 0) << ',' << r.n << ','
        << r.poses_seen << ',';
    if (r.top >= 0)
      out << r.top << ',' << r.probability << ',' << r.ci[0] << ',' << r.ci[1] << ',' << r.down.x() << ','
          << r.down.y() << ',' << r.down.z();
    else
      out << ",,,,,,";
    out << ',' << r.not_at_rest << '\n';
  }
  return out.str();
}

std::string summary_markdown(const CampaignSummary& summary) {
  check(summary);
  std::string out =
      "| particle | hull faces | drops | poses seen | most likely pose | probability | 95 % interval | "
      "down normal (body) | not at rest |\n"
      "|---|---:|---:|---:|---:|---:|---|---|---:|\n";
  char line[512];
  for (std::size_t i = 0; i < summary.particles.size(); ++i) {
    const PosesStudy& s = summary.studies[i];
    const Row r = row_of(s);
    if (r.top >= 0)
      std::snprintf(line, sizeof line,
                    "| %s | %d | %llu | %d | %d | %.5f | [%.5f, %.5f] | [%.4f, %.4f, %.4f] | %llu |\n",
                    summary.particles[i].name.c_str(), s.hull_faces, static_cast<unsigned long long>(r.n),
                    r.poses_seen, r.top, r.probability, r.ci[0], r.ci[1], r.down.x(), r.down.y(), r.down.z(),
                    static_cast<unsigned long long>(r.not_at_rest));
    else
      std::snprintf(line, sizeof line, "| %s | %d | %llu | 0 | – | – | – | – | %llu |\n",
                    summary.particles[i].name.c_str(), s.hull_faces, static_cast<unsigned long long>(r.n),
                    static_cast<unsigned long long>(r.not_at_rest));
    out += line;
  }
  return out;
}

std::string summary_json(const CampaignSummary& summary) {
  using nlohmann::json;
  check(summary);
  json j;
  j["command"] = "poses-summary";
  json particles = json::array();
  for (std::size_t i = 0; i < summary.particles.size(); ++i) {
    const PosesStudy& s = summary.studies[i];
    const Row r = row_of(s);
    json p = {{"name", summary.particles[i].name},
              {"source", summary.particles[i].source},
              {"result_file", summary.result_files[i]},
              {"hull_faces", s.hull_faces},
              {"smooth", s.smooth},
              {"method", to_string(s.tally.method)},
              {"seed", s.tally.seed},
              {"n", r.n},
              {"poses_seen", r.poses_seen},
              {"not_at_rest", r.not_at_rest}};
    if (r.top >= 0)
      p["top_pose"] = {{"pose", r.top},
                       {"probability", r.probability},
                       {"ci95", {r.ci[0], r.ci[1]}},
                       {"down_normal_body", {r.down.x(), r.down.y(), r.down.z()}}};
    else
      p["top_pose"] = nullptr;
    particles.push_back(p);
  }
  j["particles"] = particles;
  j["timing"] = {{"seconds", summary.seconds}, {"ranks", summary.ranks}, {"threads", summary.threads}};
  return j.dump(2) + "\n";
}

}  // namespace repose
