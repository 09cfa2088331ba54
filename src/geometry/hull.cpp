// Convex hull through qhull's reentrant C API (the C++ wrapper in Debian's qhull does not compile as C++20).
#include "repose/geometry/hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>

#include "repose/error.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace repose {
namespace {

// qhull writes its diagnostics to a FILE*. An in-memory stream keeps them off the user's terminal and lets
// the first line become the text of the exception.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&buffer_, &size_)) {}
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;
  ~MessageStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  FILE* file() const { return file_; }
  std::string first_line() {
    if (file_ == nullptr) return "qhull failed";
    std::fflush(file_);
    std::string text(buffer_ != nullptr ? buffer_ : "", size_);
    const auto begin = text.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "qhull failed";
    const auto end = text.find('\n', begin);
    return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

// Owns one qhull instance; frees all of its memory on every exit path (qh_new_qhull catches qhull's own
// longjmp-based errors and returns non-zero, and nothing after it calls into code that can longjmp).
class Qhull {
 public:
  explicit Qhull(FILE* err) { qh_zero(&qh_, err); }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;
  ~Qhull() {
    qh_freeqhull(&qh_, !qh_ALL);
    int curlong = 0;
    int totlong = 0;
    qh_memfreeshort(&qh_, &curlong, &totlong);
  }
  qhT* get() { return &qh_; }

 private:
  qhT qh_{};
};

}  // namespace

int ConvexHull::support_vertex(const Vec3& direction) const {
  int best = -1;
  double best_value = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const double value = direction.dot(vertices[i]);
    if (best < 0 || value > best_value) {
      best = static_cast<int>(i);
      best_value = value;
    }
  }
  return best;
}

int ConvexHull::support_vertex_from(const Vec3& direction, int start) const {
  int at = start;
  double value = direction.dot(vertices[static_cast<std::size_t>(at)]);
  // Strictly uphill: every move raises the value, so the walk ends (at most once per vertex).
  for (bool moved = true; moved;) {
    moved = false;
    for (int n : neighbors(at)) {
      const double v = direction.dot(vertices[static_cast<std::size_t>(n)]);
      if (v > value) {
        at = n;
        value = v;
        moved = true;
        break;
      }
    }
  }
  return at;
}

void ConvexHull::vertices_at_least(const Vec3& direction, double level, int top, std::vector<int>& out,
                                   std::vector<char>& visited) const {
  const std::size_t first = out.size();
  if (direction.dot(vertices[static_cast<std::size_t>(top)]) < level) return;
  out.push_back(top);
  visited[static_cast<std::size_t>(top)] = 1;
  for (std::size_t i = first; i < out.size(); ++i)
    for (int n : neighbors(out[i])) {
      if (visited[static_cast<std::size_t>(n)]) continue;
      if (direction.dot(vertices[static_cast<std::size_t>(n)]) < level) continue;
      visited[static_cast<std::size_t>(n)] = 1;
      out.push_back(n);
    }
  for (std::size_t i = first; i < out.size(); ++i) visited[static_cast<std::size_t>(out[i])] = 0;
}

