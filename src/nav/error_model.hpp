#pragma once
// Internal: the linearised INS error model shared by the covariance and Monte-Carlo models.
//
// States (all in rad, so that every entry of F is of the order of w0, Omega or 1/T and the
// matrix exponential keeps its relative accuracy):
//   0 th_N = dp_N / R, 1 th_E = dp_E / R        position angles
//   2 w_N = dv_N / (R w0), 3 w_E = dv_E / (R w0) velocity errors, scaled
//   4 psi_N, 5 psi_E, 6 psi_D                    attitude errors (phi-angle form)
//   then, per sensor (gyros x y z, accelerometers x y), noise states: rate random walk, constant
//   bias, ramp (2 states), Gauss-Markov, the flicker bank's poles; and one state per sensor with
//   quantization noise (the previous sample's angle or velocity noise). A sensor's error u
//   enters one nav state with a gain (input_of): a gyro's eps its tilt psi with -1, an
//   accelerometer's f its scaled velocity w with 1 / (R w0). Its noise states hold u |gain| / w0
//   and feed the nav state with sign(gain) w0, so every entry of F stays of the order of w0.
// Continuous dynamics, stationary and level at latitude L (Titterton & Weston ch. 12; Omega
// the Earth rate, zero when the Earth rate is off):
//   th_N' = w0 w_N                    th_E' = w0 w_E
//   w_N'  = w0 psi_E - 2 Omega sinL w_E + f_x / (R w0)
//   w_E'  = -w0 psi_N + 2 Omega sinL w_N + f_y / (R w0)
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

/// One sensor's terms in its own SI unit u (rad/s for a gyro, m/s^2 for an accelerometer).
struct SensorTerms {
  double q = 0.0;         ///< quantization (u s)
  double n = 0.0;         ///< white noise (u sqrt(s))
  double b = 0.0;         ///< bias instability (u)
  double k = 0.0;         ///< random walk (u / sqrt(s))
  double r = 0.0;         ///< ramp (u / s)
  std::vector<GaussMarkovNoise> gauss_markov;  ///< every Gauss-Markov term: sigma (u), T_c (s)
  double bias = 0.0;      ///< constant (u)
};
SensorTerms sensor_terms(const GyroTerms& terms);
SensorTerms sensor_terms(const AccelTerms& terms);

/// Gauss-Markov processes and white noise that make up one sensor's B (the simulator's bank)
/// plus its fitted Gauss-Markov terms (every one).
struct AxisProcesses {
  std::vector<sim::GaussMarkovPole> gauss_markov;  ///< sigma (u), correlation time (s)
  double white_n = 0.0;                            ///< N combined with the bank's white part (u sqrt(s))
};
AxisProcesses axis_processes(const SensorTerms& terms, const FlickerRange& range);

/// Where a sensor's error enters the nav states: x_target' += gain u.
struct SensorInput {
  int target = 0;
  double gain = 0.0;
};
/// Gyro axis a (0 x, 1 y, 2 z) and accelerometer axis a (0 x, 1 y; the down accelerometer has
/// no horizontal input).
SensorInput gyro_input(int axis);
SensorInput accel_input(const NavOptions& options, int axis);

/// The nav part of F (7 x 7).
NavMatrix nav_dynamics(const NavOptions& options);

/// One step of the nav states driven by piecewise-constant sensor errors over dt:
/// x_{k+1} = phi x_k + gamma eps_k + accel_gamma f_k (eps in rad/s, axes x y z; f in m/s^2,
/// axes x y).
struct NavStep {
  NavMatrix phi;
  NavInput gamma;
  Eigen::Matrix<double, kNavStates, 2> accel_gamma;
};
NavStep nav_step(const NavOptions& options);

/// The discrete augmented model: x_{k+1} = phi x_k + w_k, cov(w_k) = qd, cov(x_0) = p0.
struct DiscreteModel {
  Eigen::MatrixXd phi, qd, p0;
};
DiscreteModel discrete_model(const NavOptions& options, const std::array<GyroTerms, 3>& gyro,
                             const std::array<AccelTerms, 3>& accel);

/// The covariance after a stationary alignment of options.align_s seconds: from d.p0,
/// propagated step by step with zero-velocity updates (w_N w_E measured with 1 mm/s of noise;
/// Joseph form), then position and velocity set known (the start of navigation). d.p0 itself
/// when align_s is 0.
Eigen::MatrixXd aligned_p0(const NavOptions& options, const DiscreteModel& d);

/// (phi_m, q_m) = m steps of x <- phi x + w, cov w = qd, by binary powers (log2 m products);
/// each product is a sum of positive semi-definite terms, symmetrized.
void compose(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& qd, long m, Eigen::MatrixXd& phi_m,
             Eigen::MatrixXd& q_m);

}  // namespace imunoise::nav::detail
