// The C API's rest-pose catalogue: the stable hull faces with their exact quasi-static probabilities.
#include <cmath>
#include <memory>
#include <string>

#include "capi_support.hpp"

using repose::capi::CodedError;
using repose::capi::guarded;
using repose::capi::require;

extern "C" {

int repose_poses_new(const repose_particle* particle, double persistence, repose_poses** poses) {
  return guarded("repose_poses_new", REPOSE_ERROR_INTERNAL, [&] {
    require(particle, "particle");
    require(poses, "poses");
    if (std::isnan(persistence) || std::isinf(persistence))
      throw CodedError(REPOSE_ERROR_BAD_PARAMETER, "persistence must be finite (negative: the default)");
    auto out = std::make_unique<repose_poses>();
    out->model = particle->model;
    const repose::Particle& p = *out->model;
    if (persistence < 0) persistence = repose::default_persistence(p, repose::is_smooth_surface(p));
    out->landscape = repose::compute_rest_landscape(p);
    out->catalog = repose::catalog_rest_poses(p, out->landscape, persistence);
    *poses = out.release();
  });
}

void repose_poses_free(repose_poses* poses) { delete poses; }

int repose_poses_count(const repose_poses* poses, int* count) {
  return guarded("repose_poses_count", REPOSE_ERROR_INTERNAL, [&] {
    require(poses, "poses");
    require(count, "count");
    *count = static_cast<int>(poses->catalog.poses.size());
  });
}

int repose_poses_get(const repose_poses* poses, int index, repose_pose* pose) {
  return guarded("repose_poses_get", REPOSE_ERROR_INTERNAL, [&] {
    require(poses, "poses");
    require(pose, "pose");
    const auto n = static_cast<int>(poses->catalog.poses.size());
    if (index < 0 || index >= n)
      throw CodedError(REPOSE_ERROR_BAD_INDEX,
                       "index " + std::to_string(index) + " is not a pose: there are " + std::to_string(n));
    const repose::RestPose& r = poses->catalog.poses[static_cast<std::size_t>(index)];
    repose_pose out{};
    out.face = r.face;
    for (int k = 0; k < 3; ++k) out.down_normal_body[k] = r.down_normal_body[k];
    out.com_height = r.com_height;
    out.barrier = r.barrier;
    out.probability = r.quasi_static_probability;
    *pose = out;
  });
}

int repose_poses_of_face(const repose_poses* poses, int face, int* pose) {
  return guarded("repose_poses_of_face", REPOSE_ERROR_INTERNAL, [&] {
    require(poses, "poses");
    require(pose, "pose");
    const auto n = static_cast<int>(poses->catalog.face_pose.size());
    if (face < 0 || face >= n)
      throw CodedError(REPOSE_ERROR_BAD_INDEX, "face " + std::to_string(face) +
                                                   " is not a hull face: there are " + std::to_string(n));
    *pose = poses->catalog.face_pose[static_cast<std::size_t>(face)];
  });
}

}  // extern "C"