ConvexHull compute_convex_hull(const std::vector<Vec3>& points) {
  if (points.size() < 4) {
    throw Error("convex hull: need at least 4 points, got " + std::to_string(points.size()));
  }
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3)) {
    throw Error("convex hull: too many points (" + std::to_string(points.size()) + ")");
  }
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw Error("convex hull: non-finite point coordinate");
  }

  // Hand qhull coordinates relative to the bounding-box centre (better conditioned far from the origin).
  const Aabb box = bounding_box(points);
  if (box.size().maxCoeff() == 0) throw Error("convex hull: degenerate input (all points coincide)");
  const Vec3 ref = box.center();
  std::vector<coordT> coords(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) coords[3 * i + static_cast<std::size_t>(k)] = points[i][k] - ref[k];
  }

  MessageStream messages;
  FILE* err = messages.file() != nullptr ? messages.file() : stderr;
  Qhull qhull(err);
  qhT* qh = qhull.get();
  // Default qhull options merge coplanar facets ('C-0' in 3-d), so each facet is a planar polygon; 'Qs'
  // searches all points for the initial simplex, which is more robust for thin inputs. Merging costs
  // super-linear time in the number of vertices of one planar face: fine for particle meshes (thousands of
  // facets, 60k points on a finely meshed box: ~50 ms), slow for a prism with thousands of rim vertices on a
  // cap (cylinder n=4000: ~5 s).
  char options[] = "qhull Qs";
  const int exitcode =
      qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr, err);
  if (exitcode != 0) {
    std::string what = messages.first_line();
    if (exitcode == qh_ERRsingular || what.find("QH6154") != std::string::npos ||
        what.find("flat") != std::string::npos) {
      what = "degenerate input (all points coplanar or collinear): " + what;
    }
    throw Error("convex hull: " + what);
  }

  // Hull vertices in input order, so the result does not depend on qhull's internal ordering.
  std::vector<int> hull_index(points.size(), -1);
  {
    facetT* facet = nullptr;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FORALLfacets {
      FOREACHvertex_(facet->vertices) {
        const int id = qh_pointid(qh, vertex->point);
        if (id < 0 || static_cast<std::size_t>(id) >= points.size()) {
          throw Error("convex hull: qhull returned an unknown vertex");
        }
        hull_index[static_cast<std::size_t>(id)] = 0;
      }
    }
  }
  ConvexHull hull;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (hull_index[i] < 0) continue;
    hull_index[i] = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(points[i]);
    hull.source_index.push_back(static_cast<int>(i));
  }

  facetT* facet = nullptr;
  FORALLfacets {
    const Vec3 qnormal(facet->normal[0], facet->normal[1], facet->normal[2]);
    std::vector<int> loop;
    {
      vertexT* vertex = nullptr;
      vertexT** vertexp = nullptr;
      FOREACHvertex_(facet->vertices) {
        loop.push_back(hull_index[static_cast<std::size_t>(qh_pointid(qh, vertex->point))]);
      }
    }
    if (loop.size() < 3) throw Error("convex hull: qhull returned a facet with fewer than 3 vertices");

    // Order the vertices counter-clockwise about the outward normal: by angle around their mean in the
    // facet plane, with (u, v, normal) right-handed.
    Vec3 mean = Vec3::Zero();
    for (int i : loop) mean += hull.vertices[static_cast<std::size_t>(i)] - ref;
    mean /= static_cast<double>(loop.size());
    const Vec3 u = qnormal.unitOrthogonal();
    const Vec3 v = qnormal.cross(u);
    std::vector<std::pair<double, int>> by_angle;
    by_angle.reserve(loop.size());
    for (int i : loop) {
      const Vec3 d = hull.vertices[static_cast<std::size_t>(i)] - ref - mean;
      by_angle.emplace_back(std::atan2(v.dot(d), u.dot(d)), i);
    }
    std::sort(by_angle.begin(), by_angle.end());
    for (std::size_t k = 0; k < loop.size(); ++k) loop[k] = by_angle[k].second;

    // Area vector (Newell) and area centroid by a fan from the mean, in the shifted frame.
    Vec3 area_vector = Vec3::Zero();
    Vec3 weighted = Vec3::Zero();
    double weight = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3 a = hull.vertices[static_cast<std::size_t>(loop[k])] - ref;
      const Vec3 b = hull.vertices[static_cast<std::size_t>(loop[(k + 1) % loop.size()])] - ref;
      area_vector += a.cross(b);
      const double w = (a - mean).cross(b - mean).dot(qnormal);
      weighted += w * (mean + a + b) / 3.0;
      weight += w;
    }
    HullFace face;
    const double norm = area_vector.norm();
    face.normal = norm > 0 ? Vec3(area_vector / norm) : qnormal;
    face.area = 0.5 * norm;
    const Vec3 centroid = weight > 0 ? Vec3(weighted / weight) : mean;
    face.centroid = centroid + ref;
    face.offset = face.normal.dot(centroid) + face.normal.dot(ref);
    face.loop = std::move(loop);
    hull.faces.push_back(std::move(face));
  }
  // Each edge is a → b in one face's counter-clockwise loop and b → a in its neighbour's: taking the
  // directed edges gives every vertex each neighbour once. Two passes (count, then fill in face order) keep
  // each vertex's neighbours in the order of the faces, as the walks' results depend on it.
  const std::size_t nv = hull.vertices.size();
  hull.neighbor_offsets.assign(nv + 1, 0);
  for (const HullFace& face : hull.faces)
    for (int v : face.loop) ++hull.neighbor_offsets[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) hull.neighbor_offsets[v + 1] += hull.neighbor_offsets[v];
  hull.neighbor_list.resize(static_cast<std::size_t>(hull.neighbor_offsets[nv]));
  std::vector<int> fill(hull.neighbor_offsets.begin(), hull.neighbor_offsets.end() - 1);
  for (const HullFace& face : hull.faces)
    for (std::size_t k = 0; k < face.loop.size(); ++k)
      hull.neighbor_list[static_cast<std::size_t>(fill[static_cast<std::size_t>(face.loop[k])]++)] =
          face.loop[(k + 1) % face.loop.size()];
  // Every face's plane supports the hull. A sliver facet among points of very different magnitudes (found
  // by fuzz_mesh_ply: coordinates from 1 to 5e34, three vertices 1e-6·D apart) can get a plane with another
  // vertex 4e-6·D outside it; its offset is then raised to that vertex (walked to uphill on the edge graph).
  // Only a defect far above round-off (1e-12·D) is mended, so a well-conditioned hull is unchanged to the
  // bit.
  Vec3 lo = hull.vertices.front(), hi = lo;
  for (const Vec3& p : hull.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double slack = 1e-12 * (hi - lo).norm();
  for (HullFace& face : hull.faces) {
    const int top = hull.support_vertex_from(face.normal, face.loop.front());
    const double reach = face.normal.dot(hull.vertices[static_cast<std::size_t>(top)]);
    if (reach > face.offset + slack) face.offset = reach;
  }
  return hull;
}

}  // namespace repose
