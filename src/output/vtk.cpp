#include "repose/output/vtk.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

#include "near_wall.hpp"
#include "repose/error.hpp"
#include "repose/output/files.hpp"

namespace repose {

namespace {

// Locale-independent number formatting (std::to_chars never uses the C locale's decimal separator).
void append_number(std::string& out, double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 9);  // like %.9g
  out.append(buf, r.ptr);
}

// The shortest representation that reads back as the same double: distinct times stay distinct.
std::string exact_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void append_integer(std::string& out, long long v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

std::string frame_name(const char* prefix, int index) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%05d.vtp", prefix, index);
  return buf;
}

constexpr const char* kHeader =
    "<?xml version=\"1.0\"?>\n"
    "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    "  <PolyData>\n";
constexpr const char* kFooter =
    "  </PolyData>\n"
    "</VTKFile>\n";

void append_time(std::string& out, double t) {
  out += "    <FieldData>\n";
  out += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">";
  out += exact_number(t);
  out += "</DataArray>\n";
  out += "    </FieldData>\n";
}

void append_piece_start(std::string& out, std::size_t points, std::size_t verts, std::size_t polys) {
  out += "    <Piece NumberOfPoints=\"";
  append_integer(out, static_cast<long long>(points));
  out += "\" NumberOfVerts=\"";
  append_integer(out, static_cast<long long>(verts));
  out += "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"";
  append_integer(out, static_cast<long long>(polys));
  out += "\">\n";
}

void append_points(std::string& out, const std::vector<Vec3>& points) {
  out += "      <Points>\n";
  out += "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3& p : points) {
    out += "          ";
    append_number(out, p.x());
    out += ' ';
    append_number(out, p.y());
    out += ' ';
    append_number(out, p.z());
    out += '\n';
  }
  out += "        </DataArray>\n";
  out += "      </Points>\n";
}

// A cell array (Verts or Polys): connectivity, then offsets (the end of each cell in connectivity).
void append_cells(std::string& out, const char* element, const std::vector<std::int64_t>& connectivity,
                  const std::vector<std::int64_t>& offsets, int per_line) {
  out += "      <";
  out += element;
  out += ">\n";
  const std::pair<const char*, const std::vector<std::int64_t>*> arrays[] = {{"connectivity", &connectivity},
                                                                             {"offsets", &offsets}};
  for (const auto& [name, values] : arrays) {
    out += "        <DataArray type=\"Int64\" Name=\"";
    out += name;
    out += "\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < values->size(); ++i) {
      out += i % per_line == 0 ? "          " : " ";
      append_integer(out, (*values)[i]);
      if (i % per_line == static_cast<std::size_t>(per_line - 1) || i + 1 == values->size()) out += '\n';
    }
    out += "        </DataArray>\n";
  }
  out += "      </";
  out += element;
  out += ">\n";
}

}  // namespace

