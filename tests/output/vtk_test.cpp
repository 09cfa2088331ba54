// ParaView output (VtkRecorder): a real settling run is recorded, then every written file is parsed back and
// checked for structural validity (VTK XML PolyData / Collection) and for the physics it should show: the
// particle starts touching the wall and ends resting on it with the centre of mass the run reports.
// Units are CGS as in the paper: cm, g, s, g = 981 cm/s².
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <locale>
#include <map>
#include <repose/error.hpp>
#include <repose/model/orientation.hpp>
#include <repose/model/particle.hpp>
#include <repose/output/vtk.hpp>
#include <repose/sim/settle.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace repose {
namespace {

namespace fs = std::filesystem;

// Tolerances on what the files show, relative to L. The writer prints 9 significant digits (like %.9g), so a
// coordinate x reads back within 5e-9·|x|; coordinates here stay below 1.5·L, so a point moves by at most
// sqrt(3)·7.5e-9·L = 1.3e-8·L: kPrinted = 2e-8 is that bound (measured ≤ 7.9e-10·L). Heights at the wall
// print with full relative precision, leaving the engine's placement: a touching vertex is within 1e-12·L of
// the wall (docs/method.md, event location) and a rest is set exactly flush (measured ≤ 1.1e-16·L).
constexpr double kPrinted = 2e-8;
constexpr double kAtWall = 1e-12;

// ---- a minimal XML reader: elements, attributes, text; enough to check well-formedness of what we write --

struct Node {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::vector<Node> children;

  const Node& child(const std::string& n) const {
    for (const Node& c : children)
      if (c.name == n) return c;
    throw std::runtime_error("<" + name + "> has no <" + n + ">");
  }
  std::vector<const Node*> all(const std::string& n) const {
    std::vector<const Node*> out;
    for (const Node& c : children)
      if (c.name == n) out.push_back(&c);
    return out;
  }
  const std::string& attr(const std::string& a) const {
    const auto it = attrs.find(a);
    if (it == attrs.end()) throw std::runtime_error("<" + name + "> has no attribute " + a);
    return it->second;
  }
};

class XmlReader {
 public:
  explicit XmlReader(std::string text) : s_(std::move(text)) {}

