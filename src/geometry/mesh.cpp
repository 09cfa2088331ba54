#include "repose/geometry/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "repose/error.hpp"

namespace repose {
namespace {

// Relative tolerances, as documented in mesh.hpp (D = bounding-box diagonal).
constexpr double kWeldTolerance = 1e-10;
constexpr double kAreaTolerance = 1e-14;
constexpr double kVolumeTolerance = 1e-12;
// Bounding-box diagonals D accepted: far beyond any particle in any unit system.
constexpr double kMinDiagonal = 1e-50;
constexpr double kMaxDiagonal = 1e50;

std::string count_of(std::int64_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// Bounds of the vertices that triangles use: a stray unused vertex must not inflate the tolerances.
Aabb used_bounds(const std::vector<Vec3>& vertices, const std::vector<bool>& used) {
  Aabb box;
  box.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  box.max = -box.min;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    if (!used[v]) continue;
    box.min = box.min.cwiseMin(vertices[v]);
    box.max = box.max.cwiseMax(vertices[v]);
  }
  return box;
}

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// Maps every used vertex to the earliest used vertex within `tol` of it (itself if none); unused vertices map
// to themselves and may lie far outside the grid. Hashing into cells of size 4·tol makes this expected O(n):
// representatives are at least `tol` apart, so a cell holds only a few, and a vertex needs to look at one
// neighbouring cell per axis only when it lies within `tol` of that side.
std::vector<std::int32_t> weld_map(const std::vector<Vec3>& vertices, const std::vector<bool>& used,
                                   const Vec3& origin, double tol) {
  const auto n = static_cast<std::int32_t>(vertices.size());
  const double cell_size = 4.0 * tol;
  const double reach = 1.01 * tol;  // a little wider than `tol` so rounding cannot skip a cell
  std::vector<std::int32_t> rep(n);
  std::vector<std::int32_t> next_in_cell(n, -1);  // chains the representatives that share a cell
  std::unordered_map<Cell, std::int32_t, CellHash> head;
  head.reserve(vertices.size());
  const double tol2 = tol * tol;
  auto cell_of = [&](double u) { return static_cast<std::int64_t>(std::floor(u / cell_size)); };
  for (std::int32_t i = 0; i < n; ++i) {
    rep[i] = i;
    if (!used[i]) continue;
    const Vec3 p = vertices[i];
    const Vec3 u = p - origin;
    std::int32_t found = -1;
    for (std::int64_t x = cell_of(u.x() - reach); x <= cell_of(u.x() + reach); ++x) {
      for (std::int64_t y = cell_of(u.y() - reach); y <= cell_of(u.y() + reach); ++y) {
        for (std::int64_t z = cell_of(u.z() - reach); z <= cell_of(u.z() + reach); ++z) {
          const auto it = head.find(Cell{x, y, z});
          for (std::int32_t j = it == head.end() ? -1 : it->second; j >= 0; j = next_in_cell[j]) {
            if ((vertices[j] - p).squaredNorm() <= tol2 && (found < 0 || j < found)) found = j;
          }
        }
      }
    }
    if (found >= 0) {
      rep[i] = found;
      continue;
    }
    auto [it, inserted] = head.try_emplace(Cell{cell_of(u.x()), cell_of(u.y()), cell_of(u.z())}, i);
    if (!inserted) {
      next_in_cell[i] = it->second;
      it->second = i;
    }
  }
  return rep;
}

double triangle_area(const TriangleMesh& mesh, const Triangle& t) {
  const Vec3& a = mesh.vertices[t[0]];
  return 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
}

double signed_volume_about(const TriangleMesh& mesh, const Vec3& ref) {
  double six_v = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - ref;
    const Vec3 b = mesh.vertices[t[1]] - ref;
    const Vec3 c = mesh.vertices[t[2]] - ref;
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

// Checks that the surface is closed, edge-manifold and consistently wound; throws otherwise. Edges are
// bucketed by their lower vertex (a counting sort), so each bucket holds only that vertex's few edges.
void check_closed_and_oriented(const TriangleMesh& mesh, const std::string& name) {
  const std::size_t n_vertices = mesh.vertices.size();
  std::vector<std::size_t> start(n_vertices + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < n_vertices; ++v) start[v + 1] += start[v];
  // Each entry is the upper vertex, shifted left, with the low bit set if the triangle runs lower -> upper.
  std::vector<std::uint32_t> upper(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      const auto forward = static_cast<std::uint32_t>(a < b);
      upper[fill[std::min(a, b)]++] = static_cast<std::uint32_t>(std::max(a, b)) << 1 | forward;
    }
  }
  std::int64_t boundary = 0, non_manifold = 0, misoriented = 0;
  for (std::size_t v = 0; v < n_vertices; ++v) {
    const auto first = upper.begin() + static_cast<std::ptrdiff_t>(start[v]);
    const auto last = upper.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
    std::sort(first, last);
    for (auto i = first; i != last;) {
      auto j = i + 1;
      while (j != last && (*j >> 1) == (*i >> 1)) ++j;
      const auto uses = j - i;
      if (uses == 1) {
        ++boundary;
      } else if (uses > 2) {
        ++non_manifold;
      } else if ((*i & 1u) == (*(i + 1) & 1u)) {
        ++misoriented;
      }
      i = j;
    }
  }
  // Non-manifold first: three triangles on one edge usually leave boundary edges around them too.
  if (non_manifold > 0) {
    throw SurfaceError(name + ": non-manifold surface: " + std::to_string(non_manifold) +
                       " edges shared by more than two triangles");
  }
  if (boundary > 0) {
    throw SurfaceError(name + ": open surface: " + std::to_string(boundary) +
                       " boundary edges (the mesh must be a closed solid)");
  }
  if (misoriented > 0) {
    throw SurfaceError(name + ": inconsistent winding: " + std::to_string(misoriented) +
                       " edges whose two triangles face opposite ways");
  }
}

// The common first stage of clean_mesh() and validate_mesh(): `mesh` → `out` welded, without degenerate
// triangles or unused vertices; `diag` is the used vertices' bounding-box diagonal, `center` its centre.
MeshReport clean_into(const TriangleMesh& mesh, const std::string& name, TriangleMesh& out, double& diag,
                      Vec3& center) {
  MeshReport report;
  report.input_vertices = static_cast<int>(mesh.vertices.size());
  report.input_triangles = static_cast<int>(mesh.triangles.size());
  const Aabb box = check_surface_input(mesh, name);
  const auto n_vertices = static_cast<std::int32_t>(mesh.vertices.size());
  std::vector<bool> used(n_vertices, false);
  for (const Triangle& t : mesh.triangles) {
    for (const std::int32_t i : t) used[i] = true;
  }
  diag = box.size().norm();
  center = box.center();

  // Weld, then drop triangles that collapsed or have (numerically) no area.
  const std::vector<std::int32_t> rep = weld_map(mesh.vertices, used, box.min, kWeldTolerance * diag);
  for (std::int32_t v = 0; v < n_vertices; ++v) report.welded_vertices += rep[v] != v;
  const double min_area = kAreaTolerance * diag * diag;
  std::vector<Triangle> kept;
  kept.reserve(mesh.triangles.size());
  for (Triangle t : mesh.triangles) {
    for (std::int32_t& i : t) i = rep[i];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || triangle_area(mesh, t) < min_area) {
      ++report.degenerate_triangles;
    } else {
      kept.push_back(t);
    }
  }
  if (kept.empty()) {
    throw Error(name + ": all " + std::to_string(report.input_triangles) +
                " triangles are degenerate (zero area)");
  }

