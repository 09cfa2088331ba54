// basin_gradient (basin_gradient.hpp): every face's row of the tape's Jacobian.
#include "repose/design/basin_gradient.hpp"

#include "basin_tape.hpp"

namespace repose {

BasinGradient basin_gradient(const Particle& particle, const RestLandscape& landscape, MassModel mass) {
  detail::BasinTape tape(particle, landscape, mass);
  const auto faces = static_cast<Eigen::Index>(tape.probability().size());
  const Eigen::MatrixXd rows = tape.gradients(Eigen::MatrixXd::Identity(faces, faces));
  const Eigen::Index n = tape.variables() - 3;
  BasinGradient out;
  out.probability = tape.probability();
  out.d_vertices = rows.leftCols(n);
  // The offset is the centre of mass's position plus a constant in either model; its derivative is the
  // centre of mass's with the vertices fixed.
  for (Eigen::Index f = 0; f < faces; ++f) out.d_com.emplace_back(rows.row(f).tail<3>().transpose());
  return out;
}

BasinGradient basin_com_gradient(const Particle& particle, const RestLandscape& landscape) {
  detail::BasinTape tape(particle, landscape, MassModel::fixed);
  Eigen::MatrixXd directions = Eigen::MatrixXd::Zero(tape.variables(), 3);
  directions.bottomRows<3>().setIdentity();
  const Eigen::MatrixXd columns = tape.directional(directions);
  BasinGradient out;
  out.probability = tape.probability();
  for (Eigen::Index f = 0; f < columns.rows(); ++f) out.d_com.emplace_back(columns.row(f).transpose());
  return out;
}

}  // namespace repose