  Node document() {
    skip_space();
    if (s_.compare(i_, 5, "<?xml") == 0) {
      const std::size_t end = s_.find("?>", i_);
      if (end == std::string::npos) fail("unterminated XML declaration");
      i_ = end + 2;
    }
    skip_space();
    Node root = element();
    skip_space();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML: " + what + " at offset " + std::to_string(i_));
  }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  std::string name() {
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' ||
                              s_[i_] == ':' || s_[i_] == '-' || s_[i_] == '.'))
      ++i_;
    if (i_ == start) fail("expected a name");
    return s_.substr(start, i_ - start);
  }
  void expect(char c) {
    if (i_ >= s_.size() || s_[i_] != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  Node element() {
    Node node;
    expect('<');
    node.name = name();
    for (;;) {
      skip_space();
      if (i_ >= s_.size()) fail("unterminated tag");
      if (s_[i_] == '/') {
        ++i_;
        expect('>');
        return node;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      const std::string key = name();
      skip_space();
      expect('=');
      skip_space();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) fail("unquoted attribute");
      const char quote = s_[i_++];
      const std::size_t end = s_.find(quote, i_);
      if (end == std::string::npos) fail("unterminated attribute");
      const std::string value = s_.substr(i_, end - i_);
      if (value.find_first_of("<&") != std::string::npos) fail("markup in attribute value");
      if (!node.attrs.emplace(key, value).second) fail("duplicate attribute " + key);
      i_ = end + 1;
    }
    for (;;) {
      const std::size_t lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unterminated element <" + node.name + ">");
      const std::string text = s_.substr(i_, lt - i_);
      if (text.find('&') != std::string::npos || text.find('>') != std::string::npos)
        fail("raw & or > in text");
      node.text += text;
      i_ = lt;
      if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        if (name() != node.name) fail("mismatched end tag for <" + node.name + ">");
        skip_space();
        expect('>');
        return node;
      }
      node.children.push_back(element());
    }
  }

  std::string s_;
  std::size_t i_ = 0;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot read");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Node parse_file(const fs::path& path) { return XmlReader(slurp(path)).document(); }

std::vector<double> numbers(const Node& array) {
  std::istringstream in(array.text);
  in.imbue(std::locale::classic());
  std::vector<double> out;
  double v;
  while (in >> v) out.push_back(v);
  if (!in.eof())
    throw std::runtime_error("DataArray " + array.name + ": not a number in '" + array.text + "'");
  return out;
}

long count_attr(const Node& piece, const std::string& a) {
  const auto it = piece.attrs.find(a);
  return it == piece.attrs.end() ? 0 : std::stol(it->second);
}

// ---- VTK XML PolyData, checked and decoded ----------------------------------------------------------------

struct PolyFile {
  double time = std::nan("");  // FieldData TimeValue, NaN if absent
  std::vector<Vec3> points;
  std::map<std::string, std::vector<double>> point_data;
  std::vector<std::vector<long>> verts, polys;  // cells as point-index lists
};

// Checks a cell element (Verts / Polys): connectivity indices in range, offsets increasing and ending at the
// connectivity's length, as many cells as the Piece declares.
std::vector<std::vector<long>> cells(const Node& piece, const std::string& element, long n_points) {
  const long declared = count_attr(piece, "NumberOf" + element);
  std::vector<std::vector<long>> out;
  const auto nodes = piece.all(element);
  if (nodes.empty()) {
    EXPECT_EQ(declared, 0) << element;
    return out;
  }
  EXPECT_EQ(nodes.size(), 1u) << element;
  std::vector<double> connectivity, offsets;
  for (const Node* a : nodes[0]->all("DataArray")) {
    EXPECT_TRUE(a->attr("type") == "Int32" || a->attr("type") == "Int64") << a->attr("type");
    EXPECT_EQ(a->attr("format"), "ascii");
    if (a->attr("Name") == "connectivity") connectivity = numbers(*a);
    if (a->attr("Name") == "offsets") offsets = numbers(*a);
  }
  EXPECT_EQ(static_cast<long>(offsets.size()), declared) << element;
  long begin = 0;
  for (const double o : offsets) {
    EXPECT_EQ(o, std::floor(o));
    const long end = static_cast<long>(o);
    EXPECT_GT(end, begin) << element << ": offsets not increasing";
    if (end <= begin || end > static_cast<long>(connectivity.size())) break;
    std::vector<long> cell;
    for (long k = begin; k < end; ++k) {
      const double idx = connectivity[k];
      EXPECT_EQ(idx, std::floor(idx));
      EXPECT_GE(idx, 0);
      EXPECT_LT(idx, n_points) << element << ": connectivity index out of range";
      cell.push_back(static_cast<long>(idx));
    }
    out.push_back(cell);
    begin = end;
  }
  EXPECT_EQ(begin, static_cast<long>(connectivity.size())) << element << ": offsets do not end at the end";
  return out;
}

PolyFile read_polydata(const fs::path& path) {
  SCOPED_TRACE(path.string());
  const Node root = parse_file(path);
  EXPECT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attr("type"), "PolyData");
  EXPECT_EQ(root.attr("version"), "0.1");
  EXPECT_EQ(root.attr("byte_order"), "LittleEndian");
  const Node& poly = root.child("PolyData");
  PolyFile f;
  for (const Node* fd : poly.all("FieldData")) {
    for (const Node* a : fd->all("DataArray")) {
      if (a->attr("Name") != "TimeValue") continue;
      const std::vector<double> t = numbers(*a);
      EXPECT_EQ(t.size(), 1u);
      EXPECT_EQ(a->attr("NumberOfTuples"), "1");
      if (!t.empty()) f.time = t[0];
    }
  }
  const auto pieces = poly.all("Piece");
  EXPECT_EQ(pieces.size(), 1u);
  const Node& piece = *pieces.at(0);
  const long n = count_attr(piece, "NumberOfPoints");
  const Node& points = piece.child("Points").child("DataArray");
  EXPECT_EQ(points.attr("NumberOfComponents"), "3");
  EXPECT_EQ(points.attr("format"), "ascii");
  const std::vector<double> xyz = numbers(points);
  EXPECT_EQ(static_cast<long>(xyz.size()), 3 * n) << "NumberOfPoints does not match the Points";
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) f.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  for (const Node* pd : piece.all("PointData")) {
    for (const Node* a : pd->all("DataArray")) {
      std::vector<double> v = numbers(*a);
      EXPECT_EQ(static_cast<long>(v.size()), n) << "point data " << a->attr("Name");
      f.point_data[a->attr("Name")] = std::move(v);
    }
  }
  f.verts = cells(piece, "Verts", n);
  f.polys = cells(piece, "Polys", n);
  EXPECT_EQ(count_attr(piece, "NumberOfLines"), 0);
  EXPECT_EQ(count_attr(piece, "NumberOfStrips"), 0);
  return f;
}

