// Serialising settling runs: the JSON summary and the time-series CSV.
#pragma once

#include <string>
#include <vector>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

namespace repose {

/// The JSON summary of one run (field names are stable; see docs/settle.md):
/// status, time_to_rest, steps, max_penetration, rest {orientation [w,x,y,z], com, contact, contact_points,
/// down_normal_body, face}, phases [{contact, t0, t1}], energy {start, end}, plus the particle and
/// parameters.
std::string settle_summary_json(const Particle& particle, const SettleParams& params, const Quat& initial,
                                const SettleResult& result);

/// What the mesh file held, as a JSON object (the "file" of `repose info --json`, Python's
/// Particle.file_report): vertices, triangles, duplicate_vertices, degenerate_triangles, unused_vertices,
/// flipped, warnings. The counts are the file's own, before any --repair.
std::string file_report_json(const MeshReport& report);
/// What --repair did, as a JSON object (the "repair" of `repose info --json`, Python's
/// Particle.repair_report): merged_vertices, flat_components, input_components, kept_components,
/// stitched_edges, duplicate_faces, degenerate_faces, non_manifold_vertices, flipped_faces, holes_filled,
/// area_added, volume_change, notes.
std::string repair_report_json(const RepairReport& report);

/// The CSV header of the time series.
std::string time_series_header();
/// One CSV row: t, qw, qx, qy, qz, wx, wy, wz, x, y, z, contact, contact_count, kinetic, potential.
std::string time_series_row(const Sample& s);

}  // namespace repose
