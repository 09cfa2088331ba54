// BasinTape (basin_tape.hpp): the landscape's areas recorded with ADOL-C, its buffers sized so that the tape
// stays in memory (ADOL-C writes a tape that outgrows them to files in the working directory).
#include "basin_tape.hpp"

#include <adolc/adolc.h>

#include <numbers>
#include <string>

#include "../poses/arc_partitions_impl.hpp"
#include "adolc_eigen.hpp"
#include "map_replay.hpp"
#include "repose/error.hpp"
#include "solid_centroid.hpp"

namespace repose::detail {

template class ArcPartitionsT<adouble>;

namespace {

using AVec = Eigen::Matrix<adouble, 3, 1>;

constexpr short kTag = 50;
std::mutex tape_mutex;
// Buffer sizes per hull vertex (elements). Measured: ~7,500 operations per vertex on 1,000-vertex hulls
// (an ellipsoid, an irregular grain); the buffers only take memory as they fill.
constexpr std::size_t kPerVertex = 65536;

}  // namespace

BasinTape::BasinTape(const Particle& particle, const RestLandscape& landscape, MassModel mass)
    : lock_(tape_mutex) {
  const GaussMap* g = landscape.gauss_map.get();
  const ConvexHull& hull = particle.hull;
  const std::size_t n = hull.vertices.size();
  if (g == nullptr || g->regions.size() != n || g->routes.size() != hull.faces.size())
    throw Error("basin gradient: the landscape was not computed for " + particle.name);
  variables_ = static_cast<int>(3 * n + 3);
  const auto size = static_cast<unsigned>(std::min<std::size_t>(kPerVertex * n, 1u << 30));
  trace_on(kTag, 1, size, size, size, size);
  {
    std::vector<AVec> x(n);
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        x[i][k] <<= hull.vertices[i][k];
        point_.push_back(hull.vertices[i][k]);
      }
    AVec c;
    std::vector<AVec> body(n);
    // The offset's value: the centroid's, negated (follows_shape), or zero (the centre of mass is the
    // origin).
    const Vec3 offset =
        mass == MassModel::follows_shape ? Vec3(-solid_centroid<double>(hull.vertices, hull)) : Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      c[k] <<= offset[k];
      point_.push_back(offset[k]);
    }
    if (mass == MassModel::follows_shape) c += solid_centroid<adouble>(x, hull);
    for (std::size_t i = 0; i < n; ++i) body[i] = x[i] - c;
    const GaussMapT<adouble> m = replay_map<adouble>(*g, hull, body);
    ArcPartitionsT<adouble> arcs(m);
    std::vector<adouble> area(hull.faces.size());
    for (adouble& a : area) a = 0.0;
    for (int v = 0; v < static_cast<int>(n); ++v) arcs.add_region(v, area);
    probability_.resize(area.size());
    for (std::size_t f = 0; f < area.size(); ++f) area[f] / (4 * std::numbers::pi) >>= probability_[f];
  }
  trace_off();
  std::size_t stats[STAT_SIZE];
  tapestats(kTag, stats);
  if (stats[OP_FILE_ACCESS] != 0 || stats[LOC_FILE_ACCESS] != 0 || stats[VAL_FILE_ACCESS] != 0) {
    removeTape(kTag, ADOLC_REMOVE_COMPLETELY);
    throw Error("basin gradient: the tape of " + particle.name + " outgrew its memory buffers (" +
                std::to_string(stats[NUM_OPERATIONS]) + " operations)");
  }
}

BasinTape::~BasinTape() { removeTape(kTag, ADOLC_REMOVE_FROM_CORE); }

Eigen::MatrixXd BasinTape::gradients(const Eigen::MatrixXd& weights) {
  if (swept_) throw Error("basin gradient: a tape answers one sweep");
  swept_ = true;
  const int m = static_cast<int>(probability_.size());
  const int q = static_cast<int>(weights.rows());
  if (weights.cols() != m)
    throw Error("basin gradient: weights for " + std::to_string(weights.cols()) + " faces, the tape has " +
                std::to_string(m));
  Eigen::MatrixXd out(q, variables_);
  if (q == 0) return out;
  // ADOL-C takes arrays of row pointers; Eigen's row-major copies give them.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> u = weights;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> z(q, variables_);
  std::vector<double*> urows(static_cast<std::size_t>(q)), zrows(static_cast<std::size_t>(q));
  for (int r = 0; r < q; ++r) {
    urows[static_cast<std::size_t>(r)] = u.row(r).data();
    zrows[static_cast<std::size_t>(r)] = z.row(r).data();
  }
  if (fov_reverse(kTag, m, variables_, q, urows.data(), zrows.data()) < 0)
    throw Error("basin gradient: ADOL-C's reverse sweep failed");
  out = z;
  return out;
}

Eigen::MatrixXd BasinTape::directional(const Eigen::MatrixXd& directions) const {
  const int m = static_cast<int>(probability_.size());
  const int p = static_cast<int>(directions.cols());
  if (directions.rows() != variables_)
    throw Error("basin gradient: directions over " + std::to_string(directions.rows()) +
                " variables, the tape has " + std::to_string(variables_));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x_dot = directions;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> y_dot(m, p);
  std::vector<double*> xrows(static_cast<std::size_t>(variables_)), yrows(static_cast<std::size_t>(m));
  for (int r = 0; r < variables_; ++r) xrows[static_cast<std::size_t>(r)] = x_dot.row(r).data();
  for (int r = 0; r < m; ++r) yrows[static_cast<std::size_t>(r)] = y_dot.row(r).data();
  std::vector<double> x = point_, y(static_cast<std::size_t>(m));
  if (fov_forward(kTag, m, variables_, p, x.data(), xrows.data(), y.data(), yrows.data()) < 0)
    throw Error("basin gradient: ADOL-C's forward sweep failed");
  return y_dot;
}

}  // namespace repose::detail