struct PvdEntry {
  double t = 0;
  std::string file;
};

std::vector<PvdEntry> read_pvd(const fs::path& path) {
  SCOPED_TRACE(path.string());
  const Node root = parse_file(path);
  EXPECT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attr("type"), "Collection");
  EXPECT_EQ(root.attr("version"), "0.1");
  std::vector<PvdEntry> out;
  for (const Node* d : root.child("Collection").all("DataSet")) {
    EXPECT_EQ(d->attr("part"), "0");
    out.push_back({std::stod(d->attr("timestep")), d->attr("file")});
  }
  return out;
}

// The markers file of a particle frame: particle_NNNNN.vtp → markers_NNNNN.vtp.
std::string markers_of(const PvdEntry& e) {
  return "markers_" + e.file.substr(std::string("particle_").size());
}

std::vector<std::string> files_matching(const fs::path& dir, const std::string& prefix,
                                        const std::string& ext) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.starts_with(prefix) && n.ends_with(ext)) out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// ---- fixtures -------------------------------------------------------------------------------------------

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : path_(fs::temp_directory_path() / ("repose_vtk_" + tag + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

SettleParams cgs_params() {
  SettleParams p;
  p.gravity = 981.0;
  return p;
}

const Particle& tetrahedron() {
  static const Particle tet = load_particle("tetrahedron:edge=1", 1.2);
  return tet;
}

const Quat& tilted() {
  static const Quat q = parse_orientation("axis-angle:1,0.3,0,2.5");
  return q;
}

double min_z(const std::vector<Vec3>& points) {
  double z = INFINITY;
  for (const Vec3& p : points) z = std::min(z, p.z());
  return z;
}

// Checks everything in `dir` that every recording must satisfy; returns the pvd entries.
std::vector<PvdEntry> check_series(const Particle& particle, const fs::path& dir, const VtkRecorder& rec) {
  const std::vector<PvdEntry> entries = read_pvd(dir / "settling.pvd");
  const std::vector<PvdEntry> marker_entries = read_pvd(dir / "markers.pvd");
  const auto particle_files = files_matching(dir, "particle_", ".vtp");
  const auto marker_files = files_matching(dir, "markers_", ".vtp");
  EXPECT_EQ(entries.size(), particle_files.size());
  EXPECT_EQ(marker_entries.size(), marker_files.size());
  EXPECT_EQ(entries.size(), marker_entries.size());
  EXPECT_EQ(static_cast<int>(entries.size()), rec.frames());
  EXPECT_TRUE(fs::exists(dir / "wall.vtp"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();

  for (std::size_t i = 0; i < entries.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    char name[64];
    std::snprintf(name, sizeof name, "particle_%05zu.vtp", i);
    EXPECT_EQ(entries[i].file, name);
    std::snprintf(name, sizeof name, "markers_%05zu.vtp", i);
    EXPECT_EQ(marker_entries[i].file, name);
    EXPECT_EQ(entries[i].t, marker_entries[i].t);
    EXPECT_EQ(entries[i].t, rec.frame_times().at(i)) << "timesteps are written exactly";
    if (i > 0) {
      EXPECT_GT(entries[i].t, entries[i - 1].t) << "timesteps not increasing";
    }

    const PolyFile p = read_polydata(dir / entries[i].file);
    EXPECT_EQ(p.time, entries[i].t);
    EXPECT_EQ(p.points.size(), particle.mesh.vertices.size());
    EXPECT_EQ(p.polys.size(), particle.mesh.triangles.size());
    EXPECT_TRUE(p.verts.empty());
    for (std::size_t k = 0; k < p.polys.size() && k < particle.mesh.triangles.size(); ++k) {
      EXPECT_EQ(p.polys[k].size(), 3u);
      if (p.polys[k].size() != 3) continue;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(p.polys[k][c], particle.mesh.triangles[k][c]);
    }
    const auto& height = p.point_data.at("height");
    for (std::size_t k = 0; k < p.points.size(); ++k) EXPECT_EQ(height[k], p.points[k].z());

    const PolyFile m = read_polydata(dir / marker_entries[i].file);
    EXPECT_EQ(m.time, entries[i].t);
    EXPECT_TRUE(m.polys.empty());
    EXPECT_EQ(m.verts.size(), m.points.size());
    for (std::size_t k = 0; k < m.verts.size(); ++k)
      EXPECT_EQ(m.verts[k], std::vector<long>{static_cast<long>(k)});
    const auto& kind = m.point_data.at("kind");
    EXPECT_FALSE(kind.empty());
    if (kind.empty()) continue;
    EXPECT_EQ(kind[0], 0);
    for (std::size_t k = 1; k < kind.size(); ++k) {
      EXPECT_EQ(kind[k], 1);
      EXPECT_LE(m.points[k].z(), 0.05 * particle.length * (1 + 1e-8));  // the band, + 9-digit printing
    }
  }
  return entries;
}

// ---- tests ----------------------------------------------------------------------------------------------

// The paper's tetrahedron (Fig 8) tipped vertex-first: a point, line and surface contact, then rest flush.
TEST(VtkRecorder, TetrahedronRunWritesValidParaViewSeries) {
  const Particle& tet = tetrahedron();
  const double L = tet.length;
  ScratchDir dir("tet");
  const double frame_dt = 0.005;
  VtkRecorder rec(tet, dir.str(), frame_dt);
  std::vector<Sample> samples;
  const SettleResult r = settle(tet, cgs_params(), tilted(), [&](const Sample& s) {
    samples.push_back(s);
    rec(s);
  });
  ASSERT_EQ(r.status, Status::rest);
  rec.finish(r);

  const std::vector<PvdEntry> entries = check_series(tet, dir.path(), rec);
  ASSERT_GE(entries.size(), 4u) << "expected an animation, run time " << r.time;
  EXPECT_LE(entries.size(), static_cast<std::size_t>(r.time / frame_dt) + 2);

  // Cadence: first frame at t = 0, then at least frame_dt apart, each at the first sample that qualifies;
  // the final frame at the run's end.
  EXPECT_EQ(entries.front().t, 0.0);
  EXPECT_EQ(entries.back().t, r.time);
  std::size_t next = 1;
  double last = 0;
  for (const Sample& s : samples) {
    if (s.t >= last + frame_dt && next + 1 < entries.size()) {
      EXPECT_EQ(entries[next].t, s.t) << "frame " << next;
      last = s.t;
      ++next;
    }
  }
  EXPECT_EQ(next + 1, entries.size()) << "frames other than those the cadence rule gives";

  // First frame: the run starts with the lowest vertex touching the wall, and the markers show it.
  const PolyFile first = read_polydata(dir.path() / entries.front().file);
  EXPECT_NEAR(min_z(first.points), 0.0, kAtWall * L);
  const PolyFile first_markers = read_polydata(dir.path() / "markers_00000.vtp");
  EXPECT_LT((first_markers.points[0] - samples.front().com).norm(), kPrinted * L);
  EXPECT_GE(first_markers.points.size(), 2u) << "a contact point at t = 0";

  // Last frame: resting flush on a face, the surface is the body mesh at the result's pose, and the centre
  // of mass marker is the result's.
  const PolyFile last_frame = read_polydata(dir.path() / entries.back().file);
  EXPECT_NEAR(min_z(last_frame.points), 0.0, kAtWall * L);
  const Mat3 rot = r.orientation.toRotationMatrix();
  for (std::size_t k = 0; k < last_frame.points.size(); ++k)
    EXPECT_LT((last_frame.points[k] - (rot * tet.mesh.vertices[k] + r.com)).norm(), kPrinted * L) << k;
  const PolyFile last_markers = read_polydata(dir.path() / markers_of(entries.back()));
  ASSERT_FALSE(last_markers.points.empty());
  EXPECT_LT((last_markers.points[0] - r.com).norm(), kPrinted * L);
  EXPECT_EQ(last_markers.points.size(), 1 + 3u) << "resting on a face: three contact vertices";
  for (std::size_t k = 1; k < last_markers.points.size(); ++k)
    EXPECT_NEAR(last_markers.points[k].z(), 0.0, kAtWall * L);

  // The wall: one quad at z = 0 under the particle, at least 4·L across.
  const PolyFile wall = read_polydata(dir.path() / "wall.vtp");
  ASSERT_EQ(wall.points.size(), 4u);
  ASSERT_EQ(wall.polys.size(), 1u);
  EXPECT_EQ(wall.polys[0].size(), 4u);
  for (const Vec3& p : wall.points) EXPECT_EQ(p.z(), 0.0);
  const Aabb box = bounding_box(wall.points);
  EXPECT_GE(box.size().x(), 4 * L * (1 - 1e-8));  // 9-digit printing
  EXPECT_GE(box.size().y(), 4 * L * (1 - 1e-8));
  for (const Vec3& c : {samples.front().com, r.com}) {
    EXPECT_GT(c.x(), box.min.x());
    EXPECT_LT(c.x(), box.max.x());
    EXPECT_GT(c.y(), box.min.y());
    EXPECT_LT(c.y(), box.max.y());
  }
}

// frame_dt = 0 records every sample; the final sample's frame is replaced by the result's pose, not repeated.
TEST(VtkRecorder, ZeroFrameIntervalRecordsEverySample) {
  const Particle& tet = tetrahedron();
  ScratchDir dir("every");
  VtkRecorder rec(tet, dir.str());
  std::vector<double> times;
  SettleParams params = cgs_params();
  params.dt = 1e-4;  // a few hundred samples
  const SettleResult r = settle(tet, params, tilted(), [&](const Sample& s) {
    times.push_back(s.t);
    rec(s);
  });
  rec.finish(r);
  times.erase(std::unique(times.begin(), times.end()), times.end());
  ASSERT_EQ(times.back(), r.time);
  EXPECT_EQ(rec.frame_times(), times);
  const std::vector<PvdEntry> entries = read_pvd(dir.path() / "settling.pvd");
  ASSERT_EQ(entries.size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_EQ(entries[i].t, times[i]);
  EXPECT_EQ(files_matching(dir.path(), "particle_", ".vtp").size(), times.size());
  EXPECT_EQ(files_matching(dir.path(), "markers_", ".vtp").size(), times.size());
}

// max_frames caps the frame count and keeps the last slot for the final state; the step-wise Settler works
// with observer() too.
TEST(VtkRecorder, MaxFramesKeepsTheFinalState) {
  const Particle& tet = tetrahedron();
  ScratchDir dir("cap");
  VtkRecorder rec(tet, dir.str(), 0.0, 5);
  Settler settler(tet, cgs_params(), tilted());
  const SettleResult r = settler.run(rec.observer());
  rec.finish(r);
  const std::vector<PvdEntry> entries = check_series(tet, dir.path(), rec);
  ASSERT_EQ(entries.size(), 5u);
  EXPECT_EQ(entries.front().t, 0.0);
  EXPECT_EQ(entries.back().t, r.time);
  const PolyFile m = read_polydata(dir.path() / "markers_00004.vtp");
  EXPECT_LT((m.points.at(0) - r.com).norm(), kPrinted * tet.length);
}

// finish() without samples (the run observed by nobody) still writes a one-frame series at the rest pose.
TEST(VtkRecorder, FinishAloneWritesTheRestPose) {
  const Particle& tet = tetrahedron();
  ScratchDir dir("alone");
  const SettleResult r = settle(tet, cgs_params(), tilted());
  VtkRecorder rec(tet, dir.str(), 0.01);
  rec.finish(r);
  const std::vector<PvdEntry> entries = check_series(tet, dir.path(), rec);
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].t, r.time);
  EXPECT_NEAR(min_z(read_polydata(dir.path() / entries[0].file).points), 0.0, kAtWall * tet.length);
}

// A larger mesh, the paper's cylinder (Fig 7; a 64-gon prism, 256 triangles), with a tighter contact
// threshold.
TEST(VtkRecorder, CylinderSeriesIsValid) {
  const Particle cyl = load_particle("cylinder:r=0.67,h=0.67", 0.96);
  ScratchDir dir("cyl");
  VtkRecorder rec(cyl, dir.str(), 0.02, 0, 0.02);
  const SettleResult r =
      settle(cyl, cgs_params(), parse_orientation("axis-angle:1,0.2,0,1.2"), rec.observer());
  ASSERT_EQ(r.status, Status::rest);
  rec.finish(r);
  const std::vector<PvdEntry> entries = check_series(cyl, dir.path(), rec);
  ASSERT_GE(entries.size(), 5u);
  const PolyFile last = read_polydata(dir.path() / entries.back().file);
  EXPECT_NEAR(min_z(last.points), 0.0, kAtWall * cyl.length);
  const PolyFile markers = read_polydata(dir.path() / markers_of(entries.back()));
  EXPECT_LT((markers.points.at(0) - r.com).norm(), kPrinted * cyl.length);
  EXPECT_GE(markers.points.size(), 1 + r.contact_points.size());
  for (std::size_t k = 1; k < markers.points.size(); ++k)
    EXPECT_LE(markers.points[k].z(), 0.02 * cyl.length * (1 + 1e-8));  // the band, + 9-digit printing
}

// An independent XML parser (Python's xml.etree) reads every file and agrees on the counts.
TEST(VtkRecorder, PythonXmlParserReadsTheFiles) {
  if (std::system("python3 -c 'import xml.etree.ElementTree' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 not available";
  const Particle& tet = tetrahedron();
  ScratchDir dir("py");
  VtkRecorder rec(tet, dir.str(), 0.01);
  const SettleResult r = settle(tet, cgs_params(), tilted(), rec.observer());
  rec.finish(r);
  const std::string script = R"PY(
import glob, os, sys, xml.etree.ElementTree as ET
d = sys.argv[1]
def polydata(path):
    root = ET.parse(path).getroot()
    assert root.tag == 'VTKFile' and root.get('type') == 'PolyData', path
    piece = root.find('PolyData/Piece')
    n = int(piece.get('NumberOfPoints'))
    assert len(piece.find('Points/DataArray').text.split()) == 3 * n, path
    for kind in ('Verts', 'Polys'):
        el = piece.find(kind)
        count = int(piece.get('NumberOf' + kind))
        if el is None:
            assert count == 0, path
            continue
        arrays = {a.get('Name'): [int(x) for x in a.text.split()] for a in el.findall('DataArray')}
        assert len(arrays['offsets']) == count, path
        assert arrays['offsets'][-1] == len(arrays['connectivity']), path
        assert all(0 <= i < n for i in arrays['connectivity']), path
    for a in piece.findall('PointData/DataArray'):
        assert len(a.text.split()) == n, path
for pvd, prefix in (('settling.pvd', 'particle_'), ('markers.pvd', 'markers_')):
    root = ET.parse(os.path.join(d, pvd)).getroot()
    assert root.tag == 'VTKFile' and root.get('type') == 'Collection'
    sets = root.findall('Collection/DataSet')
    assert len(sets) == len(glob.glob(os.path.join(d, prefix + '*.vtp'))), pvd
    times = [float(s.get('timestep')) for s in sets]
    assert all(a < b for a, b in zip(times, times[1:])), pvd
    for s in sets:
        polydata(os.path.join(d, s.get('file')))
polydata(os.path.join(d, 'wall.vtp'))
)PY";
  const fs::path script_path = dir.path() / "check.py";
  std::ofstream(script_path) << script;
  const std::string cmd = "python3 '" + script_path.string() + "' '" + dir.str() + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

TEST(VtkRecorder, RejectsBadArgumentsAndMisuse) {
  const Particle& tet = tetrahedron();
  ScratchDir dir("bad");
  EXPECT_THROW(VtkRecorder(tet, dir.str(), -1.0), Error);
  EXPECT_THROW(VtkRecorder(tet, dir.str(), std::nan("")), Error);
  EXPECT_THROW(VtkRecorder(tet, dir.str(), 0.0, 1), Error);
  EXPECT_THROW(VtkRecorder(tet, dir.str(), 0.0, -3), Error);
  EXPECT_THROW(VtkRecorder(tet, dir.str(), 0.0, 0, 0.0), Error);
  EXPECT_THROW(VtkRecorder(tet, ""), Error);
  fs::create_directories(dir.path());
  std::ofstream(dir.path() / "file") << "x";
  EXPECT_THROW(VtkRecorder(tet, (dir.path() / "file").string()), Error);

  VtkRecorder rec(tet, (dir.path() / "out").string());
  Settler settler(tet, cgs_params(), tilted());
  rec(settler.sample());
  settler.step();
  rec.finish(settler.result());
  EXPECT_THROW(rec.finish(settler.result()), Error);
  EXPECT_THROW(rec(settler.sample()), Error);
}

}  // namespace
}  // namespace repose
