// --export FILE (peer_bullet.cpp): each shape's drops and both engines' answers as JSON, for a third peer
// that is not a C++ library: the DEM code Yade runs the same drops in scripts/dem/yade_peer.py and
// scripts/dem/peer_table.py prints its column beside repose's and Bullet's (docs/performance.md, "Yade as a
// peer"). Everything a peer needs to run and classify a drop is here, in SI units: the hull (body frame: the
// centre of mass at the origin), its faces' outward normals with their rest pose and stability margin (a
// final orientation is classified as Bullet's is: its down direction -> the nearest hull face -> that face's
// pose), the catalogue's poses, and every drop's start orientation.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <repose/model/particle.hpp>
#include <repose/poses/rest_poses.hpp>
#include <repose/poses/sampling.hpp>
#include <vector>

#include "peer_report.hpp"

namespace peer {

inline nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

inline nlohmann::json export_row(const Row& row, const repose::Particle& particle,
                                 const repose::RestPoseCatalog& catalog, std::uint64_t seed,
                                 const std::vector<int>& repose_pose) {
  nlohmann::json out;
  out["name"] = row.name;
  out["length"] = particle.length;
  out["mass"] = particle.mass.mass;
  out["principal_moments"] = to_json(particle.mass.principal_moments);
  out["hull_vertices"] = nlohmann::json::array();
  for (const Vec3& v : particle.hull.vertices) out["hull_vertices"].push_back(to_json(v));
  out["faces"] = nlohmann::json::array();
  for (std::size_t f = 0; f < particle.hull.faces.size(); ++f)
    out["faces"].push_back({{"normal", to_json(particle.hull.faces[f].normal)},
                            {"pose", catalog.face_pose[f]},
                            {"stability_margin", particle.face_stability_margin[f]}});
  out["pose_down_normals"] = nlohmann::json::array();
  for (const repose::RestPose& p : catalog.poses)
    out["pose_down_normals"].push_back(to_json(p.down_normal_body));
  out["drops"] = nlohmann::json::array();
  for (std::uint64_t i = 0; i < row.drops; ++i) {
    const Quat q = repose::drop_orientation(seed, i);
    out["drops"].push_back({{"orientation", {q.w(), q.x(), q.y(), q.z()}}, {"repose_pose", repose_pose[i]}});
  }
  const double n = static_cast<double>(row.drops);
  out["repose"] = {{"ms_per_settle", 1e3 * row.repose_seconds / n},
                   {"setup_ms", 1e3 * row.repose_setup_seconds},
                   {"histogram", row.repose_hist}};
  const BulletRun& b = row.best();
  out["bullet"] = {{"step", b.step},
                   {"ms_per_settle", 1e3 * b.seconds / n},
                   {"setup_ms", 1e3 * b.setup_seconds},
                   {"simulated_s_per_settle", b.mean_time},
                   {"max_depth_L", std::max(0.0, b.depth) / row.length},
                   {"histogram", b.hist},
                   {"same_pose_as_repose", b.agree}};
  return out;
}

}  // namespace peer