  // Keep only referenced vertices, in their original order.
  std::vector<std::int32_t> new_index(n_vertices, -1);
  for (const Triangle& t : kept) {
    for (const std::int32_t i : t) new_index[i] = 0;
  }
  std::vector<Vec3> vertices;
  for (std::int32_t v = 0; v < n_vertices; ++v) {
    if (new_index[v] < 0) continue;
    new_index[v] = static_cast<std::int32_t>(vertices.size());
    vertices.push_back(mesh.vertices[v]);
  }
  report.unused_vertices = n_vertices - report.welded_vertices - static_cast<int>(vertices.size());
  for (Triangle& t : kept) {
    for (std::int32_t& i : t) i = new_index[i];
  }
  out = TriangleMesh{std::move(vertices), std::move(kept)};
  if (report.welded_vertices > 0) {
    report.warnings.push_back("welded " +
                              count_of(report.welded_vertices, "duplicate vertex", "duplicate vertices"));
  }
  if (report.degenerate_triangles > 0) {
    report.warnings.push_back(
        "removed " + count_of(report.degenerate_triangles, "degenerate triangle", "degenerate triangles") +
        " (zero area)");
  }
  if (report.unused_vertices > 0) {
    report.warnings.push_back("removed " +
                              count_of(report.unused_vertices, "unused vertex", "unused vertices"));
  }
  return report;
}

}  // namespace

