// libFuzzer harness for the rest-pose result reader (parse_poses_json: the files `repose merge` reads).
//
// Oracle: the text is rejected with repose::Error, or the study it gives can be written back out as JSON,
// CSV and a table (what `repose merge` does with it) without a crash, and the JSON it writes reads back as
// the same study, field by field and bit for bit: every number is written by nlohmann's shortest round-trip
// formatting and read back exactly, so no tolerance is needed. The rewritten file then rewrites to itself
// (JSON and CSV byte for byte). Fields the file does not carry (PoseTally::orientation, first_drop and
// settled when count is 0; the catalogue's face_pose and the params not written) keep their defaults on both
// sides, and are compared too.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "repose/error.hpp"
#include "repose/poses/study.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

// Bit-for-bit equality of doubles (NaN cannot come out of JSON, but -0.0 can and must stay -0.0).
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const repose::Vec3& a, const repose::Vec3& b) {
  return same(a.x(), b.x()) && same(a.y(), b.y()) && same(a.z(), b.z());
}
bool same(const repose::Quat& a, const repose::Quat& b) {
  return same(a.w(), b.w()) && same(a.x(), b.x()) && same(a.y(), b.y()) && same(a.z(), b.z());
}

void require_same_params(const repose::SettleParams& a, const repose::SettleParams& b) {
  require(same(a.gravity, b.gravity) && same(a.damping, b.damping) && same(a.dt, b.dt));
  require(same(a.contact_threshold, b.contact_threshold) && same(a.line_threshold, b.line_threshold));
  require(a.smooth == b.smooth && same(a.drop_height, b.drop_height) && same(a.drop_speed, b.drop_speed));
  require(same(a.max_time, b.max_time) && a.max_steps == b.max_steps);
  require(same(a.quaternion_tolerance, b.quaternion_tolerance) && a.max_iterations == b.max_iterations);
}

void require_identical(const repose::PosesStudy& a, const repose::PosesStudy& b) {
  require(a.source == b.source && a.fingerprint == b.fingerprint);
  require(same(a.density, b.density) && same(a.length, b.length) && same(a.mass, b.mass));
  require(a.hull_faces == b.hull_faces && a.smooth == b.smooth && a.decide_early == b.decide_early);
  require(a.threads == b.threads);
  require_same_params(a.params, b.params);

  const repose::RestPoseCatalog &ca = a.catalog, &cb = b.catalog;
  require(same(ca.persistence, cb.persistence) && ca.face_pose == cb.face_pose);
  require(ca.poses.size() == cb.poses.size());
  for (std::size_t p = 0; p < ca.poses.size(); ++p) {
    const repose::RestPose &x = ca.poses[p], &y = cb.poses[p];
    require(x.face == y.face && x.faces == y.faces && same(x.down_normal_body, y.down_normal_body));
    require(same(x.com_height, y.com_height) && same(x.barrier, y.barrier));
    require(same(x.quasi_static_probability, y.quasi_static_probability));
  }

  const repose::EnsembleTally &ta = a.tally, &tb = b.tally;
  require(ta.seed == tb.seed && ta.method == tb.method && ta.status_counts == tb.status_counts);
  require(ta.decided_early == tb.decided_early && ta.steps == tb.steps && same(ta.seconds, tb.seconds));
  require(ta.ranges.size() == tb.ranges.size() && ta.drops() == tb.drops());
  for (std::size_t r = 0; r < ta.ranges.size(); ++r)
    require(ta.ranges[r].begin == tb.ranges[r].begin && ta.ranges[r].end == tb.ranges[r].end);
  require(ta.poses.size() == tb.poses.size() && ta.poses.size() == ca.poses.size());
  for (std::size_t p = 0; p < ta.poses.size(); ++p) {
    const repose::PoseTally &x = ta.poses[p], &y = tb.poses[p];
    require(x.count == y.count && x.first_drop == y.first_drop && x.settled == y.settled);
    require(same(x.orientation, y.orientation));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  repose::PosesStudy study;
  try {
    study = repose::parse_poses_json(text, "fuzz/poses.json");
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  try {
    const std::string json = repose::poses_json(study);
    const std::string csv = repose::poses_csv(study);
    (void)repose::poses_table(study);
    const repose::PosesStudy back = repose::parse_poses_json(json, "fuzz/poses-rewritten.json");
    require_identical(study, back);
    require(repose::poses_json(back) == json && repose::poses_csv(back) == csv);
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
