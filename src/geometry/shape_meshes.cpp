// The built-in shapes' meshes: box, cylinder, geodesic ellipsoid, tetrahedron and the seeded irregular
// grain.
//
// Everything that depends on the seed of an irregular particle uses only IEEE-754 arithmetic and sqrt (both
// correctly rounded everywhere) in a fixed evaluation order, so the same seed gives the same mesh bit for bit
// on every platform (the library is built with -ffp-contract=off).
#include "shape_meshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "repose/geometry/mass.hpp"

namespace repose::detail {
namespace {

// splitmix64 (Steele, Lea & Flood 2014): a tiny generator with a fully specified output sequence.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform random unit vector (rejection sampling in the cube; arithmetic and sqrt only).
  Vec3 unit_vector() {
    while (true) {
      const double x = uniform(-1, 1);
      const double y = uniform(-1, 1);
      const double z = uniform(-1, 1);
      const double r2 = x * x + y * y + z * z;
      if (r2 > 1e-6 && r2 <= 1) {
        const double r = std::sqrt(r2);
        return Vec3(x / r, y / r, z / r);
      }
    }
  }

 private:
  std::uint64_t state_;
};

double norm3(const Vec3& p) { return std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z()); }

// Geodesic icosphere of frequency n on the unit sphere: every icosahedron face is split into n² triangles by
// its barycentric grid, grid points are pushed out to the sphere. Points on shared edges and corners are
// keyed by their integer barycentric weights on the icosahedron's vertices, so neighbouring faces share them
// exactly.
TriangleMesh icosphere(int n) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Vec3, 12> ico = {Vec3(-1, phi, 0), Vec3(1, phi, 0), Vec3(-1, -phi, 0), Vec3(1, -phi, 0),
                                    Vec3(0, -1, phi), Vec3(0, 1, phi), Vec3(0, -1, -phi), Vec3(0, 1, -phi),
                                    Vec3(phi, 0, -1), Vec3(phi, 0, 1), Vec3(-phi, 0, -1), Vec3(-phi, 0, 1)};
  // The 20 faces are the triples of mutually adjacent vertices (edge length 2), oriented outward.
  std::vector<std::array<int, 3>> faces;
  const auto adjacent = [&](int i, int j) {
    return (ico[static_cast<std::size_t>(i)] - ico[static_cast<std::size_t>(j)]).squaredNorm() < 4.5;
  };
  for (int i = 0; i < 12; ++i) {
    for (int j = i + 1; j < 12; ++j) {
      for (int k = j + 1; k < 12; ++k) {
        if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
        const Vec3& a = ico[static_cast<std::size_t>(i)];
        const Vec3& b = ico[static_cast<std::size_t>(j)];
        const Vec3& c = ico[static_cast<std::size_t>(k)];
        if ((b - a).cross(c - a).dot(a + b + c) > 0) {
          faces.push_back({i, j, k});
        } else {
          faces.push_back({i, k, j});
        }
      }
    }
  }

  TriangleMesh mesh;
  std::map<std::array<int, 6>, std::int32_t> index;
  const auto vertex = [&](const std::array<int, 3>& face, int i, int j) {
    std::array<std::pair<int, int>, 3> w = {std::pair{face[0], n - i - j}, std::pair{face[1], i},
                                            std::pair{face[2], j}};
    // Canonical order: non-zero weights first, by icosahedron vertex; zero weights (id -1) last.
    for (auto& [id, weight] : w) {
      if (weight == 0) id = -1;
    }
    std::sort(w.begin(), w.end(), [](const auto& x, const auto& y) {
      return (x.first < 0) != (y.first < 0) ? y.first < 0 : x.first < y.first;
    });
    std::array<int, 6> key{};
    Vec3 p = Vec3::Zero();
    for (std::size_t m = 0; m < 3; ++m) {
      key[2 * m] = w[m].first;
      key[2 * m + 1] = w[m].second;
      if (w[m].first < 0) continue;
      const Vec3& q = ico[static_cast<std::size_t>(w[m].first)];
      const double s = static_cast<double>(w[m].second);
      p = Vec3(p.x() + s * q.x(), p.y() + s * q.y(), p.z() + s * q.z());
    }
    const auto [it, inserted] = index.try_emplace(key, static_cast<std::int32_t>(mesh.vertices.size()));
    if (inserted) {
      const double r = norm3(p);
      mesh.vertices.emplace_back(p.x() / r, p.y() / r, p.z() / r);
    }
    return it->second;
  };
  mesh.triangles.reserve(static_cast<std::size_t>(20 * n * n));
  for (const auto& face : faces) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        mesh.triangles.push_back({vertex(face, i, j), vertex(face, i + 1, j), vertex(face, i, j + 1)});
        if (i + j < n - 1) {
          mesh.triangles.push_back(
              {vertex(face, i + 1, j), vertex(face, i + 1, j + 1), vertex(face, i, j + 1)});
        }
      }
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh make_box(double x, double y, double z) {
  TriangleMesh mesh;
  // Vertex i + 2j + 4k is at (±x/2, ±y/2, ±z/2) with the sign of each coordinate given by bit i, j, k.
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) {
        mesh.vertices.emplace_back((i - 0.5) * x, (j - 0.5) * y, (k - 0.5) * z);
      }
    }
  }
  mesh.triangles = {{0, 4, 6}, {0, 6, 2},   // -x
                    {1, 3, 7}, {1, 7, 5},   // +x
                    {0, 1, 5}, {0, 5, 4},   // -y
                    {2, 6, 7}, {2, 7, 3},   // +y
                    {0, 2, 3}, {0, 3, 1},   // -z
                    {4, 5, 7}, {4, 7, 6}};  // +z
  return mesh;
}