VtkRecorder::VtkRecorder(const Particle& particle, std::string dir, double frame_dt, int max_frames,
                         double contact_threshold)
    : particle_(particle),
      dir_(std::move(dir)),
      frame_dt_(frame_dt),
      max_frames_(max_frames),
      contact_threshold_(contact_threshold) {
  if (!(std::isfinite(frame_dt) && frame_dt >= 0))
    throw Error("vtk: frame interval must be a finite number >= 0, got " + exact_number(frame_dt));
  if (max_frames < 0 || max_frames == 1)
    throw Error("vtk: max frames must be 0 (no limit) or >= 2, got " + std::to_string(max_frames));
  if (!(std::isfinite(contact_threshold) && contact_threshold > 0))
    throw Error("vtk: contact threshold must be a finite number > 0, got " + exact_number(contact_threshold));
  if (dir_.empty()) throw Error("vtk: empty output directory");
  ensure_output_directory(dir_);

  std::vector<std::int64_t> connectivity, offsets;
  connectivity.reserve(3 * particle_.mesh.triangles.size());
  offsets.reserve(particle_.mesh.triangles.size());
  for (const Triangle& tri : particle_.mesh.triangles) {
    connectivity.insert(connectivity.end(), tri.begin(), tri.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  append_cells(polys_, "Polys", connectivity, offsets, 12);
}

std::function<void(const Sample&)> VtkRecorder::observer() {
  return [this](const Sample& s) { (*this)(s); };
}

void VtkRecorder::operator()(const Sample& s) {
  if (finished_) throw Error("vtk: " + dir_ + ": sample recorded after finish()");
  if (!times_.empty()) {
    if (!(s.t > times_.back() && s.t >= times_.back() + frame_dt_)) return;
    if (max_frames_ > 0 && frames() >= max_frames_ - 1) return;  // the last slot is for the final state
  }
  if (times_.empty()) write_wall(s.com);
  write_frame(frames(), s.t, s.orientation, s.com);
  times_.push_back(s.t);
}

void VtkRecorder::finish(const SettleResult& result) {
  if (finished_) throw Error("vtk: " + dir_ + ": finish() called twice");
  if (times_.empty()) {
    write_wall(result.com);
    times_.push_back(result.time);
  } else if (result.time > times_.back()) {
    times_.push_back(result.time);
  }
  // Otherwise the last frame is already at result.time (or later, which a run does not produce): it is
  // rewritten with the result's pose, which is the one the summary reports.
  write_frame(frames() - 1, times_.back(), result.orientation, result.com);

  for (const char* prefix : {"particle", "markers"}) {
    std::string pvd =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        "  <Collection>\n";
    for (int i = 0; i < frames(); ++i) {
      pvd += "    <DataSet timestep=\"" + exact_number(times_[i]) + "\" group=\"\" part=\"0\" file=\"" +
             frame_name(prefix, i) + "\"/>\n";
    }
    pvd += "  </Collection>\n</VTKFile>\n";
    const std::string name = std::string(prefix) == "particle" ? "settling.pvd" : "markers.pvd";
    write_file_atomically(dir_ + "/" + name, pvd);
  }
  finished_ = true;
}

void VtkRecorder::write_frame(int index, double t, const Quat& orientation, const Vec3& com) {
  const Mat3 rot = orientation.normalized().toRotationMatrix();

  // The particle surface.
  std::vector<Vec3> world;
  world.reserve(particle_.mesh.vertices.size());
  for (const Vec3& v : particle_.mesh.vertices) world.push_back(rot * v + com);
  std::string out = kHeader;
  append_time(out, t);
  append_piece_start(out, world.size(), 0, particle_.mesh.triangles.size());
  out += "      <PointData Scalars=\"height\">\n";
  out += "        <DataArray type=\"Float64\" Name=\"height\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < world.size(); ++i) {
    out += i % 8 == 0 ? "          " : " ";
    append_number(out, world[i].z());
    if (i % 8 == 7 || i + 1 == world.size()) out += '\n';
  }
  out += "        </DataArray>\n";
  out += "      </PointData>\n";
  append_points(out, world);
  out += polys_;
  out += "    </Piece>\n";
  out += kFooter;
  write_file_atomically(dir_ + "/" + frame_name("particle", index), out);

  // The markers: centre of mass, then the hull vertices within the contact threshold of the wall.
  std::vector<Vec3> markers{com};
  const double eps = contact_threshold_ * particle_.length;
  for (int k : hull_vertices_near_wall(particle_, orientation, com, eps))
    markers.push_back(rot * particle_.hull.vertices[static_cast<std::size_t>(k)] + com);
  std::vector<std::int64_t> connectivity, offsets;
  for (std::size_t i = 0; i < markers.size(); ++i) {
    connectivity.push_back(static_cast<std::int64_t>(i));
    offsets.push_back(static_cast<std::int64_t>(i + 1));
  }
  out = kHeader;
  append_time(out, t);
  append_piece_start(out, markers.size(), markers.size(), 0);
  out += "      <PointData Scalars=\"kind\">\n";
  out += "        <DataArray type=\"Int32\" Name=\"kind\" format=\"ascii\">\n          0";
  for (std::size_t i = 1; i < markers.size(); ++i) out += " 1";
  out += "\n        </DataArray>\n";
  out += "      </PointData>\n";
  append_points(out, markers);
  append_cells(out, "Verts", connectivity, offsets, 12);
  out += "    </Piece>\n";
  out += kFooter;
  write_file_atomically(dir_ + "/" + frame_name("markers", index), out);
}

void VtkRecorder::write_wall(const Vec3& com) {
  double radius = 0;
  for (const Vec3& v : particle_.mesh.vertices) radius = std::max(radius, v.norm());
  const double half = 2 * std::max(particle_.length, radius);
  const std::vector<Vec3> corners{{com.x() - half, com.y() - half, 0},
                                  {com.x() + half, com.y() - half, 0},
                                  {com.x() + half, com.y() + half, 0},
                                  {com.x() - half, com.y() + half, 0}};
  std::string out = kHeader;
  append_piece_start(out, corners.size(), 0, 1);
  append_points(out, corners);
  append_cells(out, "Polys", {0, 1, 2, 3}, {4}, 12);
  out += "    </Piece>\n";
  out += kFooter;
  write_file_atomically(dir_ + "/wall.vtp", out);
}

}  // namespace repose
