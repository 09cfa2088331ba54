// Shared by the repair_mesh tests: the broken meshes they make from closed shapes, and what they compare.
// Tolerances are explained in repair_test.cpp.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "repose/error.hpp"
#include "repose/geometry/hull.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/repair.hpp"
#include "repose/geometry/shapes.hpp"

namespace repose::repair_test {

constexpr double kRel = 1e-12;

inline double volume_of(const TriangleMesh& m) { return compute_mass_properties(m, 1.0).volume; }

// A box [0,X]×[0,Y]×[0,Z] with each face an n×n grid of squares, two triangles each, wound outward. Lattice
// coordinates times size/n are exact binary fractions for n = 4, so flat patches are exactly flat.
inline TriangleMesh grid_box(int n, const Vec3& size) {
  TriangleMesh m;
  std::map<std::array<int, 3>, int> id;
  auto vertex = [&](const std::array<int, 3>& c) {
    const auto [it, inserted] = id.try_emplace(c, static_cast<int>(m.vertices.size()));
    if (inserted) m.vertices.emplace_back(c[0] * size.x() / n, c[1] * size.y() / n, c[2] * size.z() / n);
    return it->second;
  };
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;  // e_u × e_v = e_a
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> c{};
            c[a] = side * n;
            c[u] = i + di;
            c[v] = j + dj;
            return vertex(c);
          };
          const int c00 = corner(0, 0), c10 = corner(1, 0), c11 = corner(1, 1), c01 = corner(0, 1);
          if (side == 1) {
            m.triangles.push_back({c00, c10, c11});
            m.triangles.push_back({c00, c11, c01});
          } else {
            m.triangles.push_back({c00, c11, c10});
            m.triangles.push_back({c00, c01, c11});
          }
        }
      }
    }
  }
  return m;
}

// Index of the first of the two triangles of square (i, j) on face (axis a, side) of grid_box(n, ...).
inline int square(int n, int a, int side, int i, int j) { return (((a * 2 + side) * n + i) * n + j) * 2; }

inline TriangleMesh without(const TriangleMesh& m, const std::set<int>& removed) {
  TriangleMesh out = m;
  out.triangles.clear();
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
    if (!removed.contains(t)) out.triangles.push_back(m.triangles[t]);
  }
  return out;
}

inline TriangleMesh translated(TriangleMesh m, const Vec3& offset) {
  for (Vec3& v : m.vertices) v += offset;
  return m;
}

// Both meshes' triangles in one (vertex records appended, indices shifted).
inline TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const auto base = static_cast<std::int32_t>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Triangle t : b.triangles) {
    for (std::int32_t& i : t) i += base;
    m.triangles.push_back(t);
  }
  return m;
}

// Every triangle with its own three vertex records, as STL stores them.
inline TriangleMesh soup(const TriangleMesh& m) {
  TriangleMesh out;
  for (const Triangle& t : m.triangles) {
    const auto base = static_cast<std::int32_t>(out.vertices.size());
    for (const std::int32_t i : t) out.vertices.push_back(m.vertices[i]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

inline bool less_xyz(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The triangles as oriented corner positions (rotated so the smallest corner comes first, winding kept),
// sorted: two meshes with equal lists have the same triangles with the same windings, whatever the indices.
inline std::vector<std::array<double, 9>> oriented_triangles(const TriangleMesh& m) {
  std::vector<std::array<double, 9>> out;
  for (const Triangle& t : m.triangles) {
    int first = 0;
    for (int k = 1; k < 3; ++k) {
      if (less_xyz(m.vertices[t[k]], m.vertices[t[first]])) first = k;
    }
    std::array<double, 9> key;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.vertices[t[(first + k) % 3]];
      for (int c = 0; c < 3; ++c) key[3 * k + c] = p[c];
    }
    out.push_back(key);
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline std::vector<std::array<double, 3>> sorted_points(const std::vector<Vec3>& points) {
  std::vector<std::array<double, 3>> out;
  for (const Vec3& p : points) out.push_back({p.x(), p.y(), p.z()});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

inline std::string error_of(TriangleMesh m, const std::string& name = "scan.stl", bool largest = false) {
  try {
    repair_mesh(m, name, largest);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline std::string validation_error(TriangleMesh m) {
  try {
    validate_mesh(m, "scan.stl");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace repose::repair_test