TriangleMesh make_cylinder(double r, double h, int n) {
  TriangleMesh mesh;
  // Bottom rim 0..n-1, top rim n..2n-1, bottom centre 2n, top centre 2n+1.
  mesh.vertices.resize(static_cast<std::size_t>(2 * n + 2));
  for (int i = 0; i < n; ++i) {
    const double theta = 2.0 * std::numbers::pi * i / n;
    const double x = i == 0 ? r : r * std::cos(theta);
    const double y = i == 0 ? 0.0 : r * std::sin(theta);
    mesh.vertices[static_cast<std::size_t>(i)] = Vec3(x, y, -0.5 * h);
    mesh.vertices[static_cast<std::size_t>(n + i)] = Vec3(x, y, 0.5 * h);
  }
  mesh.vertices[static_cast<std::size_t>(2 * n)] = Vec3(0, 0, -0.5 * h);
  mesh.vertices[static_cast<std::size_t>(2 * n + 1)] = Vec3(0, 0, 0.5 * h);
  mesh.triangles.reserve(static_cast<std::size_t>(4 * n));
  for (int i = 0; i < n; ++i) {
    const int next = (i + 1) % n;
    mesh.triangles.push_back({i, next, n + next});
    mesh.triangles.push_back({i, n + next, n + i});
    mesh.triangles.push_back({2 * n, next, i});
    mesh.triangles.push_back({2 * n + 1, n + i, n + next});
  }
  return mesh;
}

TriangleMesh make_ellipsoid(double a, double b, double c, int n) {
  TriangleMesh mesh = icosphere(n);
  for (Vec3& p : mesh.vertices) p = Vec3(a * p.x(), b * p.y(), c * p.z());
  return mesh;
}

TriangleMesh make_tetrahedron(double edge) {
  const double height = edge * std::sqrt(2.0 / 3.0);
  const double bottom = -height / 4.0;
  const double apex = 3.0 * height / 4.0;
  const double circumradius = edge / std::sqrt(3.0);  // of the bottom face
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0, circumradius, bottom),               // azimuth 90°
                   Vec3(-edge / 2, -circumradius / 2, bottom),  // 210°
                   Vec3(edge / 2, -circumradius / 2, bottom),   // 330°
                   Vec3(0, 0, apex)};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return mesh;
}