Aabb check_surface_input(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty() || mesh.vertices.empty()) throw Error(name + ": empty mesh (no triangles)");
  if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw Error(name + ": too many vertices (" + std::to_string(mesh.vertices.size()) + ")");
  }
  const auto n_vertices = static_cast<std::int32_t>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::int32_t i : mesh.triangles[t]) {
      if (i < 0 || i >= n_vertices) {
        throw Error(name + ": in triangle " + std::to_string(t) + ", vertex index " + std::to_string(i) +
                    " does not exist (" + std::to_string(n_vertices) + " vertices)");
      }
    }
  }
  for (std::int32_t v = 0; v < n_vertices; ++v) {
    if (!mesh.vertices[v].allFinite()) {
      throw Error(name + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
  std::vector<bool> used(n_vertices, false);
  for (const Triangle& t : mesh.triangles) {
    for (const std::int32_t i : t) used[i] = true;
  }
  const Aabb box = used_bounds(mesh.vertices, used);
  const double diag = box.size().norm();
  // Also guards the weld grid, whose cell size is proportional to the diagonal.
  if (!(diag > 0.0)) throw Error(name + ": zero volume (all vertices coincide)");
  // Outside this range the tolerances underflow or the volume and inertia (∝ D⁵) overflow; found by
  // fuzz_shape_spec ("box:x=1e300,y=1e300,z=1e300" made the weld grid's cell index undefined).
  if (!(diag >= kMinDiagonal && diag <= kMaxDiagonal)) {
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.3g", diag);
    throw Error(name + ": size out of range (bounding-box diagonal " + shown + "; must be in [1e-50, 1e50])");
  }
  return box;
}

MeshReport clean_mesh(TriangleMesh& mesh, const std::string& name) {
  TriangleMesh out;
  double diag = 0;
  Vec3 center;
  MeshReport report = clean_into(mesh, name, out, diag, center);
  mesh = std::move(out);
  return report;
}

MeshReport validate_mesh(TriangleMesh& mesh, const std::string& name) {
  // `mesh` is only replaced once every check has passed.
  TriangleMesh repaired;
  double diag = 0;
  Vec3 center;
  MeshReport report = clean_into(mesh, name, repaired, diag, center);

  check_closed_and_oriented(repaired, name);

  const double volume = signed_volume_about(repaired, center);
  if (std::abs(volume) <= kVolumeTolerance * diag * diag * diag) throw Error(name + ": zero volume");

  if (volume < 0.0) {
    for (Triangle& t : repaired.triangles) std::swap(t[1], t[2]);
    report.flipped = true;
    report.warnings.push_back("inverted winding (negative volume): all triangles flipped");
  }
  mesh = std::move(repaired);
  return report;
}

double signed_volume(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  // About the box centre rather than the origin: a small particle far from the origin keeps its precision.
  return signed_volume_about(mesh, bounding_box(mesh.vertices).center());
}

}  // namespace repose
