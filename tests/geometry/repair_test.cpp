// Tests of repair_mesh (CGAL Polygon Mesh Processing stages).
//
// Every broken mesh is made here from a closed shape whose volume and triangles are known, so each repair is
// checked against the shape it came from. Tolerances:
// - kRel = 1e-12 (relative): where the repaired solid is exactly the original one (the same triangles, or a
//   flat patch in the plane of the triangles it replaces), volumes differ only by the round-off of summing
//   O(100..1000) cone volumes of size O(L³), a few 1e-16 relative; 1e-12 is a margin, and a real error (a
//   missing or reversed triangle) changes the volume by at least the smallest triangle's cone, > 1e-4 here.
// - On the curved ellipsoid a flat patch misses a cap; its bound is derived in PunchedEllipsoid below.
#include "repose/geometry/repair.hpp"

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
#include "repose/geometry/shapes.hpp"

namespace repose {
namespace {

using ::testing::HasSubstr;

constexpr double kRel = 1e-12;

double volume_of(const TriangleMesh& m) { return compute_mass_properties(m, 1.0).volume; }

// A box [0,X]×[0,Y]×[0,Z] with each face an n×n grid of squares, two triangles each, wound outward. Lattice
// coordinates times size/n are exact binary fractions for n = 4, so flat patches are exactly flat.
TriangleMesh grid_box(int n, const Vec3& size) {
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
int square(int n, int a, int side, int i, int j) { return (((a * 2 + side) * n + i) * n + j) * 2; }

TriangleMesh without(const TriangleMesh& m, const std::set<int>& removed) {
  TriangleMesh out = m;
  out.triangles.clear();
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
    if (!removed.contains(t)) out.triangles.push_back(m.triangles[t]);
  }
  return out;
}

TriangleMesh translated(TriangleMesh m, const Vec3& offset) {
  for (Vec3& v : m.vertices) v += offset;
  return m;
}

// Both meshes' triangles in one (vertex records appended, indices shifted).
TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
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
TriangleMesh soup(const TriangleMesh& m) {
  TriangleMesh out;
  for (const Triangle& t : m.triangles) {
    const auto base = static_cast<std::int32_t>(out.vertices.size());
    for (const std::int32_t i : t) out.vertices.push_back(m.vertices[i]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

bool less_xyz(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The triangles as oriented corner positions (rotated so the smallest corner comes first, winding kept),
// sorted: two meshes with equal lists have the same triangles with the same windings, whatever the indices.
std::vector<std::array<double, 9>> oriented_triangles(const TriangleMesh& m) {
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

std::vector<std::array<double, 3>> sorted_points(const std::vector<Vec3>& points) {
  std::vector<std::array<double, 3>> out;
  for (const Vec3& p : points) out.push_back({p.x(), p.y(), p.z()});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string error_of(TriangleMesh m, const std::string& name = "scan.stl", bool largest = false) {
  try {
    repair_mesh(m, name, largest);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string validation_error(TriangleMesh m) {
  try {
    validate_mesh(m, "scan.stl");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RepairMesh, ClosedMeshIsUnchanged) {
  TriangleMesh m = make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=6");
  const TriangleMesh original = m;
  const RepairReport r = repair_mesh(m, "e", false);
  EXPECT_EQ(oriented_triangles(m), oriented_triangles(original));
  EXPECT_EQ(r.input_components, 1);
  EXPECT_EQ(r.kept_components, 1);
  EXPECT_EQ(r.merged_vertices + r.degenerate_faces + r.duplicate_faces + r.non_manifold_vertices +
                r.stitched_edges + r.holes_filled + r.flat_components + r.flipped_faces,
            0);
  EXPECT_EQ(r.area_added, 0.0);
  EXPECT_EQ(r.volume_change, 0.0);
  EXPECT_TRUE(r.notes.empty());
}

// Holes punched in the flat faces of a box (whole grid squares removed, every vertex still used by a
// neighbouring square) are refilled in their own planes, so the solid is exactly the original.
TEST(RepairMesh, HolesInFlatFacesAreFilledExactly) {
  constexpr int n = 4;
  const Vec3 size(1, 2, 3);
  const TriangleMesh box = grid_box(n, size);
  ASSERT_EQ(validation_error(box), "");
  const double volume = size.prod();
  // k = 1: one square; k = 3: a square, a 1×2 strip (a hexagon with three collinear corners on each long
  // side, which a patch must not use as a triangle) and a square on a third face. Vertex-disjoint holes.
  const std::vector<std::vector<std::array<int, 4>>> cases = {
      {{0, 1, 1, 1}},
      {{0, 1, 1, 1}, {1, 0, 1, 1}, {1, 0, 1, 2}, {2, 1, 2, 2}},
  };
  for (const auto& squares : cases) {
    std::set<int> removed;
    for (const auto& s : squares) {
      const int t = square(n, s[0], s[1], s[2], s[3]);
      removed.insert({t, t + 1});
    }
    const int holes = squares.size() == 1 ? 1 : 3;
    SCOPED_TRACE(holes);
    TriangleMesh m = without(box, removed);
    EXPECT_THAT(validation_error(m), HasSubstr("open surface"));
    const RepairReport r = repair_mesh(m, "box", false);
    EXPECT_EQ(r.holes_filled, holes);
    EXPECT_EQ(r.flipped_faces, 0);
    EXPECT_EQ(validation_error(m), "");
    EXPECT_NEAR(volume_of(m), volume, kRel * volume);
    // No vertex added or lost, so the convex hull is the original's.
    EXPECT_EQ(sorted_points(m.vertices), sorted_points(box.vertices));
    EXPECT_EQ(sorted_points(compute_convex_hull(m.vertices).vertices),
              sorted_points(compute_convex_hull(box.vertices).vertices));
    // The patches cover the removed squares: area_added is their area over the rest.
    double removed_area = 0, total_area = 0, removed_cones = 0;
    const Vec3 centroid = 0.5 * size;
    for (int t = 0; t < static_cast<int>(box.triangles.size()); ++t) {
      const Vec3& a = box.vertices[box.triangles[t][0]];
      const Vec3& b = box.vertices[box.triangles[t][1]];
      const Vec3& c = box.vertices[box.triangles[t][2]];
      const double area = 0.5 * (b - a).cross(c - a).norm();
      total_area += area;
      if (removed.contains(t)) {
        removed_area += area;
        removed_cones += (a - centroid).dot((b - centroid).cross(c - centroid)) / 6;
      }
    }
    EXPECT_NEAR(r.area_added, removed_area / (total_area - removed_area), kRel);
    // A flat patch's cone from the centroid equals the cone of the triangles it replaces.
    EXPECT_NEAR(r.volume_change, removed_cones / volume, kRel);
    EXPECT_THAT(r.notes, ::testing::Contains(HasSubstr("filled " + std::to_string(holes) + " hole")));
  }
}

// Holes on a curved surface: a flat patch over a hole whose border is not planar misses a cap. Each hole here
// is one triangle (its only triangulation is itself: no change) or two triangles sharing an edge (a quad
// a-b-c-d; the patch either reuses the removed diagonal, no change, or takes the other one, which changes the
// volume by exactly the tetrahedron abcd). So |ΔV| ≤ Σ over the quads of |vol(abcd)|, plus round-off.
TEST(RepairMesh, PunchedEllipsoidLosesAtMostTheCaps) {
  const TriangleMesh e = make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=10");
  const double volume = volume_of(e);
  auto centroid = [&](int t) {
    return (e.vertices[e.triangles[t][0]] + e.vertices[e.triangles[t][1]] + e.vertices[e.triangles[t][2]]) /
           3;
  };
  // The triangle furthest along each of three directions: far apart, so the holes share no vertex.
  auto furthest = [&](const Vec3& d) {
    int best = 0;
    for (int t = 1; t < static_cast<int>(e.triangles.size()); ++t) {
      if (centroid(t).dot(d) > centroid(best).dot(d)) best = t;
    }
    return best;
  };
  auto neighbour = [&](int t) {
    for (int s = 0; s < static_cast<int>(e.triangles.size()); ++s) {
      int shared = 0;
      for (const std::int32_t i : e.triangles[s])
        shared += std::count(e.triangles[t].begin(), e.triangles[t].end(), i);
      if (s != t && shared == 2) return s;
    }
    return -1;
  };
  const int single = furthest(Vec3(0, 0, 1));
  const int quad1 = furthest(Vec3(1, 0, 0)), quad2 = furthest(Vec3(0, -1, 0));
  const std::set<int> removed = {single, quad1, neighbour(quad1), quad2, neighbour(quad2)};
  ASSERT_EQ(removed.size(), 5u);
  double bound = 0;
  for (const int t : {quad1, quad2}) {
    std::set<std::int32_t> corners(e.triangles[t].begin(), e.triangles[t].end());
    corners.insert(e.triangles[neighbour(t)].begin(), e.triangles[neighbour(t)].end());
    ASSERT_EQ(corners.size(), 4u);
    std::vector<Vec3> p;
    for (const std::int32_t i : corners) p.push_back(e.vertices[i]);
    bound += std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6;
  }
  // Measured: bound = 7.9e-6·V (each tetrahedron is about the quad's area times its bulge out of plane, over
  // 3); the actual change was 2e-16·V: CGAL's patches reused the removed diagonals.
  EXPECT_LT(bound, 1e-4 * volume);

  TriangleMesh m = without(e, removed);
  EXPECT_THAT(validation_error(m), HasSubstr("open surface"));
  const RepairReport r = repair_mesh(m, "ellipsoid", false);
  EXPECT_EQ(r.holes_filled, 3);
  EXPECT_EQ(validation_error(m), "");
  EXPECT_LE(std::abs(volume_of(m) - volume), bound + kRel * volume);
  EXPECT_EQ(sorted_points(m.vertices), sorted_points(e.vertices));
  EXPECT_EQ(sorted_points(compute_convex_hull(m.vertices).vertices),
            sorted_points(compute_convex_hull(e.vertices).vertices));
}

// A patch of reversed triangles is turned back. CGAL's soup orientation starts from one triangle and may turn
// the other side instead; the final outward orientation undoes that, so in both cases the result is the
// original and flipped_faces counts exactly the triangles that were reversed in the input.
TEST(RepairMesh, FlippedPatchIsReoriented) {
  const TriangleMesh e = make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=4");
  const double volume = volume_of(e);
  for (const bool complement : {false, true}) {
    SCOPED_TRACE(complement);
    TriangleMesh m = e;
    int flipped = 0;
    for (Triangle& t : m.triangles) {
      const double z = (e.vertices[t[0]] + e.vertices[t[1]] + e.vertices[t[2]]).z() / 3;
      if ((z > 0.3) != complement) {
        std::swap(t[1], t[2]);
        ++flipped;
      }
    }
    ASSERT_GT(flipped, 0);
    ASSERT_LT(flipped, static_cast<int>(e.triangles.size()));
    EXPECT_THAT(validation_error(m), HasSubstr("inconsistent winding"));
    const RepairReport r = repair_mesh(m, "e", false);
    EXPECT_EQ(r.flipped_faces, flipped);
    EXPECT_EQ(r.holes_filled, 0);
    EXPECT_EQ(oriented_triangles(m), oriented_triangles(e));
    EXPECT_NEAR(volume_of(m), volume, kRel * volume);
  }
}

TEST(RepairMesh, InvertedSurfaceIsTurnedOutward) {
  const TriangleMesh e = make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=4");
  TriangleMesh m = e;
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  const RepairReport r = repair_mesh(m, "e", false);
  EXPECT_EQ(r.flipped_faces, static_cast<int>(e.triangles.size()));
  EXPECT_EQ(oriented_triangles(m), oriented_triangles(e));
}

TEST(RepairMesh, UnweldedCornersAreWelded) {
  const TriangleMesh e = make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=6");
  TriangleMesh m = soup(e);
  const RepairReport r = repair_mesh(m, "e", false);
  EXPECT_EQ(r.merged_vertices, static_cast<int>(3 * e.triangles.size() - e.vertices.size()));
  EXPECT_EQ(m.vertices.size(), e.vertices.size());
  EXPECT_EQ(oriented_triangles(m), oriented_triangles(e));
  EXPECT_NEAR(volume_of(m), volume_of(e), kRel * volume_of(e));
  TriangleMesh validated = m;
  EXPECT_EQ(validate_mesh(validated, "e").welded_vertices, 0);
}

TEST(RepairMesh, DuplicateAndDegenerateTrianglesAreRemoved) {
  const TriangleMesh box = grid_box(2, Vec3(1, 2, 3));
  TriangleMesh m = box;
  const Triangle t0 = m.triangles[0], t5 = m.triangles[5], t7 = m.triangles[7];
  m.triangles.push_back(t0);                     // the same triangle again
  m.triangles.push_back({t5[0], t5[2], t5[1]});  // reversed
  m.triangles.push_back({t7[1], t7[2], t7[0]});  // rotated
  m.triangles.push_back({t0[0], t0[0], t0[1]});  // a repeated index
  m.vertices.push_back(m.vertices[t5[0]]);       // a second record of a vertex ...
  const auto copy = static_cast<std::int32_t>(m.vertices.size() - 1);
  m.triangles.push_back({t5[0], copy, t5[1]});  // ... collapses once welded
  // Three distinct collinear points, apart from the surface: a zero-area sliver with no neighbour.
  const auto base = static_cast<std::int32_t>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {Vec3(5, 5, 5), Vec3(6, 5, 5), Vec3(7, 5, 5)});
  m.triangles.push_back({base, base + 1, base + 2});
  const RepairReport r = repair_mesh(m, "box", false);
  EXPECT_EQ(r.duplicate_faces, 3);
  EXPECT_EQ(r.degenerate_faces, 3);
  EXPECT_EQ(r.merged_vertices, 1);
  EXPECT_EQ(r.kept_components, 1);
  EXPECT_EQ(oriented_triangles(m), oriented_triangles(box));
  EXPECT_EQ(validation_error(m), "");
}

// A T-junction closed by a zero-area sliver, as exporters leave when one side of an edge was split: the
// sliver cannot just be dropped (that opens a slit), so CGAL flips it away against its coplanar neighbour.
TEST(RepairMesh, ZeroAreaSliverAtATJunctionIsFlippedAway) {
  TriangleMesh m = grid_box(2, Vec3(1, 2, 3));
  const double volume = volume_of(m);
  // Split the triangle (a, b, c) at the midpoint p of its edge ab (exact: coordinates are binary fractions).
  const Triangle t = m.triangles[0];
  const auto p = static_cast<std::int32_t>(m.vertices.size());
  m.vertices.push_back(0.5 * (m.vertices[t[0]] + m.vertices[t[1]]));
  m.triangles[0] = {t[0], p, t[2]};
  m.triangles.push_back({p, t[1], t[2]});
  m.triangles.push_back({t[0], t[1], p});                       // the sliver, wound to close the surface
  EXPECT_THAT(validation_error(m), HasSubstr("open surface"));  // it drops the sliver
  const RepairReport r = repair_mesh(m, "box", false);
  EXPECT_EQ(r.degenerate_faces, 1);
  EXPECT_EQ(r.holes_filled, 0);
  EXPECT_EQ(validation_error(m), "");
  EXPECT_NEAR(volume_of(m), volume, kRel * volume);
}

// Two closed boxes sharing one vertex or one edge: CGAL cuts them apart (one copy of the shared vertices per
// box), leaving two closed components. Touching at a vertex is valid; along an edge validate_mesh() welds the
// copies back and finds four triangles on the edge, so repair_mesh() says so, and --largest-component helps.
TEST(RepairMesh, NonManifoldContactIsSplitIntoComponents) {
  const TriangleMesh a = make_shape("box:x=1,y=1,z=1");  // [-0.5, 0.5]³
  const TriangleMesh at_vertex = translated(make_shape("box:x=2,y=2,z=2"), Vec3(1.5, 1.5, 1.5));
  const TriangleMesh along_edge = translated(make_shape("box:x=2,y=2,z=1"), Vec3(1.5, 1.5, 0));

  TriangleMesh m = joined(a, at_vertex);
  const RepairReport r = repair_mesh(m, "pair", false);
  EXPECT_EQ(r.merged_vertices, 1);        // the shared record, welded first ...
  EXPECT_EQ(r.non_manifold_vertices, 1);  // ... then split again, one copy per box
  EXPECT_EQ(r.input_components, 2);
  EXPECT_EQ(r.kept_components, 2);
  EXPECT_EQ(validation_error(m), "");
  EXPECT_NEAR(volume_of(m), 9, kRel * 9);

  TriangleMesh edge = joined(a, along_edge);
  EXPECT_THAT(validation_error(edge), HasSubstr("non-manifold"));
  EXPECT_EQ(
      error_of(edge, "pair"),
      "pair: repair could not make a valid solid: non-manifold surface: 1 edges shared by more than two "
      "triangles (parts touching along an edge; --largest-component keeps one)");

  for (const TriangleMesh& b : {at_vertex, along_edge}) {
    TriangleMesh largest = joined(a, b);
    const RepairReport rl = repair_mesh(largest, "pair", true);
    EXPECT_EQ(rl.input_components, 2);
    EXPECT_EQ(rl.kept_components, 1);
    EXPECT_EQ(validation_error(largest), "");
    EXPECT_EQ(oriented_triangles(largest), oriented_triangles(b));  // the bigger box, as it was
  }
}

// Two holes touching at one corner (diagonal grid squares): CGAL's split of the pinched corner joins them
// into one border cycle through two copies of that point, whose patch would fold through it; merging the
// copies again fills each hole apart, and the corner is manifold once both are filled.
TEST(RepairMesh, HolesTouchingAtACornerAreFilledApart) {
  constexpr int n = 4;
  const TriangleMesh box = grid_box(n, Vec3(1, 2, 3));
  const int s1 = square(n, 2, 1, 1, 1), s2 = square(n, 2, 1, 2, 2);
  TriangleMesh m = without(box, {s1, s1 + 1, s2, s2 + 1});
  const RepairReport r = repair_mesh(m, "box", false);
  EXPECT_EQ(r.holes_filled, 2);
  EXPECT_EQ(r.non_manifold_vertices, 0);  // the corner was split, then merged again
  EXPECT_EQ(validation_error(m), "");
  EXPECT_NEAR(volume_of(m), 6, kRel * 6);
  EXPECT_EQ(sorted_points(m.vertices), sorted_points(box.vertices));
}

TEST(RepairMesh, DisjointBoxesStayOneBodyUnlessLargestIsAsked) {
  const TriangleMesh a = make_shape("box:x=1,y=1,z=1");
  const TriangleMesh b = translated(make_shape("box:x=2,y=2,z=2"), Vec3(5, 0, 0));
  TriangleMesh both = joined(a, b);
  const RepairReport r = repair_mesh(both, "pair", false);
  EXPECT_EQ(r.input_components, 2);
  EXPECT_EQ(r.kept_components, 2);
  EXPECT_EQ(oriented_triangles(both), oriented_triangles(joined(a, b)));
  TriangleMesh largest = joined(a, b);
  const RepairReport rl = repair_mesh(largest, "pair", true);
  EXPECT_EQ(rl.input_components, 2);
  EXPECT_EQ(rl.kept_components, 1);
  EXPECT_EQ(oriented_triangles(largest), oriented_triangles(b));
  EXPECT_THAT(rl.notes, ::testing::Contains(HasSubstr("kept the largest of 2 components")));
}

// A stray open sheet beside a solid closes into a flat two-sided patch: removed, the solid kept.
TEST(RepairMesh, FlatComponentIsRemoved) {
  const TriangleMesh a = make_shape("box:x=1,y=1,z=1");
  TriangleMesh sheet;
  sheet.vertices = {Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(4, 1, 0), Vec3(3, 1, 0)};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh m = joined(a, sheet);
  const RepairReport r = repair_mesh(m, "scan", false);
  EXPECT_EQ(r.input_components, 2);
  EXPECT_EQ(r.holes_filled, 1);
  EXPECT_EQ(r.flat_components, 1);
  EXPECT_EQ(r.kept_components, 1);
  EXPECT_EQ(oriented_triangles(m), oriented_triangles(a));
}

// Random damage (holes, flips, duplicates, stray triangles) and random triangle soups: repair_mesh either
// returns a mesh validate_mesh() accepts or throws repose::Error; it never crashes, hangs or returns junk.
// Measured: 194 of the 200 damaged shapes repaired (the other 6 have a stray triangle through the inside, or
// an island of triangles left touching the rest at its corners only: parts touching along an edge once
// closed), and 84 of the 200 soups (most bound no volume).
TEST(RepairMesh, RandomDamageIsRepairedOrRejected) {
  const TriangleMesh shapes[] = {make_shape("irregular:seed=3,n=3"),
                                 make_shape("ellipsoid:a=1,b=0.8,c=0.6,n=5"), make_shape("box:x=1,y=2,z=3")};
  int repaired = 0, rejected = 0, damaged_repaired = 0;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    std::mt19937_64 rng(seed);
    auto below = [&](std::uint64_t n) { return static_cast<std::int32_t>(rng() % n); };
    TriangleMesh m;
    if (seed % 2 == 0) {  // a shape with ~8 % of its triangles removed, 8 % reversed, 3 % doubled
      const TriangleMesh& shape = shapes[seed / 2 % 3];
      m.vertices = shape.vertices;
      for (Triangle t : shape.triangles) {
        const int u = below(100);
        if (u < 8) continue;
        if (u < 16) std::swap(t[1], t[2]);
        m.triangles.push_back(t);
        if (below(100) < 3) m.triangles.push_back(t);
      }
      const auto n = static_cast<std::uint64_t>(m.vertices.size());
      for (int k = below(3); k > 0; --k) m.triangles.push_back({below(n), below(n), below(n)});
    } else {  // a soup on a 4×4×4 lattice
      const int n = 4 + below(20);
      for (int v = 0; v < n; ++v) m.vertices.emplace_back(below(4), below(4), below(4));
      for (int t = 1 + below(40); t > 0; --t) m.triangles.push_back({below(n), below(n), below(n)});
    }
    try {
      repair_mesh(m, "random", seed % 5 == 0);
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), ::testing::StartsWith("random: "));
      ++rejected;
      continue;
    }
    EXPECT_EQ(validation_error(m), "") << "seed " << seed;
    ++repaired;
    damaged_repaired += seed % 2 == 0;
  }
  EXPECT_EQ(repaired + rejected, 400);
  EXPECT_GE(damaged_repaired, 190);  // damaged shapes are repaired, not rejected
}

TEST(RepairMesh, BadInputIsRejectedWithTheName) {
  EXPECT_EQ(error_of(TriangleMesh{}), "scan.stl: empty mesh (no triangles)");
  TriangleMesh nan = make_shape("box:x=1,y=1,z=1");
  nan.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(nan), "scan.stl: vertex 3 has a non-finite coordinate");
  TriangleMesh inf = nan;
  inf.vertices[3].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of(inf), "scan.stl: vertex 3 has a non-finite coordinate");
  TriangleMesh index = make_shape("box:x=1,y=1,z=1");
  index.triangles[2][1] = 8;
  EXPECT_THAT(error_of(index), HasSubstr("scan.stl: in triangle 2, vertex index 8 does not exist"));
}

TEST(RepairMesh, DegenerateInputIsRejectedNotCrashed) {
  TriangleMesh point;  // every corner at one point
  point.vertices = {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
  point.triangles = {{0, 1, 2}, {2, 1, 0}};
  EXPECT_EQ(error_of(point), "scan.stl: zero volume (all vertices coincide)");
  TriangleMesh line;  // distinct corners, all on one line
  for (int i = 0; i < 6; ++i) line.vertices.emplace_back(i, 2 * i, 3 * i);
  line.triangles = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 5}, {0, 2, 5}, {5, 4, 1}};
  EXPECT_THAT(error_of(line), HasSubstr("scan.stl: "));
  TriangleMesh sheet;  // an open flat square closes into a two-sided sheet: no solid
  sheet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(error_of(sheet),
            "scan.stl: nothing left to repair: the surface encloses no volume (1 flat component)");
  const TriangleMesh before = sheet;
  EXPECT_THROW(repair_mesh(sheet, "scan.stl", false), Error);
  EXPECT_EQ(sheet.vertices, before.vertices);  // unchanged on error
  EXPECT_EQ(sheet.triangles, before.triangles);
}

}  // namespace
}  // namespace repose