TriangleMesh make_irregular(std::uint64_t seed, double size, int n) {
  SplitMix64 rng(seed);

  // Global shape parameters first, then one radius per vertex, so the draw order is fixed.
  // Low-frequency bumps and dents: compactly supported kernels k = max(0, 1 - (1 - d·c)/w)² around random
  // centres c, with amplitude in [-1, 1] and angular width w (on 1 - cos(angle)) in [0.3, 0.8].
  struct Bump {
    Vec3 centre;
    double amplitude;
    double width;
  };
  std::vector<Bump> bumps(4 + static_cast<std::size_t>(rng.next() % 4));
  for (Bump& bump : bumps) {
    bump.centre = rng.unit_vector();
    bump.amplitude = rng.uniform(-1, 1);
    bump.width = rng.uniform(0.3, 0.8);
  }
  // Elongation: stretch factors (1, U[0.5, 0.9], U[0.3, 0.7]) along the axes of a random rotation (a unit
  // quaternion by rejection sampling in the 4-ball).
  const double stretch_y = rng.uniform(0.5, 0.9);
  const double stretch_z = rng.uniform(0.3, 0.7);
  double qw = 0, qx = 0, qy = 0, qz = 0;
  while (true) {
    qw = rng.uniform(-1, 1);
    qx = rng.uniform(-1, 1);
    qy = rng.uniform(-1, 1);
    qz = rng.uniform(-1, 1);
    const double r2 = qw * qw + qx * qx + qy * qy + qz * qz;
    if (r2 > 1e-6 && r2 <= 1) {
      const double r = std::sqrt(r2);
      qw /= r, qx /= r, qy /= r, qz /= r;
      break;
    }
  }
  const double rot[3][3] = {{1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)},
                            {2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)},
                            {2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)}};
  const double scale[3] = {1.0, stretch_y, stretch_z};
  // M = R · diag(scale) · Rᵀ, written out so the evaluation order is fixed.
  double m[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m[i][j] = rot[i][0] * scale[0] * rot[j][0] + rot[i][1] * scale[1] * rot[j][1] +
                rot[i][2] * scale[2] * rot[j][2];
    }
  }

  // Star-shaped surface: each icosphere vertex direction d gets radius in [0.55, 1] mixing per-vertex noise
  // (jagged) with the smooth bump field (skewed). Any positive radial function over a spherical triangulation
  // gives a closed, outward, non-self-intersecting surface, and the positive-definite stretch keeps it so.
  TriangleMesh mesh = icosphere(n);
  for (Vec3& d : mesh.vertices) {
    double smooth = 0;
    for (const Bump& bump : bumps) {
      const double cosine = d.x() * bump.centre.x() + d.y() * bump.centre.y() + d.z() * bump.centre.z();
      const double t = 1.0 - (1.0 - cosine) / bump.width;
      if (t > 0) smooth += bump.amplitude * t * t;
    }
    smooth = std::clamp(smooth, -1.0, 1.0);
    const double mix = 0.6 * rng.uniform() + 0.4 * (0.5 + 0.5 * smooth);
    const double radius = 0.55 + 0.45 * mix;
    const Vec3 p(radius * d.x(), radius * d.y(), radius * d.z());
    d = Vec3(m[0][0] * p.x() + m[0][1] * p.y() + m[0][2] * p.z(),
             m[1][0] * p.x() + m[1][1] * p.y() + m[1][2] * p.z(),
             m[2][0] * p.x() + m[2][1] * p.y() + m[2][2] * p.z());
  }

  // Centre on the centre of mass, then scale about it so the largest bounding-box extent is `size`.
  const Vec3 com = compute_mass_properties(mesh, 1.0).center_of_mass;
  for (Vec3& p : mesh.vertices) p = Vec3(p.x() - com.x(), p.y() - com.y(), p.z() - com.z());
  const Vec3 extent = bounding_box(mesh.vertices).size();
  const double factor = size / std::max({extent.x(), extent.y(), extent.z()});
  for (Vec3& p : mesh.vertices) p = Vec3(factor * p.x(), factor * p.y(), factor * p.z());
  return mesh;
}

}  // namespace repose::detail
