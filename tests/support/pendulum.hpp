// Closed forms and quadratures of a rigid body tipping about a fixed edge on the wall: an inverted pendulum
// I·φ'' + C·φ' = m·g·d·sin φ in the tilt φ of the centre of mass from the vertical through the edge (d: the
// centre of mass's distance from the edge, I: the moment of inertia about the edge). Written in the test,
// from the equation alone, as references for the engine.
#pragma once

#include <cmath>

namespace repose::pendulum {

/// The rate at which a damped inverted pendulum leaves its balance: the positive root of
/// I·λ² + C·λ − m·g·d = 0.
inline double escape_rate(double inertia, double damping, double m_g_d) {
  const double c = damping / inertia;
  return (-c + std::sqrt(c * c + 4 * m_g_d / inertia)) / 2;
}

/// Time for the undamped pendulum released from rest at φ0 > 0 to reach φ1: the quadrature of
/// dφ / sqrt(2·m·g·d·(cos φ0 − cos φ)/I). The substitution φ = φ0·cosh u removes both the 1/sqrt singularity
/// at φ0 and the logarithmic growth of the time as φ0 → 0 (the integrand tends to 1/λ0, λ0² = m·g·d/I);
/// cos φ0 − cos φ is taken as 2·sin((φ+φ0)/2)·sin((φ−φ0)/2) to keep its digits. Composite Simpson, 20 000
/// panels (the integrand is smooth in u; halving the panels changes the result by < 1e-12 relative).
inline double undamped_tip_time(double inertia, double m_g_d, double phi0, double phi1) {
  const double umax = std::acosh(phi1 / phi0);
  const double lambda0 = std::sqrt(m_g_d / inertia);
  auto f = [&](double u) {
    if (u == 0) return 1 / lambda0;
    const double phi = phi0 * std::cosh(u);
    const double drop = 2 * std::sin((phi + phi0) / 2) * std::sin((phi - phi0) / 2);
    return phi0 * std::sinh(u) / std::sqrt(2 * m_g_d * drop / inertia);
  };
  const int n = 20000;
  const double h = umax / n;
  double sum = f(0) + f(umax);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(i * h);
  return sum * h / 3;
}

/// Moment of inertia per unit mass of a right prism whose cross-section is the regular n-gon of circumradius
/// r, about its axis: r²·(1 + 2·cos²(π/n))/6 (r²/2 as n → ∞; r²/3 for the square).
inline double ngon_prism_axial_inertia_per_mass(double r, int n) {
  const double c = std::cos(3.14159265358979323846 / n);
  return r * r * (1 + 2 * c * c) / 6;
}

}  // namespace repose::pendulum
