#pragma once
// Internal: the linearised INS error model shared by the covariance and Monte-Carlo models.
//
// States (all in rad, so that every entry of F is of the order of w0, Omega or 1/T and the
// matrix exponential keeps its relative accuracy):
//   0 th_N = dp_N / R, 1 th_E = dp_E / R        position angles
//   2 w_N = dv_N / (R w0), 3 w_E = dv_E / (R w0) velocity errors, scaled
//   4 psi_N, 5 psi_E, 6 psi_D                    attitude errors (phi-angle form)
//   then, per gyro axis, noise states scaled by 1/w0: rate random walk, constant bias, ramp
//   (2 states), Gauss-Markov, the flicker bank's poles; and one state per axis with
//   quantization noise (the previous sample's angle noise, rad).
// Continuous dynamics, stationary and level at latitude L (Titterton & Weston ch. 12; Omega
// the Earth rate, zero when the Earth rate is off):
//   th_N' = w0 w_N                    th_E' = w0 w_E
//   w_N'  = w0 psi_E - 2 Omega sinL w_E
//   w_E'  = -w0 psi_N + 2 Omega sinL w_N
//   psi_N' = -Omega sinL psi_E + w0 w_E - Omega sinL th_N - eps_x
//   psi_E' = Omega sinL psi_N + Omega cosL psi_D - w0 w_N - eps_y
//   psi_D' = -Omega cosL psi_E - tanL w0 w_E - Omega cosL th_N - eps_z
// (at the pole the tan L transport term is dropped: a wander-azimuth frame has none).
#include <array>
#include <vector>

#include <Eigen/Dense>

#include "imunoise/nav/navigation.hpp"
#include "imunoise/sim/flicker.hpp"

namespace imunoise::nav::detail {

inline constexpr int kNavStates = 7;
using NavMatrix = Eigen::Matrix<double, kNavStates, kNavStates>;
using NavInput = Eigen::Matrix<double, kNavStates, 3>;

/// The flicker range used for B in every model: [dt, max(duration, 10 dt)].
struct FlickerRange {
  double tau_min_s;
  double tau_max_s;
};
FlickerRange flicker_range(const NavOptions& options);

/// Gauss-Markov processes and white noise that make up one axis's B (the simulator's bank)
/// plus its fitted Gauss-Markov term.
struct AxisProcesses {
  std::vector<sim::GaussMarkovPole> gauss_markov;  ///< sigma (rad/s), correlation time (s)
  double white_n_rad_sqrt_s = 0.0;                 ///< N combined with the bank's white part
};
AxisProcesses axis_processes(const GyroTerms& terms, const FlickerRange& range);

/// The nav part of F (7 x 7).
NavMatrix nav_dynamics(const NavOptions& options);

/// One step of the nav states driven by piecewise-constant gyro errors over dt:
/// x_{k+1} = phi x_k + gamma eps_k (eps in rad/s, axes x, y, z).
struct NavStep {
  NavMatrix phi;
  NavInput gamma;
};
NavStep nav_step(const NavOptions& options);

/// The discrete augmented model: x_{k+1} = phi x_k + w_k, cov(w_k) = qd, cov(x_0) = p0.
struct DiscreteModel {
  Eigen::MatrixXd phi, qd, p0;
};
DiscreteModel discrete_model(const NavOptions& options, const std::array<GyroTerms, 3>& terms);

}  // namespace imunoise::nav::detail
