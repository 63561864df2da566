// The paper, schuler and covariance models (Monte Carlo is in montecarlo.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <fmt/core.h>

#include "error_model.hpp"
#include "term_split.hpp"
#include "imunoise/nav/models.hpp"
#include "imunoise/nav/paper.hpp"
#include "imunoise/nav/schuler.hpp"

namespace imunoise::nav {
namespace {

double w0_of(const NavOptions& o) { return schuler::frequency_rad_s(o.earth.gravity_m_s2, o.earth.radius_m); }

bool pole(const NavOptions& o) { return std::abs(std::cos(o.latitude_rad)) < 1e-12; }

// Fills lat, lon, north, east, radial from the variances of th_N and th_E (rad^2).
void fill_from_variances(const NavOptions& o, double var_n, double var_e, ModelSeries& s) {
  const double r = o.earth.radius_m;
  const double sn = std::sqrt(std::max(var_n, 0.0)), se = std::sqrt(std::max(var_e, 0.0));
  s.lat_rad.push_back(sn);
  if (!pole(o)) s.lon_rad.push_back(se / std::abs(std::cos(o.latitude_rad)));
  s.north_m.push_back(r * sn);
  s.east_m.push_back(r * se);
  s.radial_m.push_back(r * std::sqrt(std::max(var_n + var_e, 0.0)));
}

// Variance of the position angle of one Schuler channel driven by one gyro's terms.
double channel_variance(const GyroTerms& t, const detail::FlickerRange& range, double h, double time,
                        double w0) {
  const detail::AxisProcesses p = detail::axis_processes(detail::sensor_terms(t), range);
  auto sq = [](double v) { return v * v; };
  double var = sq(schuler::constant_drift_rad(t.bias_rad_s, time, w0)) +
               sq(schuler::rate_ramp_rad(t.r_rad_s2, time, w0)) +
               sq(schuler::white_rad(p.white_n, time, w0)) +
               sq(schuler::random_walk_rad(t.k_rad_s_sqrt_s, time, w0)) +
               sq(schuler::quantization_rad(t.q_rad, h, time, w0));
  for (const auto& gm : p.gauss_markov) var += sq(schuler::gauss_markov_rad(gm.sigma_unit, gm.time_s, time, w0));
  return var;
}

// The same for one accelerometer's terms.
double accel_channel_variance(const AccelTerms& t, const detail::FlickerRange& range, double h, double time,
                              double w0, double radius_m) {
  const detail::AxisProcesses p = detail::axis_processes(detail::sensor_terms(t), range);
  auto sq = [](double v) { return v * v; };
  double var = sq(schuler::accel_bias_rad(t.bias_m_s2, time, w0, radius_m)) +
               sq(schuler::accel_ramp_rad(t.r_m_s3, time, w0, radius_m)) +
               sq(schuler::accel_white_rad(p.white_n, time, w0, radius_m)) +
               sq(schuler::accel_random_walk_rad(t.k_m_s2_sqrt_s, time, w0, radius_m)) +
               sq(schuler::accel_quantization_rad(t.q_m_s, h, time, w0, radius_m));
  for (const auto& gm : p.gauss_markov) {
    var += sq(schuler::accel_gauss_markov_rad(gm.sigma_unit, gm.time_s, time, w0, radius_m));
  }
  return var;
}

}  // namespace

ModelSeries paper_series(const NavOptions& o, const ImuTerms& terms, const std::vector<double>& t_s) {
  ModelSeries s;
  s.model = Model::paper;
  const double w0 = w0_of(o);
  const double eps = o.paper_sigma_eps_rad_s ? *o.paper_sigma_eps_rad_s
                                              : terms.gyro[1].n_rad_sqrt_s * 1.0;  // N's value read as a rate (x 1/sqrt(s))
  s.paper_sigma_eps_rad_s = eps;
  s.assumptions = fmt::format(
      "the paper's eq. 6 as published: lat = (e/w0)|cos w0t - 1|, path = (e R/w0)|sin w0t - w0t|, "
      "lon = (e/w0)|sin w0t - w0t| with w0 = sqrt(g/R) = {:.6g} rad/s and sigma_eps e = {:.6g} deg/s ({}); "
      "the latitude line is the velocity-error shape, not the drift's latitude response; no latitude "
      "factor on longitude; east = R lon, radial = sqrt(2) path (the paper gives none); reproduces the "
      "published 3.9 deg longitude at 1 h from gyro 1's N = 8.9e-4, not 0.37 deg nor 22.6 km "
      "(docs/navigation.md)",
      w0, eps * 180.0 / std::numbers::pi,
      o.paper_sigma_eps_rad_s ? "given" : "the paper's reading: the east gyro's N value, deg/sqrt(s) read as deg/s");
  for (double t : t_s) {
    s.t_s.push_back(t);
    const double lat = paper::latitude_rad(eps, t, w0);
    const double lon = paper::longitude_rad(eps, t, w0);
    const double path = paper::path_m(eps, t, w0, o.earth.radius_m);
    s.lat_rad.push_back(lat);
    if (!pole(o)) s.lon_rad.push_back(lon);
    s.north_m.push_back(path);
    s.east_m.push_back(o.earth.radius_m * lon);
    s.radial_m.push_back(std::numbers::sqrt2 * path);
  }
  return s;
}

ModelSeries schuler_series(const NavOptions& o, const ImuTerms& terms, const std::vector<double>& t_s) {
  ModelSeries s;
  s.model = Model::schuler;
  const double w0 = w0_of(o);
  const detail::FlickerRange range = detail::flicker_range(o);
  s.assumptions = fmt::format(
      "single-channel Schuler loop per level axis (w0 = sqrt(g/R) = {:.6g} rad/s, R = {:.6g} m, g = {:.6g} "
      "m/s^2), closed forms per noise term added in variance: constant drift, ramp, white (N), rate random "
      "walk (K), Gauss-Markov, quantization (white angle noise at dt = {:.6g} s); B as the simulator's "
      "Gauss-Markov bank over [{:.6g}, {:.6g}] s; east gyro and north accelerometer -> north error (latitude, "
      "path), north gyro and east accelerometer -> east error (longitude = east / (R cos L)); no Earth rate, no "
      "coupling, down gyro and down accelerometer ignored",
      w0, o.earth.radius_m, o.earth.gravity_m_s2, o.dt_s, range.tau_min_s, range.tau_max_s);
  for (double t : t_s) {
    s.t_s.push_back(t);
    const double r = o.earth.radius_m;
    const double var_n = channel_variance(terms.gyro[1], range, o.dt_s, t, w0) +
                         accel_channel_variance(terms.accel[0], range, o.dt_s, t, w0, r);
    const double var_e = channel_variance(terms.gyro[0], range, o.dt_s, t, w0) +
                         accel_channel_variance(terms.accel[1], range, o.dt_s, t, w0, r);
    fill_from_variances(o, var_n, var_e, s);
  }
  return s;
}

namespace {

// P at each reported time (only its nav part kept, and the whole P at the end for the checks),
// for the discrete model of these terms.
struct Propagated {
  std::vector<double> var_n, var_e;  // of th_N and th_E (rad^2)
  Eigen::MatrixXd last;
};

Propagated propagate(const NavOptions& o, const detail::DiscreteModel& d, const std::vector<double>& t_s) {
  // The discrete model is exact at dt; between reported times its m-fold composition
  // (Phi^m, sum_j Phi^j Qd Phi^j') is formed by doubling, which is the same propagation in
  // log2(m) products instead of m. Navigation starts after the alignment, if any.
  Propagated out;
  Eigen::MatrixXd p = detail::aligned_p0(o, d);
  long k = 0;
  long cached_m = -1;
  Eigen::MatrixXd phi_m, q_m;
  for (double t : t_s) {
    const long target = std::lround(t / o.dt_s);
    if (target > k) {
      const long m = target - k;
      if (o.covariance_per_step) {
        for (long j = 0; j < m; ++j) {
          p = d.phi * p * d.phi.transpose() + d.qd;
          p = 0.5 * (p + p.transpose()).eval();
        }
      } else {
        if (m != cached_m) {
          detail::compose(d.phi, d.qd, m, phi_m, q_m);
          cached_m = m;
        }
        p = phi_m * p * phi_m.transpose() + q_m;
        p = 0.5 * (p + p.transpose()).eval();
      }
      k = target;
    }
    out.var_n.push_back(p(0, 0));
    out.var_e.push_back(p(1, 1));
  }
  out.last = std::move(p);
  return out;
}

}  // namespace

ModelSeries covariance_series(const NavOptions& o, const ImuTerms& terms, const std::vector<double>& t_s) {
  ModelSeries s;
  s.model = Model::covariance;
  const detail::DiscreteModel d = detail::discrete_model(o, terms.gyro, terms.accel);
  const detail::FlickerRange range = detail::flicker_range(o);
  s.assumptions = fmt::format(
      "linearised NED error model of a stationary level INS at latitude {:.6g} deg: both horizontal "
      "channels and the azimuth (phi-angle form, Titterton & Weston ch. 12), {}; vertical channel not "
      "modelled (the down accelerometer left out); gyro and accelerometer noise as states (rate random "
      "walk, bias, ramp, Gauss-Markov, B as the simulator's Gauss-Markov bank over [{:.6g}, {:.6g}] s, "
      "quantization at dt); exact discrete transition exp(F dt) and Van Loan noise at dt = {:.6g} s; "
      "P <- Phi P Phi' + Qd (a sum of positive semi-definite terms), composed by doubling to the reporting "
      "step, symmetrized after every product; {} states; the error budget from one propagation per term",
      o.latitude_rad * 180.0 / std::numbers::pi,
      o.earth_rate ? "with Earth rate and Coriolis coupling" : "Earth rate and Coriolis off", range.tau_min_s,
      range.tau_max_s, o.dt_s, d.phi.rows());
  const Propagated whole = propagate(o, d, t_s);
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    s.t_s.push_back(t_s[i]);
    fill_from_variances(o, whole.var_n[i], whole.var_e[i], s);
  }
  // The budget: each term alone; the shares of the horizontal variance add up to 1.
  std::vector<std::pair<std::string, std::vector<double>>> parts;
  std::vector<double> total(t_s.size(), 0.0);
  for (const detail::TermPart& part : detail::split_terms(terms.gyro, terms.accel)) {
    const Propagated p = propagate(o, detail::discrete_model(o, part.gyro, part.accel), t_s);
    std::vector<double> var(t_s.size());
    for (std::size_t i = 0; i < t_s.size(); ++i) {
      var[i] = p.var_n[i] + p.var_e[i];
      total[i] += var[i];
    }
    parts.emplace_back(part.name, std::move(var));
  }
  for (auto& [name, var] : parts) {
    for (std::size_t i = 0; i < t_s.size(); ++i) var[i] = total[i] > 0.0 ? var[i] / total[i] : 0.0;
    s.budget.emplace_back(name, std::move(var));
  }
  const Eigen::MatrixXd& p = whole.last;
  CovarianceCheck check;
  check.states = static_cast<std::size_t>(p.rows());
  const double scale = p.cwiseAbs().maxCoeff();
  check.max_asymmetry = scale > 0 ? (p - p.transpose()).cwiseAbs().maxCoeff() / scale : 0.0;
  // Eigenvalues of the correlation form D^-1/2 P D^-1/2: the states differ by orders of magnitude.
  Eigen::VectorXd dinv = p.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd c = dinv.asDiagonal() * p * dinv.asDiagonal();
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(c, Eigen::EigenvaluesOnly).eigenvalues();
  check.min_eigenvalue_ratio = ev.maxCoeff() > 0 ? ev.minCoeff() / ev.maxCoeff() : 0.0;
  s.covariance_check = check;
  return s;
}

}  // namespace imunoise::nav
